#!/usr/bin/env bash
# The wavelet applications of thesis 4.7 (dwtool edit, combine, decouple, deform) on the Kodak
# photographs (generated images when they are absent), with their inputs, into OUT/wavelet_apps/,
# then a short run of their benchmark. Called by scripts/main.sh; usage: wavelet_apps.sh BIN OUT
set -euo pipefail
bin=$1
dir=$2/wavelet_apps
mkdir -p "$dir"
kodak=../shared/testimages/kodak
photo() {  # index, generated pattern used without the photographs -> path of the input
  if [[ -f "$kodak/kodim$1.png" ]]; then cp "$kodak/kodim$1.png" "$dir/kodim$1.png"; echo "$dir/kodim$1.png"
  else "$bin/gentestimage" --pattern "$2" --size 768x512 --channels 3 -o "$dir/generated$1.png" >/dev/null; echo "$dir/generated$1.png"; fi
}
for backend in cpu gpu; do
  # Subband editing: in YCbCr, the finest luma details boosted, level 2's diagonal detail removed.
  "$bin/dwtool" edit -i "$(photo 05 mix)" -o "$dir/edit-$backend.png" --space ycc --levels 5 \
    --band 'Y:1:*=1.8' --band 'Y:2:HH=0' --backend "$backend"
done
# Stylising (Figure 4.10): the base keeps its lowest band and chroma, luma detail bands take the
# larger coefficient of the two; the detail image's lowest band is dropped.
"$bin/dwtool" edit -i "$(photo 03 zoneplate)" -o "$dir/soft-03.png" --levels 5 --band '1:*=0' --band '2:*=0'
"$bin/dwtool" combine -i "$(photo 03 zoneplate)" --detail "$(photo 13 edges)" -o "$dir/combine-03-13.png" --levels 5 --backend gpu
# Texture-illuminance decoupling (Figure 4.11).
"$bin/dwtool" decouple -i "$(photo 01 gradient-diag)" -o "$dir/decal-01.png" --illuminance "$dir/illuminance-01.png" --levels 5 --backend gpu
# Geometric deformation (Figure 4.9): three designs of the built-in head (the performer's procedural
# head as a 35x48 control net, 3 levels), as nets, surfaces and pictures with their band layouts.
"$bin/dwtool" deform --head -o "$dir/head-original.ply" --mesh "$dir/head-original.obj" --picture "$dir/head-original.png" -q
"$bin/dwtool" deform --head --band '3:*=1.5' -o "$dir/head-coarse-up.ply" --mesh "$dir/head-coarse-up.obj" \
  --picture "$dir/head-coarse-up.png" --backend gpu
"$bin/dwtool" deform --head --band '1:*=0' --band '2:*=0.4' -o "$dir/head-smooth.ply" --mesh "$dir/head-smooth.obj" \
  --picture "$dir/head-smooth.png" --backend gpu
"$bin/dwtool" deform --head --band 'Y:LL=1.2' --band 'X:LL=0.9' --band '2:*=1.6' -o "$dir/head-long.ply" \
  --mesh "$dir/head-long.obj" --picture "$dir/head-long.png" --backend gpu
echo "== Wavelet applications: ms per edit (bench/wavelet_apps_bench)"
"$bin/wavelet_apps_bench" --sizes 512,1024,2048 --reps 3
