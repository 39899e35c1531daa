#!/bin/bash
# A one-node Slurm cluster on this machine for the study export test, private to DIR: munged on
# its own socket, slurmctld and slurmd with a slurm.conf in DIR (ports 16817/16818, no cgroups,
# no accounting), all as root. Debian's slurmctld, slurmd, slurm-client and munge packages.
#
#   slurm_one_node.sh start DIR   starts them and waits until the node is idle; prints
#                                 "SLURM_CONF=DIR/slurm.conf" for the clients (sbatch, squeue)
#   slurm_one_node.sh stop DIR    stops them (by their pid files)
set -euo pipefail
mode=$1 dir=$(readlink -f "$2")

stop() {
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    if [ -s "$pidfile" ]; then kill "$(cat "$pidfile")" 2>/dev/null || true; fi
  done
  # Daemons whose pid file is gone: by the private paths on their command lines.
  pkill -f -- "$dir/slurm.conf" 2>/dev/null || true
  pkill -f -- "$dir/munge/munge.socket" 2>/dev/null || true
  sleep 1
}

if [ "$mode" = stop ]; then stop; exit 0; fi
[ "$mode" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" >/dev/null || { echo "SKIPPED: $tool is not installed (config/setup.sh installs Slurm and munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "SKIPPED: the one-node cluster runs as root"; exit 77; }
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 700 "$dir/munge"
# munged insists on a key only its user can read, in a folder nobody else may write.
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed"
host=$(hostname -s)
cpus=$(nproc)
cat >"$dir/slurm.conf" <<CONF
ClusterName=cbtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=cbtest Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -1 || true)
  case "$state" in idle*) echo "SLURM_CONF=$SLURM_CONF"; exit 0 ;; esac
  sleep 1
done
echo "FAIL: the node did not become idle in 60 s (state '${state:-none}'); logs:" >&2
tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" "$dir/munged.log" >&2 || true
stop
exit 1
