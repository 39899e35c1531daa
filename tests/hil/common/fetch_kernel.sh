#!/usr/bin/env bash
# Fetches Debian's stock amd64 kernel into a cache directory, with apt-get download + dpkg -x
# (the only network access the HIL tests make: Debian's archive, through apt).
#
#   fetch_kernel.sh CACHE_DIR
#
# Prints three lines on stdout (everything else goes to stderr):
#   KVER=<version, e.g. 6.1.0-56-amd64>
#   VMLINUZ=<path to the kernel image>
#   MODDIR=<path to lib/modules/<version>>
# The archive moves on (new ABI numbers); the version actually fetched is always printed, and a
# kernel already in the cache is reused without touching the network.
set -euo pipefail
cache=${1:?usage: fetch_kernel.sh CACHE_DIR}
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)

find_kernel() {
  local vmlinuz
  vmlinuz=$(ls -1 "$cache"/root/boot/vmlinuz-*-amd64 2>/dev/null | sort -V | tail -n1 || true)
  [ -n "$vmlinuz" ] || return 1
  local kver=${vmlinuz##*/vmlinuz-}
  [ -d "$cache/root/lib/modules/$kver/kernel" ] || return 1
  echo "KVER=$kver"
  echo "VMLINUZ=$vmlinuz"
  echo "MODDIR=$cache/root/lib/modules/$kver"
}

if find_kernel >/dev/null 2>&1; then
  find_kernel
  exit 0
fi

# The metapackage linux-image-amd64 depends on the current linux-image-<abi>-amd64.
pkg=$(apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/{print $2; exit}')
if [ -z "$pkg" ]; then
  echo "fetch_kernel: apt-cache knows no linux-image-amd64; run apt-get update" >&2
  exit 2
fi
echo "fetch_kernel: downloading $pkg from Debian's archive" >&2
(cd "$cache" && rm -f linux-image-*.deb && apt-get download -q "$pkg" >&2)
deb=$(ls -1 "$cache"/linux-image-*.deb | head -n1)
rm -rf "$cache/root.tmp"
dpkg -x "$deb" "$cache/root.tmp"
rm -rf "$cache/root"
mv "$cache/root.tmp" "$cache/root"
rm -f "$deb"
find_kernel || { echo "fetch_kernel: $deb held no vmlinuz/modules" >&2; exit 2; }
