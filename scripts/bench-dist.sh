#!/usr/bin/env bash
# scripts/bench-dist.sh -- data-parallel training throughput on this
# machine (docs/benchmarks.md "Data-parallel training"): one epoch of the
# same windows trained by 1 process and by 2 ranks (`layers launch`), one
# run after the other with the same inputs, as a Markdown table of
# predicted frames per second (all ranks together) and the share of the
# epoch spent in the gradient exchange (all-reduce, waiting included).
#
#   bash scripts/bench-dist.sh [experiment.yaml] [windows] [batch]
#     defaults: configs/experiments/layersnet_tiny.yaml, 96 windows, batch 4
# Rows: 1 process at batch B; 2 ranks at batch B/2 each (the same steps:
# N ranks x b == 1 x N b); 2 ranks at batch B each (twice the windows per step);
# and 1 process at batch B with twice the experiment's torch threads (the
# other way to use the second rank's cores).
# Needs the experiment's dataset (data/tiny: layers generate --config
# configs/data/tiny.yaml). Writes into runs/bench-dist/.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
layers="${LAYERS:-$root/build/bin/layers}"
experiment="${1:-configs/experiments/layersnet_tiny.yaml}"
windows="${2:-96}"
batch="${3:-4}"
out="${LAYERS_BENCH_OUT:-runs/bench-dist}"
half=$((batch / 2))
[ "$half" -ge 1 ] || { echo "bench-dist: batch must be at least 2" >&2; exit 2; }

# One epoch, no curriculum step, validation of one short sequence (not timed).
common=(--quiet --force --set train.epochs=1 --set train.windows_per_epoch="$windows" --set train.val_sequences=1
        --set train.val_horizon=2)

threads=$("$layers" config "$experiment" | sed -nE 's/^ *threads: *([0-9]+).*/\1/p' | head -n 1)
threads=${threads:-1}

row() {  # label nproc batch [threads]
  local label=$1 nproc=$2 b=$3 t=${4:-$threads} log="$out/$1.log"
  mkdir -p "$out"
  if [ "$nproc" -eq 1 ]; then
    "$layers" train "$experiment" "${common[@]}" --set train.batch_size="$b" --set run.output="$out/$label" \
      --set run.threads="$t" > "$log"
  else
    "$layers" launch --nproc "$nproc" -- train "$experiment" "${common[@]}" --set train.batch_size="$b" \
      --set run.output="$out/$label" > "$log"
  fi
  local line fps secs comm
  line=$(grep -E "^  epoch 1:" "$log")
  fps=$(sed -E 's/.* ([0-9.]+) frames\/s.*/\1/' <<< "$line")
  secs=$(sed -E 's/.*frames\/s  ([0-9.]+) s.*/\1/' <<< "$line")
  comm=$(grep -oE "[0-9]+% in gradient exchange" <<< "$line" | cut -d% -f1 || true)
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$nproc" "$t" "$b" "$((nproc * b))" "$fps" "$secs" "${comm:-0}%"
}

echo "experiment $experiment, $windows windows (one epoch), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| processes | threads per rank | batch per rank | windows per step | frames/s (all ranks) | epoch s | in gradient exchange |"
echo "|---|---|---|---|---|---|---|"
row one-b"$batch" 1 "$batch"
row two-b"$half" 2 "$half"
row two-b"$batch" 2 "$batch"
row one-b"$batch"-t$((2 * threads)) 1 "$batch" $((2 * threads))
