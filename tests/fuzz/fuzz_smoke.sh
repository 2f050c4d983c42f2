#!/usr/bin/env bash
# tests/fuzz/fuzz_smoke.sh -- the fuzz smoke test of ctest: each reader
# (BVH, YAML, LAYERS-H5, and the importers: OBJ, PLY, STL, GLB, garment
# side files, PC2) on a few hundred mutants of a seed with a fixed RNG
# seed, after every kept finding in tests/fuzz/regressions/.
#   fuzz_smoke.sh <layers_fuzz> <layers> <source dir> [iterations] [rng seed]
# With LAYERS_FUZZ_KEEP=<dir>, a finding (or the input a reader crashed
# on) is copied there as seed<rng seed>-<name> before the work folder goes.
set -euo pipefail
fuzz="$1"; layers="$2"; src="$3"; n="${4:-300}"; seed="${5:-1}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# Seeds: the first 40 frames of a shipped CMU clip, a resolved experiment
# and generator config, and a 3-frame body-only shard made by the real
# writer.
clip="$src/assets/motions/cmu/131_01_start_walk_stop.bvh"
{ sed '/^MOTION/q' "$clip"; echo "Frames: 40"; grep -m1 '^Frame Time' "$clip";
  sed -n '/^Frame Time/,$p' "$clip" | sed -n '2,41p'; } > "$work/seed.bvh"
"$layers" config "$src/configs/experiments/layersnet_tiny.yaml" --out "$work/seed.yaml" > /dev/null
"$layers" config "$src/configs/data/tiny.yaml" --out "$work/generator.yaml" > /dev/null
"$layers" --log-level warn body --motion procedural:walk --frames 3 --transition 1 --out "$work/seed.h5" > /dev/null
status=0
for kind in bvh yaml h5; do
  mapfile -t kept < <(find "$src/tests/fuzz/regressions" -name "*.$kind" -type f | sort)
  "$fuzz" "$kind" "$work/seed.$kind" "$n" "$seed" "$work/$kind" "${kept[@]}" || status=1
done
"$fuzz" yaml "$work/generator.yaml" "$n" "$seed" "$work/generator" || status=1
# The importers of users' garments and mesh sequences, from the fuzzer's
# own seeds (a small tube as OBJ, binary PLY and STL, GLB, a side file, a
# PC2 cache).
for kind in obj ply stl glb side pc2; do
  "$fuzz" seed "$kind" "$work/seed.$kind"
  mapfile -t kept < <(find "$src/tests/fuzz/regressions" -name "*.$kind" -type f | sort)
  "$fuzz" "$kind" "$work/seed.$kind" "$n" "$seed" "$work/$kind" "${kept[@]}" || status=1
done
if [ $status != 0 ] && [ -n "${LAYERS_FUZZ_KEEP:-}" ]; then
  for f in "$work"/*/finding.* "$work"/*/current.*; do
    [ -e "$f" ] || continue
    kept="$LAYERS_FUZZ_KEEP/seed$seed-$(basename "$f" | sed 's/^current/crash/')"
    cp "$f" "$kept" && echo "kept $kept"
  done
fi
exit $status
