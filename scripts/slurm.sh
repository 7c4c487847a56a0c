#!/usr/bin/env bash
# Ensembles on a real single-node Slurm (issue 51). Installs Debian's Slurm and munge when they
# are missing, starts munge, slurmctld and slurmd on a slurm.conf of its own (in a temporary
# directory, on free ports), then runs the recipe of docs/book/src/distributed.md, which is the
# files in scripts/slurm/ (checked to be the chapter's copies, byte for byte):
#   1. the pendulum ensemble of examples/monte_carlo.rs as a job array of 3 shards with a
#      dependent merge, whose pendulum.csv and .png must equal a one-process run's byte for byte;
#   2. the same with one array task cancelled by scancel: Slurm must cancel the merge, a merge of
#      the files there must refuse naming the missing shard, and running that shard again alone
#      (`sbatch --array=1`) must give the one-process result again.
# Then the same binary under another driver (xargs, 4 shards). Tears the daemons down on any
# exit. Everything runs under timeouts (the inner ones --foreground: in this script's process
# group, so that the outer one's signal reaches what they run); a failure prints Slurm's logs and
# the jobs' output.
# Run as root (CI is); works without systemd. Writes out/slurm/ and target/slurm/.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${ODYN_SLURM_TIMED:-}" ]; then
  # The whole script, a first release build of the example (minutes) included.
  # A minute more before KILL, for the teardown.
  ODYN_SLURM_TIMED=1 exec timeout -k 60 1500 bash "$0" "$@"
fi
start=$SECONDS
log() { echo "slurm: $*"; }
fail() {
  echo "slurm: $*" >&2
  exit 1
}

# The recipe the chapter shows is these files.
python3 - docs/book/src/distributed.md scripts/slurm/{submit.sh,shard.sbatch,merge.sbatch} << 'EOF'
import sys
chapter = open(sys.argv[1]).read()
for path in sys.argv[2:]:
    if "```sh\n" + open(path).read() + "```\n" not in chapter:
        sys.exit(f"slurm: {path} differs from its copy in {sys.argv[1]}")
EOF

if ! command -v slurmctld > /dev/null || ! command -v slurmd > /dev/null \
  || ! command -v sbatch > /dev/null || ! command -v munged > /dev/null; then
  log "installing Debian's slurmctld, slurmd, slurm-client and munge"
  packages=(slurmctld slurmd slurm-client munge)
  export DEBIAN_FRONTEND=noninteractive
  timeout --foreground 600 apt-get install -y -q "${packages[@]}" > /dev/null \
    || { timeout --foreground 300 apt-get update -q > /dev/null \
      && timeout --foreground 600 apt-get install -y -q "${packages[@]}" > /dev/null; }
fi

