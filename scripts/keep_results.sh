#!/usr/bin/env bash
# scripts/keep_results.sh -- copy what a study's report is made of out of
# its output folder into a folder kept with the repository (docs/results/),
# without checkpoints, predictions or the picture's point data (the
# report's charts/frames_*.dat, megabytes; frames.png stays) or the
# viewer (report/viewer/, up to 9.5 MB; `layers report` rebuilds it where
# the predictions are): every run's
# experiment.yaml, selection.json, bench.json, lane.log and
# eval-*/metrics.json, the
# study's steps.yaml and report/ (Markdown, CSV, JSON, charts), and the
# dataset's dataset.yaml (its per-sequence content hashes say which data
# the figures are on). `layers report --runs <dest>/<run> ...` rebuilds a
# report from the copy, so runs of later sessions can join it.
#
#   bash scripts/keep_results.sh runs/table9_small docs/results/table9_small [data/small]
#
# Refuses (exit 1) to write into a destination that exists: nothing kept
# is overwritten. Exit 2 on usage errors.
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: keep_results.sh STUDY_OUTPUT DEST [DATASET_FOLDER]" >&2
  exit 2
fi
src="$1"
dest="$2"
data="${3:-}"
if [ ! -d "$src" ]; then
  echo "keep_results: $src: expected a study output folder, got no such folder" >&2
  exit 1
fi
if [ -e "$dest" ]; then
  echo "keep_results: $dest: expected a new folder, got one that exists (kept results are never overwritten)" >&2
  exit 1
fi
if [ -n "$data" ] && [ ! -f "$data/dataset.yaml" ]; then
  echo "keep_results: $data/dataset.yaml: expected the dataset's description, got no such file" >&2
  exit 1
fi

tmp="$(mkdir -p "$(dirname "$dest")" && cd "$(dirname "$dest")" && pwd)/$(basename "$dest").tmp-$$"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp"
# The result files, copied with their paths below the study folder.
(cd "$src" && find . -type f \( -name experiment.yaml -o -name selection.json -o -name bench.json \
  -o -name lane.log -o -name steps.yaml -o -path '*/eval-*/metrics.json' -o -path './report/*' \) \
  ! -name '*.pt' ! -name '*.h5' ! -name 'frames_*.dat' ! -path './report/viewer/*' -exec cp -p --parents -t "$tmp" {} +)
copied="$(find "$tmp" -type f | wc -l)"
if [ "$copied" -eq 0 ]; then
  echo "keep_results: $src: expected runs or a report, got no result files" >&2
  exit 1
fi
[ -n "$data" ] && cp -p "$data/dataset.yaml" "$tmp/dataset.yaml"
mv "$tmp" "$dest"
trap - EXIT
echo "keep_results: $copied files from $src kept in $dest"
