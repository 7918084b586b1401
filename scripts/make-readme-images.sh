#!/usr/bin/env bash
# Regenerates the gallery pictures shown in the README (docs/images/gallery/*.png) with
# `splinekit gallery`: the same command a user runs, at a smaller size. The pictures are the
# same bytes on every run, so `git status` after this script shows only real changes.
#
#   bash scripts/make-readme-images.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out="target/readme-gallery"
cargo run --release --locked -q -p splinekit-cli -- gallery -o "$out" --size 480x360
mkdir -p docs/images/gallery
for name in wineglass weirder gentorus trefoil-rmf bunny-loop0 bunny-loop3 icosahedron-loop1 arc-length-markers; do
    cp "$out/images/$name.png" "docs/images/gallery/$name.png"
done
echo "docs/images/gallery: $(ls docs/images/gallery | wc -l) pictures from $out/index.html"
