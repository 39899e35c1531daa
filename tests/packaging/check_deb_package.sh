#!/usr/bin/env bash
# Builds the Debian package with CPack from BUILD_DIR, then checks it: `dpkg-deb -c` lists
# exactly expected_install_files.txt (prefix /usr), the control file has the run-time Depends and
# carries the maintainer scripts, and `lintian` reports no errors (warnings are printed).
# Then it installs the package into a throwaway Debian 12 root (mmdebstrap --variant=apt, cached
# as BUILD_DIR/deb-root-cache/bookworm-apt.tar; dependencies come from Debian's archive):
# `apt-get install ./cloudbrush_*.deb` in a chroot, the postinst's user, `cloudbrush` renders the
# bundled cloud headlessly there (EGL surfaceless, llvmpipe) as the `cloudbrush` user with the
# unit's environment, and `apt-get purge cloudbrush` leaves the root's files as they were before
# the install (apt's and dpkg's own records aside; the system user stays, as Debian does).
# Then the installer's steps on a second install (deb_root_kiosk_steps.sh): the conffile kept
# over a reinstall and an upgrade, --set-pin, cloudbrush-kiosk-setup without and with systemd,
# the build tree's config ignored, purge.
# usage: check_deb_package.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
root=""
cleanup() {
  if [ -n "$root" ]; then
    for m in proc dev/pts dev; do mountpoint -q "$root/$m" && umount "$root/$m"; done
    rm -rf "$root"
  fi
  rm -rf "$out"
}
trap cleanup EXIT

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

# The package in a throwaway Debian 12 root.
cache="$build/deb-root-cache/bookworm-apt.tar"
if [ ! -f "$cache" ] || [ ! -s "$cache" ]; then
  rm -rf "$cache"  # a directory left by an older version of this script
  if ! command -v mmdebstrap >/dev/null; then
    echo "SKIPPED the Debian 12 root: mmdebstrap is not installed (config/setup.sh installs it)" >&2
    [ "$fail" -eq 0 ] && exit 77
    exit "$fail"
  fi
  mkdir -p "$(dirname "$cache")"
  echo "making a Debian 12 root with mmdebstrap (once; cached as $cache)"
  # --format: mmdebstrap picks the format from the target's name, and "….tar.part" is not one it
  # knows, so without it a directory would be made (and renamed to ….tar).
  mmdebstrap --variant=apt --format=tar --quiet bookworm "$cache.part" \
    "deb http://deb.debian.org/debian bookworm main" \
    "deb http://deb.debian.org/debian bookworm-updates main" \
    "deb http://deb.debian.org/debian-security bookworm-security main"
  mv "$cache.part" "$cache"
fi
root=$(mktemp -d)
tar -C "$root" -xf "$cache"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
cp /etc/resolv.conf "$root/etc/resolv.conf"
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive "$@"; }
# Files of the root, apt's and dpkg's own records aside (they note every install and removal).
listing() {
  (cd "$root" && find . -xdev \( -path ./proc -o -path ./dev -o -path ./tmp -o -path ./var/lib/dpkg \
      -o -path ./var/lib/apt -o -path ./var/cache -o -path ./var/log -o -path ./run \) -prune -o -print |
    sort)
}
t0=$(date +%s)
in_root apt-get update -qq >"$out/apt.log" 2>&1 || { echo "FAIL: apt-get update in the root:"; cat "$out/apt.log"; exit 1; }
# The dependencies first, so the snapshot before the install has them (purge leaves them).
in_root apt-get satisfy -y -qq --no-install-recommends "$(dpkg-deb -f "$deb" Depends)" >>"$out/apt.log" 2>&1 ||
  { echo "FAIL: the package's Depends cannot be installed from Debian 12:"; tail -30 "$out/apt.log"; exit 1; }
listing >"$out/before.txt"
cp "$deb" "$root/tmp/"
if in_root apt-get install -y -qq --no-install-recommends "/tmp/$(basename "$deb")" >"$out/install.log" 2>&1; then
  echo "installed in a Debian 12 root: apt-get install ./$(basename "$deb") ($(($(date +%s) - t0)) s with dependencies)"
else
  echo "FAIL: apt-get install ./$(basename "$deb") in the Debian 12 root:"; tail -30 "$out/install.log"; fail=1
fi
if in_root getent passwd cloudbrush >/dev/null; then
  echo "  postinst made the system user: $(in_root getent passwd cloudbrush)"
else
  echo "FAIL: the postinst did not make the cloudbrush user"; fail=1
fi
# Headless render as the kiosk's user, with the unit's environment: its data dir made as the
# unit's StateDirectory= makes it, Mesa's shader cache and the output inside it (purge must
# delete them all).
data=/var/lib/cloudbrush
in_root install -d -m 0750 -o cloudbrush -g cloudbrush "$data"
if in_root runuser -u cloudbrush -- env HOME="$data" CLOUDBRUSH_STATE_DIR="$data" \
     LIBGL_ALWAYS_SOFTWARE=1 MESA_SHADER_CACHE_DIR="$data/mesa-shader-cache" sh -c \
     "cd $data && cloudbrush --size 320x200 --grid 64 --out-dir $data/out" \
     >"$out/render.log" 2>&1 && [ -s "$root$data/out/cloudbrush-cumulus.png" ] &&
   [ -s "$root$data/out/cloudbrush-cumulus.exr" ]; then
  echo "  rendered headlessly in the root as cloudbrush: $(tr '\n' ' ' <"$out/render.log" | cut -c1-160)"
  echo "    ($(find "$root$data" -type f | wc -l) files under $data)"
  cp "$root$data/out/cloudbrush-cumulus.png" "$build/deb-root-render.png"
else
  echo "FAIL: cloudbrush did not render in the root:"; cat "$out/render.log"; fail=1
fi
rm -f "$root/tmp/$(basename "$deb")"
if in_root apt-get purge -y -qq cloudbrush >"$out/purge.log" 2>&1; then
  listing >"$out/after.txt"
  # The system user stays (postrm): adduser's backup copies of the account files may appear.
  leftover=$(diff "$out/before.txt" "$out/after.txt" | grep -vE '^[<>] \./etc/(passwd|group|shadow|gshadow)-$' |
             grep '^[<>]' || true)
  if [ -n "$leftover" ]; then
    echo "FAIL: the root after purge differs from before the install:"; echo "$leftover" | head -40; fail=1
  else
    echo "  purged: the root's files are as before the install ($(wc -l <"$out/after.txt") paths compared)"
  fi
else
  echo "FAIL: apt-get purge cloudbrush:"; tail -20 "$out/purge.log"; fail=1
fi

# The installer's steps (conffile, PIN, cloudbrush-kiosk-setup, no build-tree path) on a second
# install in the same root.
source=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
. "$here/deb_root_kiosk_steps.sh"

[ "$fail" -eq 0 ] && echo "PASS: $(basename "$deb") has the expected files and scripts, installs, renders and purges in Debian 12, keeps its conffile, takes the PIN and the kiosk setup"
exit "$fail"
