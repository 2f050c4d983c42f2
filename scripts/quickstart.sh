#!/usr/bin/env bash
# scripts/quickstart.sh -- from a fresh machine to the main job on the
# embedded default: install dependencies and build (scripts/setup.sh),
# generate the `tiny` LAYERS dataset (simulated inner + outer garments on
# moving bodies), check it, and export a sequence for Blender. Training,
# evaluation and reports join this script as they are built. Output goes
# to runs/quickstart (override with LAYERS_QUICKSTART_OUT). Re-running
# reuses what is already generated.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${LAYERS_QUICKSTART_OUT:-$root/runs/quickstart}"
bash "$root/scripts/setup.sh"
layers="${LAYERS_BUILD_DIR:-$root/build}/bin/layers"
mkdir -p "$out"

echo "== generate the tiny dataset ($root/configs/data/tiny.yaml)"
"$layers" generate --config "$root/configs/data/tiny.yaml" --out "$out/data" --threads "$(nproc)"

echo "== check it"
"$layers" validate "$out/data"
"$layers" info "$out/data"

first=$("$layers" info "$out/data" | awk '/^  seq-/{print $1; exit}')
if [ -n "$first" ]; then
  echo "== export $first for Blender (PC2 point caches + OBJ meshes)"
  "$layers" export "$out/data" "$first" --format pc2 --out "$out/export"
fi

echo "== registered models"
"$layers" models

echo
echo "quickstart: done. Dataset in $out/data (layers info / validate / export work on it),"
echo "Blender files in $out/export."
echo "Not built yet: training, evaluation and the report (see README, Status)."
