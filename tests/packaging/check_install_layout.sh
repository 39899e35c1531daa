#!/usr/bin/env bash
# `cmake --install` into a throwaway DESTDIR; the installed files must be exactly
# expected_install_files.txt (@PREFIX@ = the configured install prefix), the installed binary
# must run, the installed unit must name the installed binary, and the maintainer scripts must
# parse.
# usage: check_install_layout.sh BUILD_DIR INSTALL_PREFIX SOURCE_DIR
set -euo pipefail
build=$1
prefix=$2
source=$3
here=$(cd "$(dirname "$0")" && pwd)
destdir=$(mktemp -d)
trap 'rm -rf "$destdir"' EXIT

DESTDIR="$destdir" cmake --install "$build" >/dev/null
fail=0

expected=$(sed -e '/^#/d' -e '/^$/d' -e "s|@PREFIX@|$prefix|" "$here/expected_install_files.txt" | sort)
actual=$(cd "$destdir" && find . \( -type f -o -type l \) | sed 's|^\.||' | sort)
if [ "$expected" != "$actual" ]; then
  echo "FAIL: installed files differ from tests/packaging/expected_install_files.txt"
  diff <(echo "$expected") <(echo "$actual") | sed 's/^</missing:/; s/^>/unexpected:/' || true
  fail=1
fi

bin="$destdir$prefix/bin/cloudbrush"
if ! "$bin" --help | grep -q '^usage: cloudbrush'; then
  echo "FAIL: the installed $bin does not print its usage"
  fail=1
fi
unit="$destdir/lib/systemd/system/cloudbrush-kiosk.service"
if ! grep -qxF "ExecStart=$prefix/bin/cloudbrush kiosk" "$unit"; then
  echo "FAIL: the installed unit does not start $prefix/bin/cloudbrush:"
  grep '^ExecStart=' "$unit" || true
  fail=1
fi
if ! grep -qxF "Environment=CLOUDBRUSH_CONFIG_DIR=$prefix/share/cloudbrush/config" "$unit"; then
  echo "FAIL: the installed unit does not point CLOUDBRUSH_CONFIG_DIR at the installed config"
  fail=1
fi
for toml in "$source"/config/*.toml; do
  if ! cmp -s "$toml" "$destdir$prefix/share/cloudbrush/config/$(basename "$toml")"; then
    echo "FAIL: $(basename "$toml") is not installed unchanged"
    fail=1
  fi
done
for script in postinst prerm postrm; do
  if ! sh -n "$source/packaging/debian/$script"; then
    echo "FAIL: packaging/debian/$script does not parse"
    fail=1
  fi
done

[ "$fail" -eq 0 ] && echo "PASS: $(echo "$actual" | wc -l) files installed as expected"
exit "$fail"
