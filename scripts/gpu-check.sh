#!/usr/bin/env bash
# scripts/gpu-check.sh -- build layers against a CUDA LibTorch on a machine
# with an NVIDIA GPU and check it there (docs/gpu.md):
#   1. the CUDA-only tests, which CPU builds skip (Losses.RunOnTheInputsDevice,
#      Skinned.FollowsTheModelToAnotherDevice): they must pass, not skip;
#   2. one short LayersNet training (and its evaluation) with run.device=cuda
#      on the tiny dataset (generated first if data/tiny is missing), and
#      with 2+ GPUs the same as 2 data-parallel ranks over NCCL;
#   3. LayersNet inference ms per frame at 2k, 8k and 32k garment vertices
#      (bench_layersnet with LAYERS_BENCH_DEVICE=cuda).
#
#   bash scripts/gpu-check.sh /path/to/libtorch            # the LibTorch archive (cxx11 ABI, CUDA)
#   bash scripts/gpu-check.sh "$(python3 -c 'import torch; print(torch.utils.cmake_prefix_path)')"
#
# The rest of the dependencies come from scripts/setup.sh's Debian packages.
# Builds into build-cuda/ (LAYERS_CUDA_BUILD_DIR); results in
# runs/gpu-check/ and a summary on stdout. Exit 0 when every check passed.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAYERS_CUDA_BUILD_DIR:-$root/build-cuda}"
out="$root/runs/gpu-check"
torch_prefix="${1:-${TORCH_PREFIX:-}}"

fail() { echo "gpu-check: $*" >&2; exit 1; }

command -v nvidia-smi >/dev/null || fail "no nvidia-smi: this machine has no NVIDIA driver (no GPU to check)"
gpus=$(nvidia-smi --query-gpu=name --format=csv,noheader | wc -l)
[ "$gpus" -ge 1 ] || fail "nvidia-smi lists no GPU"
[ -n "$torch_prefix" ] || fail "usage: bash scripts/gpu-check.sh <CUDA LibTorch folder or PyTorch's share/cmake prefix>"
[ -e "$torch_prefix/share/cmake/Torch/TorchConfig.cmake" ] || [ -e "$torch_prefix/Torch/TorchConfig.cmake" ] ||
  fail "$torch_prefix: no TorchConfig.cmake under share/cmake/Torch (or Torch/): not a LibTorch folder"
nvidia-smi --query-gpu=index,name,memory.total,driver_version --format=csv

echo "== build against $torch_prefix into $build"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$torch_prefix"
cmake --build "$build" -j "${LAYERS_JOBS:-$(nproc)}"
grep -q "LAYERS_DIST_NCCL" "$build/build.ninja" || echo "gpu-check: note: this LibTorch brings no CUDA libraries to CMake (TORCH_CUDA_LIBRARIES empty): data-parallel CUDA runs are refused"
mkdir -p "$out"
layers="$build/bin/layers"
summary="$out/summary.txt"
: > "$summary"

echo "== 1. CUDA-only tests"
run_cuda_test() {  # binary filter: must print PASSED, never SKIPPED
  local log="$out/$1.log"
  "$build/bin/$1" --gtest_filter="$2" > "$log" 2>&1 || { cat "$log"; fail "$1 $2 failed"; }
  grep -q "SKIPPED" "$log" && { cat "$log"; fail "$1 $2 was skipped: torch sees no CUDA device"; }
  grep -q "\[  PASSED  \] 1 test" "$log" || { cat "$log"; fail "$1 $2 did not run"; }
  echo "passed: $1 $2" | tee -a "$summary"
}
run_cuda_test test_losses Losses.RunOnTheInputsDevice
run_cuda_test test_skinned Skinned.FollowsTheModelToAnotherDevice

echo "== 2. a short LayersNet training on cuda"
cd "$root"
if [ ! -f data/tiny/dataset.yaml ]; then
  "$layers" generate --config configs/data/tiny.yaml --out data/tiny
fi
common=(--set run.device=cuda --set train.epochs=2 --set train.windows_per_epoch=64 --set run.threads=4)
"$layers" train configs/experiments/layersnet_tiny.yaml "${common[@]}" --set run.output="$out/layersnet" --force \
  --quiet | tee "$out/train.txt"
"$layers" eval configs/experiments/layersnet_tiny.yaml --set run.device=cuda --set run.output="$out/layersnet" \
  --quiet | tee "$out/eval.txt"
grep -E "frames/s" "$out/train.txt" | sed 's/^/train (1 GPU): /' | tee -a "$summary"
grep -E "^overall" "$out/eval.txt" | sed 's/^/eval: /' | tee -a "$summary"
if [ "$gpus" -ge 2 ]; then
  "$layers" launch --nproc 2 -- train configs/experiments/layersnet_tiny.yaml "${common[@]}" \
    --set run.output="$out/layersnet-2gpu" --force --quiet | tee "$out/train-2gpu.txt"
  grep -E "frames/s" "$out/train-2gpu.txt" | sed 's/^/train (2 GPUs, NCCL): /' | tee -a "$summary"
else
  echo "one GPU: the 2-rank NCCL training is not run" | tee -a "$summary"
fi

echo "== 3. LayersNet inference ms per frame at 2k, 8k, 32k garment vertices (cuda)"
LAYERS_BENCH_DEVICE=cuda "$build/bin/bench_layersnet" \
  --benchmark_filter='BM_LayersNetInference/vertices:(2000|8000|32000)/far_body:0' --benchmark_min_time=1 \
  --benchmark_format=console | tee "$out/bench.txt"
grep -E "^BM_LayersNetInference" "$out/bench.txt" | awk '{print "inference " $1 ": " $2 " " $3 " per frame"}' |
  tee -a "$summary"

echo "== summary ($summary)"
cat "$summary"
