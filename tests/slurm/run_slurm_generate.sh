#!/usr/bin/env bash
# tests/slurm/run_slurm_generate.sh -- the real Slurm test of generation on
# a batch scheduler (docs/cluster.md), called by .ci/run.
#
# It starts a private single-node Slurm in a temporary folder (its own
# munged with its own key and socket, slurmctld and slurmd on free ports,
# state, spool and logs in that folder; nothing in /etc is read or
# changed, and a Slurm or munge already running on the machine is left
# alone), submits configs/data/tiny.yaml as 3 shards through
# scripts/slurm/submit_generate.sh (an array of 3 tasks, then the finalize
# job with --dependency=afterok), waits for both within a bound, then
# checks that every task and the finalize job succeeded, that the finalize
# job (not a task) wrote the dataset files, that `layers validate` passes,
# and that every file of the folder is byte for byte the file a single
# `layers generate` process writes for the same config.
# On exit it cancels its jobs, stops the daemons it started and removes
# the folder (LAYERS_SLURM_KEEP=1 keeps it); on failure it prints the
# job and daemon logs first.
#
# Runs as root (slurmd does); installs Debian's munge, slurmctld, slurmd
# and slurm-client when missing. The layers program is
# $LAYERS_BIN, else build/bin/layers of this checkout. The jobs' bound is
# $LAYERS_SLURM_TIMEOUT seconds (default 1200).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
layers="${LAYERS_BIN:-$repo/build/bin/layers}"
limit="${LAYERS_SLURM_TIMEOUT:-1200}"
shards=3
config="$repo/configs/data/tiny.yaml"
sets=(--set sequences_per_shard=2)  # tiny's 6 scenes as 3 shards of 2
start=$(date +%s)

say() { echo "slurm-test: $*"; }
failure=""
die() {
  failure="$*"
  echo "slurm-test: FAILED: $failure" >&2
  exit 1
}
elapsed() { echo $(($(date +%s) - start)); }

