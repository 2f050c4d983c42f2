#!/usr/bin/env bash
# tests/regression/make_fixture.sh -- regenerate the committed regression
# fixture (tests/regression/fixture.tar.xz), on purpose only: the model
# goldens run on it, so they must be updated after it (docs/studies.md).
#   bash tests/regression/make_fixture.sh [path/to/layers]
# The dataset: configs/data/tiny.yaml shrunk to 6 sequences of 20 frames
# (3 train, 1 val, 2 test), packed reproducibly (sorted names, fixed owner
# and time) so that the same data give the same archive.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
layers="${1:-$root/build/bin/layers}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$layers" generate --config "$root/configs/data/tiny.yaml" --out "$work/fixture" --threads 2 --quiet \
  --set sequences=6 --set frames=20 --set sequences_per_shard=6 --set splits.val=0.17 --set splits.test=0.34
"$layers" validate "$work/fixture"
tar --sort=name --owner=0 --group=0 --numeric-owner --mtime=@0 -C "$work" -cf - fixture | xz -9e -T1 > "$work/fixture.tar.xz"
mv "$work/fixture.tar.xz" "$here/fixture.tar.xz"
sha256sum "$work/fixture/shard-00000.h5" "$work/fixture/splits.yaml" | sed "s|$work/||"
echo "wrote $here/fixture.tar.xz ($(du -h "$here/fixture.tar.xz" | cut -f1)); now: LAYERS_UPDATE_GOLDENS=1 ctest --test-dir build -R regression"
