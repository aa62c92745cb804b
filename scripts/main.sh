#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: set up, build, run a DWT round trip through dwtool on
# the CPU and the GPU (whatever renderer the GL layer finds), then the DWT benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build
bin=build/bin
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The bundled image: the project's own generator, so nothing depends on downloads.
"$bin/gentestimage" --pattern mix --size 768x512 -o "$work/mix.png"
echo "== DWT round trips on a generated 768x512 image"
# Forward to coefficients and back to an 8-bit PNG; rounding absorbs the 9/7's float error, so the
# written file must equal the original byte for byte.
round_trip() {  # name, then dwtool options
  local name=$1; shift
  "$bin/dwtool" forward -i "$work/mix.png" -o "$work/$name.pfm" "$@"
  "$bin/dwtool" inverse -i "$work/$name.pfm" -o "$work/$name.png" "$@"
  if cmp -s "$work/mix.png" "$work/$name.png"; then echo "$name: round trip exact"; else echo "$name: round trip FAILED"; exit 1; fi
}
round_trip 97-cpu --kernel 97 --levels 5 --backend cpu
round_trip 97-gpu --kernel 97 --levels 5 --backend gpu
round_trip 53-cpu --kernel 53 --levels 5 --origin 1,1
echo "== DWT benchmark"
"$bin/dwt_bench" --sizes 512,1024,2048,4096 --reps 3
