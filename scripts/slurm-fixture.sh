#!/usr/bin/env bash
# A one-node Slurm cluster for the tests (tests/cluster/): munged, slurmctld and slurmd from
# Debian (slurm-wlm, munge; scripts/install-deps.sh), run as root with everything — key, sockets,
# state, spool, logs, pid files — in one folder, and nothing of the host's own configuration
# used. The node is this host (`hostname -s`) with its cores.
#   scripts/slurm-fixture.sh start DIR   starts the daemons; waits until the node is idle
#   scripts/slurm-fixture.sh stop DIR    stops them (SIGTERM, then SIGKILL) and removes DIR
# Clients use it with SLURM_CONF=DIR/slurm.conf (its AuthInfo names DIR's munge socket).
# STOCHTEX_SKIP_SLURM=1: start exits 0 with a notice and writes DIR/skipped (the tests skip).
set -euo pipefail
action=${1:?usage: slurm-fixture.sh start|stop DIR}
dir=${2:?usage: slurm-fixture.sh start|stop DIR}

stop() {
  [ -d "$dir" ] || return 0
  local pids=() pid daemon
  for daemon in slurmd slurmctld munged; do
    [ -s "$dir/$daemon.pid" ] || continue
    pid=$(cat "$dir/$daemon.pid")
    # Only the daemon itself: a stale pid file's number may belong to another process by now.
    [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$daemon" ] && pids+=("$pid")
  done
  # All at once (each takes a moment to wind down), then whatever is left after 10 s.
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  rm -rf "$dir"
}

fail() {
  echo "slurm-fixture: $*" >&2
  for log in "$dir"/*.log; do [ -f "$log" ] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }; done
  stop
  exit 1
}

case "$action" in
stop) stop; exit 0 ;;
start) ;;
*) echo "slurm-fixture: unknown action '$action' (start or stop)" >&2; exit 2 ;;
esac

stop  # what an interrupted earlier run left behind
mkdir -p "$dir"
chmod 700 "$dir"
if [ "${STOCHTEX_SKIP_SLURM:-0}" = 1 ]; then
  echo "slurm-fixture: STOCHTEX_SKIP_SLURM=1: no cluster started; the Slurm tests skip"
  touch "$dir/skipped"
  exit 0
fi
for program in munged slurmctld slurmd sbatch sinfo; do
  command -v "$program" >/dev/null ||
    fail "$program not found: install slurm-wlm and munge (scripts/install-deps.sh), or set STOCHTEX_SKIP_SLURM=1 to skip the Slurm tests"
done
[ "$(id -u)" -eq 0 ] || fail "the daemons run as root here (SlurmUser=root); run the tests as root or set STOCHTEX_SKIP_SLURM=1"

dir=$(cd "$dir" && pwd)
node=$(hostname -s)
cpus=$(nproc)
# munge: its own key and socket, so a host munged (if any) is neither used nor disturbed.
dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge.key"
munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munged.seed" || fail "munged did not start"

mkdir -p "$dir/state" "$dir/spool"
# Two free ports unless given: two test runs on one machine (a developer's suite beside a lane's)
# met on Slurm's defaults 6817/6818, and the second cluster failed with "Address already in use".
if [ -z "${STOCHTEX_SLURMCTLD_PORT:-}" ] || [ -z "${STOCHTEX_SLURMD_PORT:-}" ]; then
  read -r STOCHTEX_SLURMCTLD_PORT STOCHTEX_SLURMD_PORT < <(python3 -c 'import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets:
    s.bind(("", 0))
print(*[s.getsockname()[1] for s in sockets])')
fi
cat > "$dir/slurm.conf" <<CONF
ClusterName=stochtex-test
SlurmctldHost=$node
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=$STOCHTEX_SLURMCTLD_PORT
SlurmdPort=$STOCHTEX_SLURMD_PORT
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
# Short timers: the tests cancel and resubmit, and wait for nothing else.
KillWait=2
MinJobAge=10
InactiveLimit=0
NodeName=$node CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 150); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -n 1 || true)
  case "$state" in idle|mix|alloc) echo "slurm-fixture: node $node ($cpus CPUs) $state; SLURM_CONF=$SLURM_CONF"; exit 0 ;; esac
  sleep 0.2
done
fail "the node did not become idle within 30 s (sinfo: '${state:-no answer}')"
