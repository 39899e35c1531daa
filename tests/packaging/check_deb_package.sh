#!/usr/bin/env bash
# Builds the Debian package with CPack from BUILD_DIR, then checks it: `dpkg-deb -c` lists
# exactly expected_install_files.txt (prefix /usr), the control file has the run-time Depends and
# carries the maintainer scripts, and `lintian` reports no errors (warnings are printed).
# usage: check_deb_package.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

(cd "$out" && cpack -G DEB --config "$build/CPackConfig.cmake" >cpack.log 2>&1) || {
  echo "FAIL: cpack failed:"; cat "$out/cpack.log"; exit 1; }
deb=$(ls "$out"/cloudbrush_*.deb)
echo "built $(basename "$deb")"
fail=0

expected=$(sed -e '/^#/d' -e '/^$/d' -e 's|@PREFIX@|/usr|' "$here/expected_install_files.txt" | sort)
actual=$(dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print $6}' | sed 's|^\.||' | sort)
if [ "$expected" != "$actual" ]; then
  echo "FAIL: the package's files differ from tests/packaging/expected_install_files.txt"
  diff <(echo "$expected") <(echo "$actual") | sed 's/^</missing:/; s/^>/unexpected:/' || true
  fail=1
fi
if dpkg-deb -c "$deb" | awk '{print $2}' | grep -qv '^root/root$'; then
  echo "FAIL: files not owned by root/root:"; dpkg-deb -c "$deb" | grep -v ' root/root '
  fail=1
fi
control=$(dpkg-deb -I "$deb")
for dependency in adduser fonts-noto-cjk libhidapi-hidraw0 libhidapi-libusb0 libc6; do
  grep -q "^ Depends:.*\b$dependency\b" <<<"$control" || { echo "FAIL: Depends lacks $dependency"; fail=1; }
done
for script in postinst prerm postrm; do
  grep -qE "^ +[0-9]+ bytes, +[0-9]+ lines +\*? *$script " <<<"$control" ||
    { echo "FAIL: the package has no $script"; fail=1; }
done

if command -v lintian >/dev/null; then
  report=$(lintian --tag-display-limit 0 "$deb" 2>&1 || true)
  echo "lintian:"
  echo "${report:-  (nothing reported)}"
  if grep -q '^E: ' <<<"$report"; then
    echo "FAIL: lintian reports errors"
    fail=1
  fi
else
  echo "SKIPPED lintian: not installed (config/setup.sh installs it)" >&2
  [ "$fail" -eq 0 ] && exit 77
fi

[ "$fail" -eq 0 ] && echo "PASS: $(basename "$deb") has the expected files and scripts"
exit "$fail"
