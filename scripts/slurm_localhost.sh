#!/bin/bash
# A one-node Slurm cluster on this machine, for the tests of `roadslam-experiment --emit slurm`
# (Debian: slurm-wlm, munge; run as root). Everything lives in STATE_DIR; ports 16817/16818.
#   scripts/slurm_localhost.sh start STATE_DIR   # prints the SLURM_CONF to export; exit 1 if it cannot start
#   scripts/slurm_localhost.sh stop STATE_DIR
set -uo pipefail
cmd=${1:?start|stop}; dir=$(realpath -m "${2:?STATE_DIR}")
stop() {
  for p in slurmd slurmctld; do [ -f "$dir/$p.pid" ] && kill "$(cat "$dir/$p.pid")" 2>/dev/null; done
  [ -f "$dir/munge/munged.pid" ] && kill "$(cat "$dir/munge/munged.pid")" 2>/dev/null
  for _ in $(seq 20); do
    ls "$dir"/slurmd.pid "$dir"/slurmctld.pid "$dir"/munge/munged.pid > /dev/null 2>&1 || return 0
    sleep 0.5
  done
  return 0
}
if [ "$cmd" = stop ]; then stop; exit 0; fi
for b in slurmctld slurmd munged sbatch sinfo; do command -v $b > /dev/null || { echo "no $b (Debian: slurm-wlm, munge)" >&2; exit 1; }; done
[ "$(id -u)" = 0 ] || { echo "needs root (munged runs as the munge user, slurmd as root)" >&2; exit 1; }
[ -r /etc/munge/munge.key ] || { echo "no /etc/munge/munge.key" >&2; exit 1; }
stop
host=$(hostname)
mkdir -p "$dir/state" "$dir/spool" "$dir/munge" /run/munge
chown munge:munge "$dir/munge" /run/munge && chmod 700 "$dir/munge"
cat > "$dir/slurm.conf" <<CONF
ClusterName=roadslam-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=16817
SlurmdPort=16818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
su -s /bin/sh munge -c "munged --socket=/run/munge/munge.socket.2 --force --log-file=$dir/munge/munged.log \
  --pid-file=$dir/munge/munged.pid --seed-file=$dir/munge/seed" || { echo "munged did not start" >&2; exit 1; }
export SLURM_CONF=$dir/slurm.conf
slurmctld && slurmd || { echo "slurmctld/slurmd did not start (see $dir/*.log)" >&2; stop; exit 1; }
for _ in $(seq 30); do
  sinfo -h -o %T 2>/dev/null | grep -q idle && { echo "$SLURM_CONF"; exit 0; }
  sleep 1
done
echo "the node did not come up within 30 s (see $dir/*.log)" >&2
stop
exit 1
