#!/usr/bin/env bash
# scripts/quickstart.sh -- from a fresh machine to the main job on the
# embedded default: install dependencies and build (scripts/setup.sh), then
# run what the toolkit can do today on a small dataset it makes, and say
# where the results are. Output goes to runs/quickstart (override with
# LAYERS_QUICKSTART_OUT).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${LAYERS_QUICKSTART_OUT:-$root/runs/quickstart}"
bash "$root/scripts/setup.sh"
layers="${LAYERS_BUILD_DIR:-$root/build}/bin/layers"
mkdir -p "$out"

echo "== registered models"
"$layers" models

echo "== resolved default config"
"$layers" config "$root/configs/default.yaml" --out "$out/config.yaml"

echo
echo "quickstart: done; resolved config in $out/config.yaml"
echo "Not built yet: the dataset generator (issues 2-3 of docs/roadmap.md), training,"
echo "evaluation and reports. This script grows into generate -> train -> evaluate -> report."
