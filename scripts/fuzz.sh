#!/usr/bin/env bash
# scripts/fuzz.sh -- a longer run of the readers' fuzzer (tests/fuzz):
# ROUNDS rounds of ITERATIONS mutants per reader (BVH, YAML experiment and
# generator configs, LAYERS-H5, and the importers: OBJ, PLY, STL, GLB,
# garment side files, PC2), each round with its own RNG seed. An input
# that crashes a reader or escapes with something other than the toolkit's
# error is kept in tests/fuzz/regressions/ (the ctest fuzz_smoke replays
# them all), and the script exits 1.
#   bash scripts/fuzz.sh [rounds=20] [iterations=2000] [first rng seed=1000]
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAYERS_BUILD_DIR:-$root/build}"
rounds="${1:-20}"; n="${2:-2000}"; first="${3:-1000}"
found=0
start=$(date +%s)
for ((r = 0; r < rounds; r++)); do
  seed=$((first + r))
  LAYERS_FUZZ_KEEP="$root/tests/fuzz/regressions" \
    bash "$root/tests/fuzz/fuzz_smoke.sh" "$build/bin/layers_fuzz" "$build/bin/layers" "$root" "$n" "$seed" || found=1
done
echo "fuzz: $rounds rounds x $n mutants per reader (seeds $first..$((first + rounds - 1))) in $(( $(date +%s) - start )) s;" \
     "$([ $found = 0 ] && echo 'no finding' || echo 'FINDINGS kept in tests/fuzz/regressions')"
exit $found
