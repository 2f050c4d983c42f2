#!/usr/bin/env bash
# scripts/quickstart.sh -- from a fresh machine to a report: install
# dependencies and build (scripts/setup.sh), then run the study
# configs/studies/compare_tiny.yaml: generate the `tiny` LAYERS dataset
# (simulated inner + outer garments on moving bodies), train every model of
# the zoo on it briefly (LayersNet, DeePSD, DeePSD+, MGNet; the static and
# skinned references need no training), evaluate them with rollouts, time
# them, and write a Markdown report with charts. Everything goes to
# runs/quickstart (override with LAYERS_QUICKSTART_OUT). Re-running skips
# every step that is current.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${LAYERS_QUICKSTART_OUT:-$root/runs/quickstart}"
bash "$root/scripts/setup.sh"
layers="${LAYERS_BUILD_DIR:-$root/build}/bin/layers"
mkdir -p "$out"

echo "== registered models"
"$layers" models

echo "== study configs/studies/compare_tiny.yaml -> $out"
"$layers" run "$root/configs/studies/compare_tiny.yaml" --set output="$out" --set dataset.folder="$out/data"

echo
echo "quickstart: done."
echo "  report:   $out/report/report.md (charts in $out/report/charts/)"
echo "  dataset:  $out/data (layers info / validate / export work on it)"
echo "  runs:     $out/<model>/ (checkpoints, eval-test/metrics.json, predictions.h5, bench.json)"
