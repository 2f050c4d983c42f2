#!/usr/bin/env bash
# scripts/quickstart.sh -- from a fresh machine to the main job on the
# embedded default: install dependencies and build (scripts/setup.sh),
# generate the `tiny` LAYERS dataset (simulated inner + outer garments on
# moving bodies), check it, train LayersNet on it briefly, evaluate it
# beside the `static` and `skinned` reference models, and print the
# comparison. Everything goes to runs/quickstart (override with
# LAYERS_QUICKSTART_OUT). Re-running reuses the generated dataset.
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

echo "== registered models"
"$layers" models

for model in layersnet static skinned; do
  exp="$root/configs/experiments/${model}_tiny.yaml"
  echo "== train and evaluate $model ($exp)"
  "$layers" train "$exp" --set data.dataset="$out/data" --set run.output="$out/$model"
  "$layers" eval "$exp" --set data.dataset="$out/data" --set run.output="$out/$model"
done

first=$("$layers" info "$out/data" | awk '/^  seq-/{print $1; exit}')
echo "== export LayersNet's rollout of $first for Blender (PC2 point caches + OBJ meshes)"
"$layers" rollout "$root/configs/experiments/layersnet_tiny.yaml" --set data.dataset="$out/data" \
  --set run.output="$out/layersnet" --sequence "$first" --out "$out/rollout" --export pc2

echo
echo "quickstart: done."
echo "  dataset:     $out/data"
for model in layersnet static skinned; do
  echo "  $model: checkpoints in $out/$model, metrics in $out/$model/eval-test/metrics.json"
done
echo "  rollout:     $out/rollout (predictions.h5, pc2/ for Blender)"
