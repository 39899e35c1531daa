#!/bin/busybox sh
# Runs in the guest of kms_kiosk_test (busybox sh, from /init, its output on the serial console).
# The host reads the KIOSK-HIL lines and answers with keys on the qemu monitor (sendkey), which
# reach the guest through the emulated PS/2 keyboard: the kernel's VT keyboard handler and evdev.
#   1. control: without the kiosk, Ctrl+Alt+F2 switches from VT 1 to VT 2;
#   2. `cloudbrush kiosk` on the virtual card with VT 1 as its terminal; the active VT is
#      printed every second while it runs (the host sends Ctrl+Alt+F2, the mode keys 1-5 and quit
#      combinations);
#   3. once the kiosk has seen the keys: the virtual tablet plugged in 20 times while the attract
#      loop shows (a pause longer than the idle reset between) and 20 times mid-visit, each plug
#      kept until the kiosk says its first sample reached the screen;
#   4. the kiosk is stopped (SIGTERM, as systemd would) and says how it ran.
active() { cat /sys/class/tty/tty0/active; }
: > /dev/tty2  # allocate VT 2: the kernel switches only to allocated VTs
echo "KIOSK-HIL control-ready $(active)"
i=0
while [ "$(active)" = tty1 ] && [ $i -lt 1200 ]; do sleep 0.1; i=$((i+1)); done
echo "KIOSK-HIL control-after $(active)"
chvt 1
echo "KIOSK-HIL back $(active)"

export CLOUDBRUSH_CONFIG_DIR=/config MESA_SHADER_CACHE_DIR=/tmp/data/mesa-shader-cache
mkdir -p /tmp/data
cloudbrush kiosk --display kms --grid 32 --data-dir /tmp/data --idle-seconds 6 \
  --warning-seconds 1 </dev/tty1 >/tmp/kiosk.log 2>&1 &
kiosk=$!
# Every second while the kiosk runs: its new log lines (as KIOSK-LOG), then the active VT.
(
  n=0
  while kill -0 $kiosk 2>/dev/null; do
    m=$(wc -l </tmp/kiosk.log)
    [ "$m" -gt "$n" ] && head -n "$m" /tmp/kiosk.log | tail -n $((m - n)) | sed 's/^/KIOSK-LOG /'
    n=$m
    echo "KIOSK-HIL active $(active)"
    sleep 1
  done
  m=$(wc -l </tmp/kiosk.log)
  [ "$m" -gt "$n" ] && head -n "$m" /tmp/kiosk.log | tail -n $((m - n)) | sed 's/^/KIOSK-LOG /'
) &
reporter=$!
while [ ! -e /tmp/data/health.json ] && kill -0 $kiosk 2>/dev/null; do sleep 0.2; done
echo "KIOSK-HIL kiosk-up"
# The host's keys end with Esc and the other quit combinations (10 s).
i=0
while ! grep -qF "That key is for the operator / 该按键仅供操作员使用 (Esc)" /tmp/kiosk.log && [ $i -lt 3000 ]; do
  sleep 0.2; i=$((i+1))
done
echo "KIOSK-HIL keys-seen"
sleep 20  # the other quit combinations, then the idle reset (6 + 1 s) back to the attract loop
kiosk_pen_hotplug /bin/wacom-pth660_v145.rdesc /tmp/kiosk.log attract 20 10000
kiosk_pen_hotplug /bin/wacom-pth660_v145.rdesc /tmp/kiosk.log visit 20 300
kill -TERM $kiosk
wait $kiosk
status=$?
wait $reporter
echo "KIOSK-HIL kiosk-exit $status"
