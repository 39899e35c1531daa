#!/usr/bin/env bash
# Boots a kernel + initramfs in qemu-system-x86_64 with TCG (KVM is not usable on the CI
# machines), console on stdio, and stops it after TIMEOUT seconds at the latest.
#
#   run_qemu.sh VMLINUZ INITRD TIMEOUT [extra qemu arguments...]
#
# The guest's /init is expected to power the machine off when done. The console is copied to
# stdout; the exit status is qemu's, or 124 on timeout.
set -uo pipefail
vmlinuz=${1:?vmlinuz}; initrd=${2:?initrd}; timeout_s=${3:?timeout}; shift 3
qemu=$(command -v qemu-system-x86_64 || true)
if [ -z "$qemu" ]; then
  echo "run_qemu: qemu-system-x86_64 is not installed" >&2
  exit 127
fi
exec timeout --foreground -k 5 "$timeout_s" "$qemu" -accel tcg -m 1024 -smp 1 -nographic \
  -no-reboot -kernel "$vmlinuz" -initrd "$initrd" \
  -append "console=ttyS0 panic=-1 quiet loglevel=4 ${CB_QEMU_APPEND:-}" "$@"