case "$layers" in /*) ;; *) layers="$PWD/$layers" ;; esac
[ -x "$layers" ] || die "$layers not found: build first (cmake --build build) or set LAYERS_BIN"
[[ "$limit" =~ ^[1-9][0-9]*$ ]] || die "LAYERS_SLURM_TIMEOUT: expected seconds >= 1, got '$limit'"

# --- Packages -----------------------------------------------------------
# slurmd runs jobs as their users, so it runs as root.
[ "$(id -u)" = 0 ] || die "this test starts slurmd and munged: run it as root"
export PATH="$PATH:/usr/sbin:/sbin"
tools=(munged mungekey munge unmunge slurmctld slurmd sbatch squeue scontrol scancel sinfo)
have_tools() {
  local t
  for t in "${tools[@]}"; do command -v "$t" >/dev/null 2>&1 || return 1; done
}
if ! have_tools; then
  packages=(munge slurmctld slurmd slurm-client)
  say "installing ${packages[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null ||
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null; } ||
    die "apt-get install ${packages[*]} failed"
  have_tools || die "after installing, one of ${tools[*]} is still missing"
fi
say "$(slurmctld -V), munge $(munged -V 2>&1 | head -1 | awk '{print $1}')"

# --- A private single-node cluster ---------------------------------------
cluster_start=$(date +%s)
work="$(mktemp -d "${TMPDIR:-/tmp}/layers-slurm.XXXXXX")"
chmod 755 "$work"  # munged wants every folder above its socket searchable
pids=()            # daemons this script started, stopped in this order
array_job="" finalize_job=""

print_logs() {
  local f
  for f in "$work"/logs/* "$work"/daemons/*.log; do
    [ -f "$f" ] || continue
    echo "----- $f (last 40 lines)" >&2
    tail -n 40 "$f" >&2
  done
}
cleanup() {
  local rc=$?
  trap - EXIT
  set +e
  if [ -n "$array_job" ] && [ ${#pids[@]} -gt 0 ]; then
    scancel "$array_job" ${finalize_job:+"$finalize_job"} 2>/dev/null
    for _ in $(seq 20); do
      [ -z "$(squeue -h -j "$array_job${finalize_job:+,$finalize_job}" -t PD,R,CG,CF,S 2>/dev/null)" ] && break
      sleep 0.5
    done
  fi
  if [ "$rc" != 0 ]; then
    print_logs
    [ -z "$failure" ] || echo "slurm-test: FAILED: $failure (logs above)" >&2
  fi
  local i
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null; done
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do wait "${pids[i]}" 2>/dev/null; done
  if [ "${LAYERS_SLURM_KEEP:-0}" = 1 ]; then echo "slurm-test: kept $work" >&2; else rm -rf "$work"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

mkdir -p "$work/munge" "$work/run" "$work/daemons" "$work/state" "$work/spool" "$work/logs"
chmod 700 "$work/munge"
chmod 755 "$work/run"
mungekey --create --keyfile="$work/munge/munge.key" || die "mungekey could not make a key"
socket="$work/run/munge.socket"
munged -F --socket="$socket" --key-file="$work/munge/munge.key" --pid-file="$work/run/munged.pid" \
  --seed-file="$work/munge/munged.seed" --log-file="$work/daemons/munged.log" >"$work/daemons/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do
  munge -S "$socket" -n 2>/dev/null | unmunge -S "$socket" >/dev/null 2>&1 && break
  sleep 0.2
done
munge -S "$socket" -n | unmunge -S "$socket" >/dev/null || die "munged did not start (see $work/daemons/munged.log)"

# A port nothing listens on (bash's /dev/tcp connects when something does).
free_port() {
  local p
  for _ in $(seq 100); do
    p=$((20000 + RANDOM % 20000))
    [ "$p" = "${1:-}" ] && continue
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then
      echo "$p"
      return
    fi
  done
  die "no free TCP port found for Slurm"
}
ctld_port="$(free_port)"
slurmd_port="$(free_port "$ctld_port")"
node="$(hostname -s)"
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<EOF
# Written by tests/slurm/run_slurm_generate.sh: one node, this machine.
ClusterName=layers-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/daemons/slurmctld.log
SlurmdLogFile=$work/daemons/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
MinJobAge=3600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=layers Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
# Jobs must not see an outer scheduler's variables.
unset SLURM_JOB_ID SLURM_ARRAY_TASK_ID SLURM_ARRAY_TASK_COUNT JOB_COMPLETION_INDEX LAYERS_SHARD_COUNT
slurmctld -D -f "$SLURM_CONF" >"$work/daemons/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >"$work/daemons/slurmd.out" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 120); do
  state="$(sinfo -h -n "$node" -o %T 2>/dev/null || true)"
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || die "the node did not come up idle within 60 s (state '${state:-none}')"
say "private Slurm up in $(($(date +%s) - cluster_start)) s: node $node, $(nproc) CPUs, ports $ctld_port/$slurmd_port, $work"

# --- The dataset through Slurm -------------------------------------------
out="$work/slurm/tiny"
jobs_start=$(date +%s)
ids="$(cd "$work" && LAYERS_BIN="$layers" bash "$repo/scripts/slurm/submit_generate.sh" --config "$config" \
  --shards "$shards" --cpus 1 --out "$out" "${sets[@]}" --logs "$work/logs")"
array_job="$(sed -n 's/^array_job=//p' <<<"$ids")"
finalize_job="$(sed -n 's/^finalize_job=//p' <<<"$ids")"
[[ "$array_job" =~ ^[0-9]+$ && "$finalize_job" =~ ^[0-9]+$ ]] || die "submit_generate.sh printed no job ids: $ids"
say "submitted array job $array_job ($shards tasks) and finalize job $finalize_job (afterok)"

deadline=$(($(date +%s) + limit))
while [ -n "$(squeue -h -j "$array_job,$finalize_job" -t PD,R,CG,CF,S -o %i)" ]; do
  if [ "$(date +%s)" -ge "$deadline" ]; then
    squeue -j "$array_job,$finalize_job" >&2 || true
    die "the jobs did not finish within ${limit} s (LAYERS_SLURM_TIMEOUT); cancelling them"
  fi
  sleep 2
done
jobs_seconds=$(($(date +%s) - jobs_start))

# Every task and the finalize job: COMPLETED with exit code 0.
records="$(scontrol -o show job "$array_job"; scontrol -o show job "$finalize_job")"
n_ok="$(grep -c 'JobState=COMPLETED .*ExitCode=0:0' <<<"$records" || true)"
if [ "$n_ok" != $((shards + 1)) ]; then
  grep -o 'JobId=[0-9]* ArrayJobId=[0-9]* ArrayTaskId=[0-9]*\|JobId=[0-9]* JobName=[^ ]*\|JobState=[A-Z_]*\|ExitCode=[0-9:]*' <<<"$records" >&2 || true
  die "expected $shards array tasks and the finalize job COMPLETED with exit code 0, got $n_ok"
fi
say "array and finalize jobs completed in $jobs_seconds s"

# Each task made its own shard and left the dataset files to the finalize job.
for k in $(seq 0 $((shards - 1))); do
  log="$work/logs/layers-generate-${array_job}_$k.out"
  grep -q "in shard $k/$shards:" "$log" || die "task $k's log ($log) does not say it made shard $k/$shards"
  grep -q "not finalized (--no-finalize)" "$log" || die "task $k's log does not say it left finalizing to the finalize job"
done
grep -q "dataset complete: $shards shards" "$work/logs/layers-finalize-$finalize_job.out" ||
  die "the finalize job's log does not say it completed the dataset"

# --- Checks ---------------------------------------------------------------
"$layers" validate "$out" >"$work/logs/validate.txt" 2>&1 || die "layers validate $out failed"
say "layers validate: $(tail -n 1 "$work/logs/validate.txt")"

single="$work/single/tiny"
single_start=$(date +%s)
"$layers" generate --config "$config" "${sets[@]}" --out "$single" --threads "$(nproc)" --quiet \
  >"$work/logs/single.txt" 2>&1 || die "the single-process layers generate failed"
say "single-process run in $(($(date +%s) - single_start)) s"

files="$(cd "$single" && find . -type f | sort)"
[ "$files" = "$(cd "$out" && find . -type f | sort)" ] ||
  die "the file lists differ: single $(tr '\n' ' ' <<<"$files"), slurm $(cd "$out" && find . -type f | sort | tr '\n' ' ')"
for f in dataset.yaml splits.yaml stats.h5 generator.yaml $(for j in $(seq 0 $((shards - 1))); do printf 'shard-%05d.h5 ' "$j"; done); do
  grep -qx "./$f" <<<"$files" || die "$f is missing from the dataset"
done
names=()
while IFS= read -r f; do
  cmp -s "$single/$f" "$out/$f" || die "$f differs between the Slurm run and the single-process run"
  names+=("${f#./}")
done <<<"$files"
say "passed: ${#names[@]} files byte for byte identical to the single-process run (${names[*]});" \
  "jobs $jobs_seconds s, total $(elapsed) s"
