#!/usr/bin/env bash
# The render farm end to end: starts a private one-node Slurm cluster on this machine (its own
# munged, slurmctld and slurmd, every file in a temporary folder, free ports), renders the 40-frame
# orbit of tests/farm/orbit.lua as a 4-task job array through scripts/farm/submit, and checks that
# every frame is byte-identical to a local render of the whole orbit. The daemons are always
# stopped (trap), also on failure or timeout; a watchdog stops them if this script is killed.
#
# Usage: farm_test.sh VDG SOURCE_DIR WORK_DIR
# Needs root (slurmd runs the jobs as the submitting user) and the slurm-wlm and munge packages
# (scripts/install-deps). Without them it skips (exit 77), or fails when VDG_REQUIRE_SLURM=1
# (make test sets it, as install-deps installs them).
set -euo pipefail

[ $# -eq 3 ] || {
  echo "usage: farm_test.sh VDG SOURCE_DIR WORK_DIR" >&2
  exit 2
}
vdg=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
source_dir=$(cd "$2" && pwd)
work=$3
kFrames=40         # frames of the orbit: 0-39
kTasks=4           # array tasks
kStartSeconds=60   # for the cluster to come up (a few seconds)
kJobSeconds=150    # for the job array to end (about 10 s; a minute under ASan on a loaded machine)
export PATH=$PATH:/usr/sbin:/sbin  # munged, slurmctld, slurmd

skip_or_fail() {
  if [ "${VDG_REQUIRE_SLURM:-0}" = 1 ]; then
    echo "FAIL: $* (VDG_REQUIRE_SLURM=1: this test must run, not skip)" >&2
    exit 1
  fi
  echo "SKIP: $*" >&2
  exit 77
}
for c in munged slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
  command -v "$c" >/dev/null || skip_or_fail "$c not found (scripts/install-deps installs the Debian packages slurm-wlm and munge)"
done
[ "$(id -u)" -eq 0 ] || skip_or_fail "the one-node Slurm cluster needs root (slurmd runs jobs as their user)"
command -v python3 >/dev/null || skip_or_fail "python3 not found (to pick free ports)"

# The cluster's files live in a short /tmp path (munge's socket path must fit in 108 bytes); the
# frames and job logs in WORK_DIR.
rm -rf "$work"
mkdir -p "$work"
cluster=$(mktemp -d /tmp/vdg-farm.XXXXXX)
mkdir -p "$cluster/state" "$cluster/spool"
watchdog_pid=""

log_tails() {
  # slurmctld and slurmd write their log to stderr too (-D): the .out files also hold the errors
  # of a configuration they could not read.
  for f in "$cluster/munged.log" "$cluster/slurmctld.out" "$cluster/slurmd.out"; do
    [ -e "$f" ] || continue
    echo "---- last lines of $f" >&2
    tail -n 25 "$f" >&2
  done
}

# Stops a daemon by its pid file: TERM, then KILL after 5 s.
stop_daemon() {
  local pid_file=$1 pid
  [ -s "$pid_file" ] || return 0
  pid=$(cat "$pid_file")
  kill -TERM "$pid" 2>/dev/null || return 0
  for _ in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  echo "farm_test: $(basename "$pid_file" .pid) (pid $pid) did not stop on TERM: KILL" >&2
  kill -KILL "$pid" 2>/dev/null || true
}

