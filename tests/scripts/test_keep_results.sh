#!/usr/bin/env bash
# tests/scripts/test_keep_results.sh -- scripts/keep_results.sh on a
# study folder made here: result files are kept, checkpoints and
# predictions are not, an existing destination is refused untouched.
set -euo pipefail
script="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/scripts/keep_results.sh"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

study="$work/runs/t"
mkdir -p "$study/a/seed-0/eval-test" "$study/report" "$work/data"
echo "model: {name: a}" > "$study/a/seed-0/experiment.yaml"
echo '{"chosen_on": "val"}' > "$study/a/seed-0/selection.json"
echo '{"overall": {}}' > "$study/a/seed-0/eval-test/metrics.json"
echo "weights" > "$study/a/seed-0/checkpoint-best.pt"
echo "frames" > "$study/a/seed-0/eval-test/predictions.h5"
echo "# report" > "$study/report/report.md"
mkdir -p "$study/report/charts" && echo "1 2 3" > "$study/report/charts/frames_0_0.dat"
mkdir -p "$study/report/viewer" && echo "window.LAYERS_SCENE = {};" > "$study/report/viewer/scene.js"
echo "sequences: []" > "$work/data/dataset.yaml"

out="$(bash "$script" "$study" "$work/kept" "$work/data")"
echo "$out" | grep -q "4 files" || fail "expected 4 result files kept, got: $out"
for f in a/seed-0/experiment.yaml a/seed-0/selection.json a/seed-0/eval-test/metrics.json report/report.md dataset.yaml; do
  [ -f "$work/kept/$f" ] || fail "$f not kept"
done
[ ! -e "$work/kept/a/seed-0/checkpoint-best.pt" ] || fail "a checkpoint was kept"
[ ! -e "$work/kept/a/seed-0/eval-test/predictions.h5" ] || fail "predictions were kept"
[ ! -e "$work/kept/report/charts/frames_0_0.dat" ] || fail "the picture's point data was kept"
[ ! -e "$work/kept/report/viewer" ] || fail "the viewer (megabytes) was kept"

# An existing destination: exit 1, one line, nothing changed.
echo "mine" > "$work/kept/report/report.md"
set +e
err="$(bash "$script" "$study" "$work/kept" 2>&1 >/dev/null)"
rc=$?
set -e
[ "$rc" -eq 1 ] || fail "expected exit 1 for an existing destination, got $rc"
echo "$err" | grep -q "never overwritten" || fail "unclear refusal: $err"
[ "$(cat "$work/kept/report/report.md")" = "mine" ] || fail "an existing destination was changed"

# Usage: exit 2.
set +e
bash "$script" "$study" >/dev/null 2>&1
rc=$?
set -e
[ "$rc" -eq 2 ] || fail "expected exit 2 on usage errors, got $rc"
echo "keep_results: ok"
