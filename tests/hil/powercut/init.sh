#!/bin/sh
# /init of the power-cut guest: mount the journal's disk (ext4 on virtio, the kernel replays
# the filesystem's own journal after a reset), read back and carry on writing the session
# journal (journal_power_writer), then unmount and power off once it is all written.
export PATH=/bin:/sbin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
echo "POWERCUT BOOT $(uname -r)"
load-modules
mkdir -p /mnt
n=0
while [ ! -b /dev/vda ] && [ $n -lt 50 ]; do sleep 0.1; n=$((n + 1)); done
if ! mount -t ext4 /dev/vda /mnt; then
  echo "POWERCUT FAIL cannot mount /dev/vda"
  poweroff -f
fi
/powercut/journal_power_writer /powercut/source.cbj /mnt/session.cbj
status=$?
umount /mnt
echo "POWERCUT EXIT $status"
poweroff -f
