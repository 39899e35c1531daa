#!/usr/bin/env bash
# Builds the initramfs of the KMS tests: busybox-static, the kernel's virtual display drivers
# (bochs for -device bochs-display, virtio-gpu for -device virtio-gpu-pci) with their module
# dependencies read from each module's .modinfo (the Debian package ships no modules.dep), and
# the programs to run.
#
#   make_kms_initramfs.sh OUT.cpio.gz MODDIR COMMAND FILE...
#
# FILEs are copied to /bin. With CB_KMS_WITH_LIBS=1 each FILE's shared-library closure (ldd)
# and Mesa's EGL/GBM/DRI drivers are copied too (the EGL-on-GBM test; about 180 MB).
# /init loads the modules, waits for /dev/dri/card0, runs COMMAND and powers off.
set -euo pipefail
out=${1:?usage: make_kms_initramfs.sh OUT.cpio.gz MODDIR COMMAND FILE...}
moddir=${2:?MODDIR}
command=${3:?COMMAND}
shift 3
busybox=$(command -v busybox || true)
[ -n "$busybox" ] && file -L "$busybox" 2>/dev/null | grep -q static || busybox=/bin/busybox
[ -x "$busybox" ] || { echo "make_kms_initramfs: busybox-static is not installed" >&2; exit 2; }

root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,sbin,dev,proc,sys,tmp,run,lib/modules,etc}
cp "$busybox" "$root/bin/busybox"

# Modules in load order: every dependency before its user.
declare -A seen=()
order=()
module_path() { find "$moddir/kernel" -name "$1.ko" -o -name "${1//_/-}.ko" | head -n1; }
add_module() {
  local name=${1//-/_}
  [ -n "${seen[$name]:-}" ] && return 0
  seen[$name]=1
  local path
  path=$(module_path "$1")
  if [ -z "$path" ]; then
    grep -q "/${1}.ko\$\|/${1//_/-}.ko\$" "$moddir/modules.builtin" 2>/dev/null && return 0
    echo "make_kms_initramfs: module $1 not found under $moddir" >&2
    exit 2
  fi
  local deps
  deps=$(objcopy -O binary --only-section=.modinfo "$path" /dev/stdout | tr '\0' '\n' |
         sed -n 's/^depends=//p' | tr ',' ' ')
  for d in $deps; do add_module "$d"; done
  cp "$path" "$root/lib/modules/"
  order+=("$(basename "$path")")
}
for m in bochs virtio_pci virtio-gpu; do add_module "$m"; done
printf '%s\n' "${order[@]}" > "$root/lib/modules/order"

for f in "$@"; do
  cp -L "$f" "$root/bin/"
  strip --strip-debug "$root/bin/$(basename "$f")" 2>/dev/null || true  # smaller initramfs
done

if [ "${CB_KMS_WITH_LIBS:-0}" = 1 ]; then
  libdir=/usr/lib/x86_64-linux-gnu
  extra=("$libdir"/dri/kms_swrast_dri.so "$libdir"/dri/swrast_dri.so "$libdir"/libEGL_mesa.so.0
         "$libdir"/libgbm.so.1 "$libdir"/libglapi.so.0)
  [ -d "$libdir/gbm" ] && extra+=("$libdir"/gbm/*.so)
  for f in "$@" "${extra[@]}"; do
    for lib in $(ldd "$f" 2>/dev/null | awk '/=>/ {print $3} /^\t\/lib/ {print $1}'); do
      [ -e "$root$lib" ] || { mkdir -p "$root$(dirname "$lib")"; cp -L "$lib" "$root$lib"; }
    done
  done
  for f in "${extra[@]}"; do mkdir -p "$root$(dirname "$f")"; cp -L "$f" "$root$f"; done
  mkdir -p "$root/usr/share/glvnd/egl_vendor.d"
  cp /usr/share/glvnd/egl_vendor.d/50_mesa.json "$root/usr/share/glvnd/egl_vendor.d/"
  mkdir -p "$root/lib64"
  cp -L /lib64/ld-linux-x86-64.so.2 "$root/lib64/"
fi

cat > "$root/init" <<INIT
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t tmpfs tmp /tmp
for m in \$(cat /lib/modules/order); do insmod /lib/modules/\$m 2>/dev/null; done
i=0
while [ ! -e /dev/dri/card0 ] && [ \$i -lt 100 ]; do sleep 0.1; i=\$((i+1)); done
echo "KMS-INIT cards: \$(ls /dev/dri 2>/dev/null)"
export PATH=/bin:/sbin HOME=/tmp XDG_RUNTIME_DIR=/tmp LIBGL_ALWAYS_SOFTWARE=1
$command
echo "KMS-INIT exit=\$?"
poweroff -f
INIT
chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc --quiet | gzip -1) > "$out"
echo "make_kms_initramfs: $out ($(du -h "$out" | cut -f1)), modules: ${order[*]}" >&2
