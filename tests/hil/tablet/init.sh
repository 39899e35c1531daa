#!/bin/sh
# /init of the tablet HIL guest: mount the pseudo filesystems, load the modules, run the test.
export PATH=/bin:/sbin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /dev/pts /run /tmp && mount -t tmpfs tmpfs /run && mount -t tmpfs tmpfs /tmp
echo "CB-HIL KERNEL $(uname -r)"
load-modules
mount -t configfs none /sys/kernel/config 2>/dev/null
export CB_HIL_UHID_TRACE=1
phases=$(sed -n 's/.*cbhil.phases=\([^ ]*\).*/\1/p' /proc/cmdline | tr ',' ' ')
/hil/cb_tablet_hil_vm /hil/fixtures /hil/devices $phases
echo "CB-HIL EXIT $?"
sync
poweroff -f
