#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: set up, build, run DWT round trips through dwtool on the
# CPU and the GPU (whatever renderer the GL layer finds), encode an image losslessly and lossily and
# check both through OpenJPEG, the same for HTJ2K through OpenJPH, decode them all with j2kdec,
# then the DWT benchmark, the thesis' Table 4.1 and 4.2 runs, the encoder and decoder speed
# benchmarks, and the performer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build
bin=build/bin
# Everything the job makes stays in out/ (pictures, figure, codestreams, speech, meshes, benchmark JSON).
work=out
rm -rf "$work"
mkdir -p "$work"

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
echo "== JPEG 2000: lossless and lossy encodes of the same image, decoded by OpenJPEG"
"$bin/j2kenc" -i "$work/mix.png" -o "$work/lossless.jp2" --lossless
opj_decompress -i "$work/lossless.jp2" -o "$work/lossless.png" >/dev/null
"$bin/imgpsnr" "$work/mix.png" "$work/lossless.png"   # prints inf: bit-exact
"$bin/j2kenc" -i "$work/mix.png" -o "$work/lossy.j2k" --rate 0.75 --dwt auto --timing
opj_decompress -i "$work/lossy.j2k" -o "$work/lossy.png" >/dev/null
"$bin/imgpsnr" "$work/mix.png" "$work/lossy.png"
echo "== HTJ2K (Part 15): a lossless JPH file and a rate-controlled codestream, decoded by OpenJPH"
"$bin/j2kenc" -i "$work/mix.png" -o "$work/ht_lossless.jph" --ht --lossless
ojph_expand -i "$work/ht_lossless.jph" -o "$work/ht_lossless.pgm" >/dev/null
"$bin/imgpsnr" "$work/mix.png" "$work/ht_lossless.pgm"   # inf: bit-exact
"$bin/j2kenc" -i "$work/mix.png" -o "$work/ht_lossy.j2c" --ht --rate 0.75
ojph_expand -i "$work/ht_lossy.j2c" -o "$work/ht_lossy.pgm" >/dev/null
"$bin/imgpsnr" "$work/mix.png" "$work/ht_lossy.pgm"
echo "== Our decoder (j2kdec) on those files, the CPU inverse DWT and the GPU one for the 9/7"
"$bin/j2kdec" -i "$work/lossless.jp2" -o "$work/j2kdec_lossless.png"
"$bin/imgpsnr" "$work/mix.png" "$work/j2kdec_lossless.png"   # inf
"$bin/j2kdec" -i "$work/lossy.j2k" -o "$work/j2kdec_lossy.png" --dwt gpu
"$bin/imgpsnr" "$work/lossy.png" "$work/j2kdec_lossy.png"    # against OpenJPEG's decode: within 1
"$bin/j2kdec" -i "$work/ht_lossless.jph" -o "$work/j2kdec_ht_lossless.png"
"$bin/imgpsnr" "$work/mix.png" "$work/j2kdec_ht_lossless.png"   # inf
"$bin/j2kdec" -i "$work/ht_lossy.j2c" -o "$work/j2kdec_ht_lossy.png" --reduce 1 --region 0,0,384,256

echo "== DWT benchmark"
"$bin/dwt_bench" --sizes 512,1024,2048,4096 --reps 3

echo "== Wavelet applications of thesis 4.7 (edit, combine, decouple, deform) into $work/wavelet_apps"
bash scripts/wavelet_apps.sh "$bin" "$work"

echo "== Table 4.1 / Figure 4.13 (bench/table41) and Table 4.2 (bench/psnr)"
python3=/usr/bin/python3
$python3 bench/table41 --sizes 128,256,512,1024,2048 --runs 3 --plot "$work/figure413.png"
kodak=../shared/testimages/kodak
if [ -f "$kodak/kodim01.png" ]; then
  $python3 bench/psnr "$kodak/kodim01.png" "$kodak/kodim03.png"
else
  $python3 bench/psnr
fi

echo "== Encoder speed: j2kenc against OpenJPEG, Grok and OpenJPH on the 2048x2048 mosaic (bench/speed)"
$python3 bench/speed --sizes 2048 --runs 3 --json "$work/speed.json"
echo "== Decoder speed: j2kdec against OpenJPEG and Grok on the 2048x2048 mosaic (bench/decode)"
$python3 bench/decode --sizes 2048 --runs 3 --json "$work/decode_speed.json"
echo "== HTJ2K decoder speed: j2kdec against OpenJPEG, Grok and OpenJPH on j2kenc --ht's 2048x2048 streams (bench/decode)"
$python3 bench/decode --sizes 2048 --runs 3 --reduce 0 --streams j2kenc-ht --decoders j2kdec-cpu,opj,grk,ojph \
  --json "$work/decode_speed_ht.json"

echo "== The virtual performer: speech to visemes to face, motion capture to the whole character"
"$bin/performer" visemes --lang yue --text "你好" --fps 30 -o "$work/weights.csv" --wav "$work/hello.wav"
"$bin/performer" face --weights "$work/weights.csv" -o "$work/face_frames"
bvh=../shared/assets/bvh/cmu_131_01.bvh
if [ -f "$bvh" ]; then
  "$bin/performer" info --bvh "$bvh"
  "$bin/performer" pose --bvh "$bvh" --frames 0:29 --lang en-us --text "Hello, I am the performer" -o "$work/pose_frames"
  echo "== The performer rendered on the GPU (equation 3.20 in a vertex shader, section 3.7's effects), with its speech"
  cubemap=../shared/assets/cubemap
  effects=hair
  if [ -f "$cubemap/posx.jpg" ]; then effects=env,hair; fi
  "$bin/performer" render --bvh "$bvh" --frames 0:479 --lang en-us --text "Hello, I am your virtual performer. Watch me walk." \
    --effects "$effects" --size 640x480 -o "$work/performer.mp4"
  "$bin/performer" render --bvh "$bvh" --frames 0:239 --effects snow,toon --size 640x480 -o "$work/performer_toon_snow.mp4"
  echo "== A glTF avatar through the same shader path: the generated performer written as a skinned glTF with morph"
  echo "   targets, then rendered from another clip, its joints following the clip's by name, speech on its morph targets"
  "$bin/performer" avatar --bvh "$bvh" -o "$work/performer_avatar.glb"
  clip=../shared/assets/bvh/cmu_131_02.bvh
  if [ ! -f "$clip" ]; then clip=$bvh; fi
  "$bin/performer" render --bvh "$clip" --gltf "$work/performer_avatar.glb" --frames 0:239 --lang en-us \
    --text "I am a glTF avatar." --effects "$effects" --size 640x480 -o "$work/performer_gltf_avatar.mp4"
  # Its benchmark drives the same clip.
  "$bin/performer_bench"
else
  echo "note: $bvh not found; skipping performer pose, render and benchmark"
fi

echo "== Done: what the job made is in $(cd "$work" && pwd):"
ls "$work"
