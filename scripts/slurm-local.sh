#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the batch tests and CI (docs/batch.md):
# munged, slurmctld and slurmd as root, with a config this script writes.
#
#   scripts/slurm-local.sh start    install the packages (install-deps.sh), write the config, start the daemons,
#                                   wait until the node takes jobs
#   scripts/slurm-local.sh stop     stop the daemons this script started (by their pid files)
#   scripts/slurm-local.sh status   exit 0 when the controller answers
#
# Everything lives in $CROPSIGHT_SLURM_DIR (default /tmp/cropsight-slurm): slurm.conf, the state,
# the logs and the pid files. Slurm's commands find the config through SLURM_CONF, which
# `start` prints as an export line; the tests look in the default folder when SLURM_CONF is unset.
# A real cluster's /etc/slurm is never touched. The node is this machine with its CPUs (2 on
# the project's machines) and its memory; no accounting database (sacct is not needed).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${CROPSIGHT_SLURM_DIR:-/tmp/cropsight-slurm}"
conf="$dir/slurm.conf"
export SLURM_CONF="$conf"

need_root() {
  [[ $(id -u) -eq 0 ]] || { echo "slurm-local: must run as root (the daemons run as root)" >&2; exit 1; }
}

write_config() {
  local host cpus mem
  host="$(hostname -s)"
  cpus="$(nproc)"
  mem="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"  # MB, leave the OS its share
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
  cat >"$conf" <<CONF
# Written by scripts/slurm-local.sh: a one-node cluster for cropsight's batch tests.
ClusterName=cropsight-local
SlurmctldHost=$host
AuthType=auth/munge
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
# Keep finished jobs visible to scontrol for an hour (the tests read their array tasks).
MinJobAge=3600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start_munge() {
  local socket=/run/munge/munge.socket.2
  if [[ -S $socket ]] && munge -n </dev/null >/dev/null 2>&1; then return; fi  # a munged already answers
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null || true
  if [[ ! -s /etc/munge/munge.key ]]; then
    mungekey --create --keyfile=/etc/munge/munge.key
    chown munge:munge /etc/munge/munge.key
    chmod 600 /etc/munge/munge.key
  fi
  # As the munge user, as the Debian service does (munged refuses root without --force).
  if id munge >/dev/null 2>&1; then
    runuser -u munge -- munged --pid-file=/run/munge/munged.pid
  else
    munged --force --pid-file=/run/munge/munged.pid
  fi
  cp /run/munge/munged.pid "$dir/munged.pid"
}

controller_answers() { [[ -f $conf ]] && scontrol ping 2>/dev/null | grep -q "is UP"; }

start() {
  need_root
  "$here/install-deps.sh" >&2  # stdout carries only the export line (eval "$(... start)")
  if controller_answers; then echo "export SLURM_CONF=$conf"; return; fi
  write_config
  start_munge
  slurmctld -L "$dir/slurmctld.log"
  slurmd -L "$dir/slurmd.log"
  for _ in $(seq 1 60); do
    if controller_answers && sinfo -h -o "%T" 2>/dev/null | grep -qE "^(idle|mixed|allocated)"; then
      echo "export SLURM_CONF=$conf"
      return
    fi
    sleep 0.5
  done
  echo "slurm-local: the node did not come up; see $dir/slurmctld.log and $dir/slurmd.log" >&2
  exit 1
}

stop_pid_file() {
  local f="$1"
  [[ -f $f ]] || return 0
  local pid
  pid="$(cat "$f")"
  if kill -0 "$pid" 2>/dev/null; then
    kill "$pid"
    for _ in $(seq 1 40); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
  fi
  rm -f "$f"
}

stop() {
  need_root
  stop_pid_file "$dir/slurmd.pid"
  stop_pid_file "$dir/slurmctld.pid"
  stop_pid_file "$dir/munged.pid"  # only a munged this script started (its pid was copied here)
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) controller_answers ;;
  *) echo "usage: scripts/slurm-local.sh start|stop|status" >&2; exit 2 ;;
esac
