#!/usr/bin/env bash
# scripts/slurm/submit_generate.sh -- submits a dataset's generation to
# Slurm (docs/cluster.md): an array job of n tasks running
# scripts/slurm/generate.sbatch (task k makes the shards j with
# j % n == k), then a finalize job that starts only if every task
# succeeded (--dependency=afterok:<array>, and is cancelled otherwise) and
# writes dataset.yaml, splits.yaml and stats.h5. Prints the two job ids as
# `array_job=<id>` and `finalize_job=<id>` lines.
#
#   scripts/slurm/submit_generate.sh --config configs/data/layers.yaml --shards 64 --cpus 4 \
#       [--out DIR] [--set key=value]... [--logs DIR] [-- more sbatch options, e.g. --partition=cpu]
#
# Relative paths are taken from the current folder. The jobs run
# $LAYERS_BIN, else `layers` on PATH, else this checkout's build/bin/layers.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() {
  echo "usage: $0 --config FILE --shards N [--out DIR] [--cpus C] [--set key=value]... [--logs DIR] [-- sbatch options]" >&2
  exit 2
}
absolute() { case "$1" in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$PWD/$1" ;; esac; }

config="" out="" shards="" cpus=1 logs="$PWD"
sets=() extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --config) [ $# -ge 2 ] || usage; config="$(absolute "$2")"; shift 2 ;;
    --out) [ $# -ge 2 ] || usage; out="$(absolute "$2")"; shift 2 ;;
    --shards) [ $# -ge 2 ] || usage; shards="$2"; shift 2 ;;
    --cpus) [ $# -ge 2 ] || usage; cpus="$2"; shift 2 ;;
    --set) [ $# -ge 2 ] || usage; sets+=(--set "$2"); shift 2 ;;
    --logs) [ $# -ge 2 ] || usage; logs="$(absolute "$2")"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "submit_generate: unknown option '$1'" >&2; usage ;;
  esac
done
[ -n "$config" ] || { echo "submit_generate: --config: expected a generator config, got nothing" >&2; exit 2; }
[ -f "$config" ] || { echo "submit_generate: --config: expected an existing file, got '$config'" >&2; exit 2; }
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || { echo "submit_generate: --shards: expected a whole number >= 1, got '$shards'" >&2; exit 2; }
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || { echo "submit_generate: --cpus: expected a whole number >= 1, got '$cpus'" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "submit_generate: sbatch not found: run this on a Slurm submit host" >&2; exit 1; }

if [ -z "${LAYERS_BIN:-}" ]; then
  if command -v layers >/dev/null; then LAYERS_BIN="$(command -v layers)"
  elif [ -x "$here/../../build/bin/layers" ]; then LAYERS_BIN="$(cd "$here/../../build/bin" && pwd)/layers"
  else echo "submit_generate: layers not found: set LAYERS_BIN, put it on PATH or build this checkout" >&2; exit 1
  fi
fi
mkdir -p "$logs"
generate_args=(--config "$config")
if [ -n "$out" ]; then generate_args+=(--out "$out"); fi
generate_args+=("${sets[@]}")
common=(--chdir="$PWD" --export="ALL,LAYERS_BIN=$LAYERS_BIN" "${extra[@]}")

array_job="$(sbatch --parsable "${common[@]}" --job-name=layers-generate --array="0-$((shards - 1))" \
  --cpus-per-task="$cpus" --output="$logs/layers-generate-%A_%a.out" \
  "$here/generate.sbatch" "${generate_args[@]}")"
array_job="${array_job%%;*}"  # --parsable gives id[;cluster]
finalize_job="$(sbatch --parsable "${common[@]}" --job-name=layers-finalize --cpus-per-task=1 \
  --dependency="afterok:$array_job" --kill-on-invalid-dep=yes --output="$logs/layers-finalize-%j.out" \
  "$here/generate.sbatch" --finalize "${generate_args[@]}")"
finalize_job="${finalize_job%%;*}"
echo "array_job=$array_job"
echo "finalize_job=$finalize_job"