stop_cluster() {
  local status=$?
  set +e
  trap - EXIT INT TERM
  trap '' PIPE  # a closed stdout (| head) must not end the clean-up half-way
  if [ -n "${SLURM_CONF:-}" ]; then
    # Every job of this private cluster is this test's; let slurmd end their steps before it stops.
    scancel --partition=farm 2>/dev/null
    for _ in $(seq 50); do
      [ -z "$(squeue -h 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  stop_daemon "$cluster/submit.pid"
  stop_daemon "$cluster/slurmd.pid"
  stop_daemon "$cluster/slurmctld.pid"
  stop_daemon "$cluster/munged.pid"
  [ -z "$watchdog_pid" ] || kill "$watchdog_pid" 2>/dev/null
  if [ "$status" -ne 0 ]; then
    log_tails
  fi
  rm -rf "$cluster"
  exit "$status"
}
trap stop_cluster EXIT
trap 'exit 1' INT TERM

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# ctest kills a test past its TIMEOUT with SIGKILL, which no trap sees: a watchdog in its own
# session stops the daemons when this script's process is gone.
# shellcheck disable=SC2016  # the watchdog's own script, expanded by the bash that runs it
setsid bash -c '
  while kill -0 "$1" 2>/dev/null; do sleep 1; done
  for d in submit slurmd slurmctld munged; do
    [ -s "$2/$d.pid" ] && kill -TERM "$(cat "$2/$d.pid")" 2>/dev/null
  done
  sleep 2
  rm -rf "$2"' farm-watchdog $$ "$cluster" </dev/null >/dev/null 2>&1 &
watchdog_pid=$!

# --- munge: its own key and socket, not the system's (/etc/munge, /run/munge)
dd if=/dev/urandom of="$cluster/munge.key" bs=1024 count=1 status=none
chmod 400 "$cluster/munge.key"
munge_socket=$cluster/munge.socket
munged --force --key-file="$cluster/munge.key" --socket="$munge_socket" \
  --pid-file="$cluster/munged.pid" --log-file="$cluster/munged.log" \
  --seed-file="$cluster/munged.seed" || fail "munged did not start"

# --- slurm.conf: one node named after this host, with 2 CPUs, on free local ports
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
node=$(hostname -s)
cat >"$cluster/slurm.conf" <<CONF
ClusterName=vdgfarm
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge_socket
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/slurmctld.log
SlurmdLogFile=$cluster/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=300
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=farm Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$cluster/slurm.conf

# -D: in the foreground (no systemd here); they write their pid files all the same.
slurmctld -D -i -f "$SLURM_CONF" >"$cluster/slurmctld.out" 2>&1 &
slurmctld_pid=$!
slurmd -D -N "$node" -f "$SLURM_CONF" >"$cluster/slurmd.out" 2>&1 &
slurmd_pid=$!

# Wait for the node to be idle; a daemon that exits fails the test at once.
deadline=$((SECONDS + kStartSeconds))
until [ "$(sinfo -h -n "$node" -o %T 2>/dev/null)" = idle ]; do
  kill -0 "$slurmctld_pid" 2>/dev/null || fail "slurmctld exited while the cluster started (its log below)"
  kill -0 "$slurmd_pid" 2>/dev/null || fail "slurmd exited while the cluster started (its log below)"
  [ "$SECONDS" -lt "$deadline" ] ||
    fail "the one-node cluster did not come up within ${kStartSeconds} s (node state: '$(sinfo -h -n "$node" -o %T 2>&1)')"
  sleep 0.2
done

# --- the orbit on the farm, 4 tasks of 10 frames run in WORK_DIR, and meanwhile locally. submit
# --wait returns when every task has ended, with status 0 only when every task's was 0; it runs in
# the background with its pid in a pid file, so that the clean-up and the watchdog stop it too.
cd "$work"
timeout "$kJobSeconds" "$source_dir/scripts/farm/submit" --frames "0-$((kFrames - 1))" \
  --tasks "$kTasks" --vdg "$vdg" --sbatch "--output=$work/task-%a.log" --wait -- \
  run "$source_dir/tests/farm/orbit.lua" --root "$source_dir" -o "$work/farm" --quiet \
  >"$work/job_id" &
submit_pid=$!
echo "$submit_pid" >"$cluster/submit.pid"
"$vdg" run "$source_dir/tests/farm/orbit.lua" --root "$source_dir" -o "$work/local" --quiet ||
  fail "the local render failed"
submit_status=0
wait "$submit_pid" || submit_status=$?
job_id=$(head -n 1 "$work/job_id")
job_id=${job_id%%;*}
show_task_logs() {
  for f in "$work"/task-*.log; do
    [ -e "$f" ] || continue
    echo "---- $f" >&2
    cat "$f" >&2
  done
}
if [ "$submit_status" -eq 124 ]; then
  squeue >&2
  fail "the job array did not end within ${kJobSeconds} s"
fi
[[ $job_id =~ ^[0-9]+$ ]] || fail "submit printed '$job_id', not a job id (exit status $submit_status)"
if [ "$submit_status" -ne 0 ]; then
  show_task_logs
  fail "submit --wait: exit status $submit_status (a task failed)"
fi

# Every task ended COMPLETED with exit code 0 (the controller keeps ended jobs MinJobAge seconds).
states=$(scontrol -o show job "$job_id" | grep -o 'JobState=[A-Z_]* .* ExitCode=[0-9:]*' |
  sed -E 's/JobState=([A-Z_]+) .* ExitCode=([0-9:]+)/\1 \2/')
tasks_done=$(grep -c '^COMPLETED 0:0$' <<<"$states" || true)
if [ "$tasks_done" -ne "$kTasks" ]; then
  show_task_logs
  fail "$tasks_done of $kTasks array tasks completed (state and exit code of each: $(tr '\n' ',' <<<"$states"))"
fi

# Every frame of the farm is byte-identical to the local one, and there are no others.
local_count=$(find "$work/local/orbit" -name 'frame_*.png' | wc -l)
farm_count=$(find "$work/farm/orbit" -name 'frame_*.png' 2>/dev/null | wc -l)
[ "$local_count" -eq "$kFrames" ] || fail "the local render wrote $local_count frames, not $kFrames"
[ "$farm_count" -eq "$kFrames" ] || fail "the farm wrote $farm_count frames, not $kFrames"
for ((f = 0; f < kFrames; ++f)); do
  printf -v name 'frame_%04d.png' "$f"
  cmp "$work/local/orbit/$name" "$work/farm/orbit/$name" ||
    fail "$name rendered on the farm differs from the local render"
done
# Different frames really differ: a farm that wrote one frame 40 times would not pass.
cmp -s "$work/local/orbit/frame_0000.png" "$work/local/orbit/frame_0010.png" &&
  fail "frames 0 and 10 of the orbit are identical: the test scene does not move"
echo "farm_test: $kFrames frames from $kTasks array tasks (job $job_id) match the local render"
