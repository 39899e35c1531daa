#!/usr/bin/env bash
# Checks config/systemd/cloudbrush-kiosk.service with `systemd-analyze verify`, the unit's
# ExecStart pointed at the built binary (verify needs the executable to exist), and that the
# directives the kiosk relies on are there. Also proves the check bites: a copy with a broken
# directive must fail verification.
# usage: verify_systemd_unit.sh UNIT_FILE CLOUDBRUSH_BINARY
set -euo pipefail
unit=$1
binary=$2
if ! command -v systemd-analyze >/dev/null; then
  echo "SKIPPED: systemd-analyze not found; install the 'systemd' package (config/setup.sh)" >&2
  exit 77
fi
[ -x "$binary" ] || { echo "FAIL: $binary is not an executable (build the cloudbrush target)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail=0
# The hardening directives the kiosk's unit must carry, each on its own line.
for directive in 'Type=notify' 'WatchdogSec=10s' 'Restart=always' 'User=cloudbrush' \
    'SupplementaryGroups=input video render' 'TTYPath=/dev/tty7' 'StandardInput=tty-fail' \
    'StateDirectory=cloudbrush' 'Environment=MESA_SHADER_CACHE_DIR=/var/lib/cloudbrush/mesa-shader-cache' \
    'Environment=CLOUDBRUSH_STATE_DIR=/var/lib/cloudbrush' 'Conflicts=getty@tty7.service' \
    'ProtectSystem=strict' 'ExecStart=/usr/bin/cloudbrush kiosk' \
    'RestartPreventExitStatus=10'; do
  if ! grep -qxF "$directive" "$unit"; then
    echo "FAIL: $unit lacks the line '$directive'"
    fail=1
  fi
done

copy="$work/cloudbrush-kiosk.service"
sed "s|^ExecStart=/usr/bin/cloudbrush |ExecStart=$binary |" "$unit" > "$copy"
echo "systemd-analyze verify $unit (ExecStart -> $binary)"
if ! out=$(systemd-analyze verify --man=no "$copy" 2>&1) || [ -n "$out" ]; then
  echo "FAIL: systemd-analyze verify reported:"
  echo "$out"
  fail=1
fi

broken="$work/broken/cloudbrush-kiosk.service"
mkdir -p "$work/broken"
sed 's|^Type=notify$|Type=notifyy|' "$copy" > "$broken"
if out=$(systemd-analyze verify --man=no "$broken" 2>&1) && [ -z "$out" ]; then
  echo "FAIL: verify accepted a unit with Type=notifyy; the check cannot catch mistakes"
  fail=1
fi

[ "$fail" -eq 0 ] && echo "PASS: the unit verifies and has every kiosk directive"
exit "$fail"
