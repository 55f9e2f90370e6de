#!/usr/bin/env bash
# A private single-node Slurm cluster on this machine, for tests/slurm.rs and for
# anyone who wants to try the user guide's array script (docs/src/how-to/slurm.md).
#
#   tests/slurm/cluster.sh start DIR   # start munged (if none answers), slurmctld, slurmd
#   export SLURM_CONF=DIR/slurm.conf   # then sbatch, sinfo, squeue talk to it
#   tests/slurm/cluster.sh stop DIR    # stop what start started, by PID
#
# Needs Debian's slurm-wlm and munge (apt-get install slurm-wlm munge) and root: the
# daemons run as root, jobs as the submitter (root). Everything of the cluster lives in
# DIR (its slurm.conf, state, spool, logs, PID files) and it listens on its own ports
# (16817, 16818), so it stays clear of any other Slurm on the machine. Jobs run in the
# directory sbatch was called from, with the submitter's environment (PATH included).
set -euo pipefail

cmd=${1:-}
dir=${2:-}
if [[ -z $cmd || -z $dir ]]; then
  echo "usage: $0 start|stop DIR" >&2
  exit 2
fi

stop() {
  for name in slurmd slurmctld munged; do
    pidfile="$dir/$name.pid"
    [[ -f $pidfile ]] || continue
    pid=$(cat "$pidfile")
    if kill "$pid" 2>/dev/null; then
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
    fi
    rm -f "$pidfile"
  done
}

case $cmd in
stop)
  stop
  exit 0
  ;;
start) ;;
*)
  echo "usage: $0 start|stop DIR" >&2
  exit 2
  ;;
esac

for tool in slurmctld slurmd sbatch sinfo munged munge; do
  command -v "$tool" >/dev/null || PATH="$PATH:/usr/sbin"
  command -v "$tool" >/dev/null || { echo "$tool not found: apt-get install slurm-wlm munge" >&2; exit 3; }
done
mkdir -p "$dir"/{state,spool,log}
dir=$(cd "$dir" && pwd)
trap 'stop' ERR

# munge: reuse a daemon that answers; otherwise start one, with a key if none exists.
if ! munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
  if [[ ! -s /etc/munge/munge.key ]]; then
    mungekey -c -f 2>/dev/null || mungekey -c
  fi
  chown munge:munge /etc/munge/munge.key
  chmod 0400 /etc/munge/munge.key
  mkdir -p /run/munge /var/lib/munge /var/log/munge
  chown munge:munge /run/munge /var/lib/munge /var/log/munge
  # As root (--force): munged warns that it should run as munge, harmlessly here.
  munged --force --pid-file "$dir/munged.pid" 2>"$dir/log/munged.err"
  for _ in $(seq 50); do munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
fi

host=$(hostname -s)
cpus=$(nproc)
cat >"$dir/slurm.conf" <<CONF
ClusterName=impactlab-test
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
# -D keeps them in the foreground of their own background job: their PIDs are ours.
slurmctld -D -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 &
echo $! >"$dir/slurmctld.pid"
slurmd -D -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 &
echo $! >"$dir/slurmd.pid"
for _ in $(seq 300); do
  if [[ $(sinfo -h -o %T 2>/dev/null) == idle ]]; then
    echo "slurm: node $host idle ($cpus CPUs); SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "slurm: the node did not come up within 60 s; logs in $dir/log" >&2
tail -n 20 "$dir"/log/*.log >&2 || true
stop
exit 1
