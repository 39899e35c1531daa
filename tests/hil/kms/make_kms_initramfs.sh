#!/usr/bin/env bash
# Builds the initramfs of the KMS tests with tests/hil/common/build_initramfs.sh: busybox-static,
# the kernel's virtual display drivers (bochs for -device bochs-display, virtio-gpu for
# -device virtio-gpu-pci) and the programs to run.
#
#   make_kms_initramfs.sh KERNEL_CACHE OUT.cpio.gz COMMAND FILE...
#
# FILEs go to /bin (with their ldd closure). With CB_KMS_WITH_LIBS=1 Mesa's EGL/GBM/DRI
# drivers (dlopen()ed, so named here) and glvnd's vendor file are added too (the EGL-on-GBM
# test; about 90 MB compressed). CB_KMS_MODULES adds kernel modules (e.g. "evdev uhid wacom" for
# the kiosk test's keyboard and virtual tablet), CB_KMS_FILES adds SRC:DEST files or folders.
# /init loads the modules, waits for /dev/dri/card0, runs COMMAND and powers off.
set -euo pipefail
cache=${1:?usage: make_kms_initramfs.sh KERNEL_CACHE OUT.cpio.gz COMMAND FILE...}
out=${2:?OUT}
command=${3:?COMMAND}
shift 3
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

args=(--kernel-cache "$cache" --out "$out" --init "$work/init")
for m in bochs virtio_pci virtio-gpu ${CB_KMS_MODULES:-}; do args+=(--module "$m"); done
for f in ${CB_KMS_FILES:-}; do args+=(--file "$f"); done
for f in "$@"; do
  # Without debug info: a smaller initramfs, a faster boot.
  strip --strip-debug -o "$work/$(basename "$f")" "$f" 2>/dev/null || cp -L "$f" "$work/"
  # Static programs go as plain files: build_initramfs.sh's ldd closure fails on them.
  if ldd "$f" >/dev/null 2>&1; then kind=--binary; else kind=--file; fi
  args+=("$kind" "$work/$(basename "$f"):/bin/$(basename "$f")")
done
if [ "${CB_KMS_WITH_LIBS:-0}" = 1 ]; then
  libdir=/usr/lib/x86_64-linux-gnu
  for lib in "$libdir"/dri/kms_swrast_dri.so "$libdir"/dri/swrast_dri.so \
             "$libdir"/libEGL_mesa.so.0 "$libdir"/libgbm.so.1 "$libdir"/libglapi.so.0 \
             "$libdir"/libGL.so.1; do  # libGL: Dear ImGui's GL loader dlopen()s it
    args+=(--binary "$lib")
  done
  args+=(--file /usr/share/glvnd/egl_vendor.d/50_mesa.json:/usr/share/glvnd/egl_vendor.d/50_mesa.json)
fi

cat > "$work/init" <<INIT
#!/bin/busybox sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t tmpfs tmp /tmp
load-modules 2>/dev/null
i=0
while [ ! -e /dev/dri/card0 ] && [ \$i -lt 100 ]; do sleep 0.1; i=\$((i+1)); done
echo "KMS-INIT cards: \$(ls /dev/dri 2>/dev/null)"
export PATH=/bin:/sbin HOME=/tmp XDG_RUNTIME_DIR=/tmp LIBGL_ALWAYS_SOFTWARE=1
$command
echo "KMS-INIT exit=\$?"
poweroff -f
INIT
bash "$here/../common/build_initramfs.sh" "${args[@]}" >&2
echo "make_kms_initramfs: $out ($(du -h "$out" | cut -f1))" >&2
