#!/usr/bin/env bash
# Host side of the virtual-tablet test: fetch Debian's kernel, build the initramfs with the
# in-guest test binary, boot it in qemu (TCG) and turn the guest's verdict into an exit status.
#
#   run_tablet_hil.sh BUILD_DIR VM_BINARY FIXTURE_DIR [phases, comma-separated]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
common=$here/../common
build=${1:?build dir}; binary=${2:?vm binary}; fixtures=${3:?fixture dir}; phases=${4:-uhid,intuos4,gadget,latency,corpus,uclogic}
if ! command -v qemu-system-x86_64 >/dev/null; then
  echo "************************************************************************" >&2
  echo "*** SKIPPED: qemu-system-x86_64 is not installed; the virtual tablet   ***" >&2
  echo "*** test did NOT run. Install qemu-system-x86 (config/setup.sh).       ***" >&2
  echo "************************************************************************" >&2
  exit 77
fi
cache=$build/hil-cache
mkdir -p "$cache"
libdir=/usr/lib/x86_64-linux-gnu
out=$(
  "$common/build_initramfs.sh" --kernel-cache "$cache/kernel" --out "$cache/tablet-initrd.cpio.gz" \
    --init "$here/init.sh" \
    --module evdev --module uinput --module hid --module uhid --module usbhid --module wacom \
    --module hid-generic --module dummy_hcd --module libcomposite --module usb_f_hid \
    --module gadgetfs --module hid-uclogic \
    --binary "$binary:/hil/cb_tablet_hil_vm" \
    --binary "$libdir/libhidapi-hidraw.so.0" --binary "$libdir/libhidapi-libusb.so.0" \
    --file "$fixtures:/hil/fixtures" --file "$here/../../../config/devices:/hil/devices"
)
eval "$(echo "$out" | grep -E '^(KVER|VMLINUZ|INITRD)=')"
echo "tablet HIL: Debian kernel $KVER (qemu TCG)"
log=$build/tablet_hil_console.log
start=$(date +%s)
CB_QEMU_APPEND="cbhil.phases=$phases" "$common/run_qemu.sh" "$VMLINUZ" "$INITRD" 240 | tee "$log" || true
echo "tablet HIL: guest ran $(( $(date +%s) - start )) s"
grep '^CB-HIL FIGURE' "$log" | sed "s/^CB-HIL FIGURE //" > "$build/tablet_hil_figures.txt" || true
if grep -q '^CB-HIL RESULT PASS' "$log"; then
  exit 0
fi
echo "tablet HIL: FAILED (see $log)" >&2
grep -E '^CB-HIL CHECK FAIL' "$log" >&2 || echo "tablet HIL: the guest gave no result" >&2
exit 1