# The cluster's files: configuration, state, daemons' logs.
tmp=$(mktemp -d /tmp/odyn-slurm.XXXXXX)
out=target/slurm
rm -rf out/slurm "$out"
mkdir -p "$out"
ctld='' slurmd_pid='' munge_started=''
teardown() {
  local status=$?
  set +e
  if [ -n "$ctld" ]; then
    if [ "$status" -ne 0 ]; then
      echo "slurm: failed; the queue, the daemons' logs and the jobs' output follow" >&2
      timeout --foreground 5 squeue >&2
      tail -n 30 "$tmp"/slurmctld.log "$tmp"/slurmd.log >&2
      tail -n 20 out/slurm/*.log >&2
    fi
    timeout --foreground 5 scancel --quiet --full --user=root
    for _ in $(seq 50); do
      [ -z "$(timeout --foreground 5 squeue -h 2> /dev/null)" ] && break
      sleep 0.2
    done
  fi
  for pid in $slurmd_pid $ctld; do
    kill "$pid" 2> /dev/null && wait "$pid"
  done
  [ -n "$munge_started" ] && service munge stop > /dev/null
  rm -rf "$tmp"
  exit "$status"
}
trap teardown EXIT
trap 'exit 143' TERM INT

if ! munge -n > /dev/null 2>&1; then
  service munge start > /dev/null
  munge_started=1
fi
munge -n | unmunge > /dev/null || fail "munge does not answer"

read -r ctld_port slurmd_port < <(python3 -c '
import socket
ports = []
for _ in range(2):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    ports.append(s)
print(*(s.getsockname()[1] for s in ports))')
mkdir -p "$tmp/state" "$tmp/spool"
export SLURM_CONF=$tmp/slurm.conf
cat > "$SLURM_CONF" << EOF
ClusterName=odyn
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=odyn NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=odyn Default=YES MaxTime=INFINITE State=UP
EOF
# Each in a session of its own: a signal to this script's process group (a timeout, Ctrl-C)
# leaves them to the teardown, which cancels the jobs first.
setsid slurmctld -D > /dev/null 2>&1 &
ctld=$!
setsid slurmd -D -N odyn > /dev/null 2>&1 &
slurmd_pid=$!
for _ in $(seq 100); do
  [ "$(sinfo -h -N -o %t 2> /dev/null)" = idle ] && break
  kill -0 "$ctld" 2> /dev/null && kill -0 "$slurmd_pid" 2> /dev/null || fail "a daemon stopped"
  sleep 0.2
done
[ "$(sinfo -h -N -o %t)" = idle ] || fail "the node is not idle: $(sinfo -N)"
log "single-node cluster up ($(sinfo -h -o '%c CPUs, Slurm') $(sinfo -V | cut -d' ' -f2))"

build=$SECONDS
timeout --foreground 1200 cargo build -q --release --example monte_carlo
log "example built in release in $((SECONDS - build)) s"
bin=target/release/examples/monte_carlo
"$bin" --members 1000 --seed 1 --out "$out/one" > "$out/one.txt"
same_as_one_process() {
  for file in pendulum.csv pendulum.png; do
    cmp "out/slurm/$file" "$out/one/$file" || fail "$1: $file differs from the one-process run"
  done
}

# 1. Three shards and their merge.
phase=$SECONDS
timeout --foreground 300 sh scripts/slurm/submit.sh 3 > "$out/submit.txt" 2>&1 \
  || fail "the ensemble failed: $(cat "$out/submit.txt")"
same_as_one_process "3 array tasks merged"
log "3 array tasks and a dependent merge: pendulum.csv and .png byte-identical with one" \
  "process ($((SECONDS - phase)) s)"

# 2. One task cancelled: the partition is down while the array is submitted, so that scancel
# takes task 1 before it runs (a task killed while running leaves no file either: files appear
# by rename, whole).
phase=$SECONDS
rm -f out/slurm/pendulum*
scontrol update PartitionName=debug State=DOWN
timeout --foreground 300 sh scripts/slurm/submit.sh 3 > "$out/fault.txt" 2>&1 &
submit=$!
array=''
for _ in $(seq 300); do
  array=$(squeue -h -n pendulum-shard -o %F | head -n 1)
  [ -n "$array" ] && break
  sleep 0.1
done
[ -n "$array" ] || fail "the array was not submitted: $(cat "$out/fault.txt")"
# The merge is submitted right after the array; cancel once it is queued, so that Slurm's
# answer to the failed dependency is what is tested.
for _ in $(seq 100); do
  [ -n "$(squeue -h -n pendulum-merge)" ] && break
  sleep 0.1
done
scancel "${array}_1"
scontrol update PartitionName=debug State=UP
if wait "$submit"; then
  fail "the ensemble with task 1 cancelled succeeded: $(cat "$out/fault.txt")"
fi
grep -q 'JobState=CANCELLED Reason=DependencyNeverSatisfied' "$out/fault.txt" \
  || fail "Slurm did not cancel the merge: $(cat "$out/fault.txt")"
[ ! -e out/slurm/pendulum-shard-1-of-3.csv ] && [ ! -e out/slurm/pendulum.csv ] \
  || fail "files of a cancelled task or merge: $(ls out/slurm)"
log "task ${array}_1 cancelled: Slurm cancelled the dependent merge (DependencyNeverSatisfied)"
# A merge of the shards there once the others have ended (afterany) refuses, naming the missing
# one.
if merge=$(timeout --foreground 120 sbatch --parsable --wait --dependency="afterany:$array" \
  scripts/slurm/merge.sbatch 3); then
  fail "a merge without shard 1 succeeded"
fi
refusal=$(cat "out/slurm/merge-$merge.log")
grep -q 'shard 1/3 (members 333 … 665) is missing' <<< "$refusal" \
  || fail "the merge without shard 1 did not name it: $refusal"
log "the merge without it exits 1: ${refusal#error: }"
timeout --foreground 300 sh scripts/slurm/submit.sh 3 1 > "$out/requeue.txt" 2>&1 \
  || fail "shard 1 run again failed: $(cat "$out/requeue.txt")"
same_as_one_process "shard 1 run again and merged"
log "shard 1 run again alone (sbatch --array=1) and merged: byte-identical again" \
  "($((SECONDS - phase)) s)"

# 3. The same binary under another driver: 4 shards by xargs, no scheduler.
mkdir -p "$out/xargs"
seq 0 3 | timeout --foreground 120 xargs -P 2 -I{} \
  "$bin" --members 1000 --seed 1 --out "$out/xargs" --shard {}/4 > /dev/null
timeout --foreground 120 "$bin" --out "$out/xargs" \
  --merge "$out"/xargs/pendulum-shard-*-of-4.csv > /dev/null
cmp "$out/xargs/pendulum.csv" "$out/one/pendulum.csv" || fail "4 shards by xargs differ"
log "4 shards by xargs merged: byte-identical too"
log "all checks passed in $((SECONDS - start)) s"
