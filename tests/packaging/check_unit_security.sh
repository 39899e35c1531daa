#!/usr/bin/env bash
# The kiosk unit's sandbox: `systemd-analyze security --offline=yes` on the shipped
# config/systemd/cloudbrush-kiosk.service must give an overall exposure of at most BOUND (2.5,
# systemd's "OK" band), with the devices the kiosk needs still allowed (DRM, input, hidraw, USB)
# and PrivateDevices= not hiding them. Proves the check bites: the same unit stripped of its
# hardening lines must score above the bound.
# usage: check_unit_security.sh UNIT_FILE [BOUND]
set -euo pipefail
unit=$1
bound=${2:-2.5}
if ! command -v systemd-analyze >/dev/null; then
  echo "SKIPPED: systemd-analyze not found; install the 'systemd' package (config/setup.sh)" >&2
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

exposure() {  # prints the overall exposure of unit file $1
  local out
  out=$(systemd-analyze security --offline=yes --no-pager "$1" 2>&1) || true
  sed -n 's/.*Overall exposure level for [^:]*: \([0-9.]*\).*/\1/p' <<<"$out" | tail -1
}

fail=0
cp "$unit" "$work/cloudbrush-kiosk.service"
score=$(exposure "$work/cloudbrush-kiosk.service")
if [ -z "$score" ]; then
  echo "FAIL: systemd-analyze security gave no overall exposure for $unit"
  systemd-analyze security --offline=yes --no-pager "$work/cloudbrush-kiosk.service" || true
  exit 1
fi
echo "systemd-analyze security --offline=yes $unit: exposure $score (bound $bound)"
if awk -v s="$score" -v b="$bound" 'BEGIN { exit !(s > b) }'; then
  echo "FAIL: exposure $score is above $bound"
  systemd-analyze security --offline=yes --no-pager "$work/cloudbrush-kiosk.service" | grep '✗' || true
  fail=1
fi
for directive in 'DeviceAllow=char-drm rw' 'DeviceAllow=char-input rw' 'DeviceAllow=char-hidraw rw' \
    'DeviceAllow=char-usb_device rw' 'DevicePolicy=closed' 'CapabilityBoundingSet=' \
    'RestrictAddressFamilies=AF_UNIX AF_NETLINK' 'IPAddressDeny=any' \
    'SystemCallFilter=@system-service' 'ProtectClock=yes' 'ProtectKernelLogs=yes' \
    'RestrictNamespaces=yes' 'LockPersonality=yes'; do
  if ! grep -qxF "$directive" "$unit"; then
    echo "FAIL: $unit lacks the line '$directive'"
    fail=1
  fi
done
if grep -qE '^PrivateDevices=(yes|true|1)' "$unit"; then
  echo "FAIL: PrivateDevices= would hide /dev/dri, /dev/input, /dev/hidraw* and /dev/bus/usb"
  fail=1
fi

# The check bites: without the hardening block the same unit is above the bound.
mkdir -p "$work/bare"
sed -E '/^(DevicePolicy|DeviceAllow|CapabilityBoundingSet|AmbientCapabilities|RestrictAddressFamilies|IPAddressDeny|SystemCallFilter|SystemCallArchitectures|SystemCallErrorNumber|ProtectClock|ProtectKernelLogs|ProtectHostname|ProtectProc|RestrictNamespaces|LockPersonality|RestrictRealtime|RemoveIPC|KeyringMode|PrivateMounts)=/d' \
  "$unit" > "$work/bare/cloudbrush-kiosk.service"
bare=$(exposure "$work/bare/cloudbrush-kiosk.service")
echo "without the hardening lines: exposure $bare"
if ! awk -v s="$bare" -v b="$bound" 'BEGIN { exit !(s > b) }'; then
  echo "FAIL: the unhardened copy scores $bare, not above $bound: the check cannot catch a regression"
  fail=1
fi
[ "$fail" -eq 0 ] && echo "PASS: exposure $score <= $bound with the kiosk's devices allowed"
exit "$fail"
