#!/usr/bin/env bash
# Fuzzes the file readers for a while each: PFM and PNM (imageio), BVH and Rhubarb Lip Sync
# (performer), and the JPEG 2000 decoder (codestreams, JP2 and JPH files, seeded with small encodes
# of our own, HTJ2K ones included, and the conformance streams when ../shared/conformance is
# there). Builds the libFuzzer targets with Clang (ASan + UBSan) in build-fuzz/, or in the tree
# FUZZ_BUILD_DIR names (one configured with Clang and -DGPUJ2K_FUZZ=ON: the CI job passes its
# sanitizer build's), seeds each with small valid files written here, and runs it for FUZZ_SECONDS
# (default 30). A crash, a sanitizer report or a broken promise of a reader stops the script with
# libFuzzer's report and the input that caused it (crash-* in the build folder).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
dir="${FUZZ_BUILD_DIR:-build-fuzz}"
# The seeds' encoder and image generator: FUZZ_SEED_BIN's (a folder of j2kenc and gentestimage that
# another build made; the CI job passes the installed tools of its codec-alone Release build), else
# built here. A tree of its own is -O1 with line tables only, as the sanitizer suite, and a unity
# build (a few sources per compiler run): the build is most of this script's time (83 s for the
# five targets on a 2-core machine, against some 125 s one file per run).
seed_bin="${FUZZ_SEED_BIN:-}"
if [[ -z "${FUZZ_BUILD_DIR:-}" ]]; then
  CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGPUJ2K_FUZZ=ON -DCMAKE_UNITY_BUILD=ON >/dev/null
fi
targets=(pfm_fuzz pnm_fuzz bvh_fuzz rhubarb_fuzz codestream_fuzz)
if [[ -z "$seed_bin" ]]; then
  targets+=(j2kenc gentestimage)
  seed_bin="$dir/bin"
fi
cmake --build "$dir" --parallel "$(nproc)" --target "${targets[@]}"

corpus="$dir/corpus"
rm -rf "$corpus"
mkdir -p "$corpus"/{pfm,pnm,bvh,rhubarb,codestream}
printf 'Pf\n2 1\n-1.0\n\x00\x00\x80\x3f\x00\x00\x00\x40' > "$corpus/pfm/grey.pfm"
printf 'PF\n1 1\n1.0\n\x3f\x80\x00\x00\x40\x00\x00\x00\x40\x40\x00\x00' > "$corpus/pfm/rgb_big_endian.pfm"
printf 'P2\n2 2\n# comment\n65535\n0 1 65534 65535\n' > "$corpus/pnm/plain16.pgm"
printf 'P6\n1 1\n255\n\x01\x02\x03' > "$corpus/pnm/raw.ppm"
printf 'P1\n3 1\n1 0 1\n' > "$corpus/pnm/plain.pbm"
cat > "$corpus/bvh/two_joints.bvh" <<'BVH'
HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Chest
  {
    OFFSET 0 5 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 5 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0333333
0 0 0 0 0 0 0 0 0
1 2 3 10 20 30 5 5 5
BVH
# The Rhubarb fuzzer reads the first byte as the format switch: even TSV, odd JSON.
printf '\x000.00\tX\n0.05\tB\n0.20\tA\n' > "$corpus/rhubarb/cues.tsv"
printf '\x01{"metadata":{"duration":0.3},"mouthCues":[{"start":0.00,"end":0.05,"value":"X"},{"start":0.05,"end":0.30,"value":"B"}]}' \
  > "$corpus/rhubarb/cues.json"

# Small encodes of our own: lossless and lossy, tiles, precincts, SOP/EPH, every mode switch, layers, JP2.
seed_image="$dir/corpus/seed.ppm"
"$seed_bin/gentestimage" --pattern mix --size 24x17 --channels 3 -o "$seed_image"
enc() { "$seed_bin/j2kenc" -i "$seed_image" -q "$@"; }
enc -o "$corpus/codestream/lossless.j2k" --lossless --levels 3
enc -o "$corpus/codestream/tiles.j2k" --lossless --tile 16x8 --tile-origin 1,1 --origin 3,2 --levels 2 --order RPCL
enc -o "$corpus/codestream/precincts.j2k" --lossless --precincts 8x8 --codeblock 4x4 --sop --eph --order PCRL --levels 2
enc -o "$corpus/codestream/modes.j2k" --modes bypass,reset,termall,vcausal,pterm,segsym --codeblock 8x8 --levels 2
enc -o "$corpus/codestream/layers.j2k" --rate 1,2,4 --order CPRL --levels 2
enc -o "$corpus/codestream/file.jp2" --levels 1
enc -o "$corpus/codestream/resolution.jp2" --levels 1 --capture-resolution 3780,2000 --display-resolution 2835,2835
# HTJ2K (T.814): lossless and lossy HT code-blocks, small blocks in precincts, and a JPH file.
enc -o "$corpus/codestream/ht_lossless.j2k" --ht --lossless --levels 2
enc -o "$corpus/codestream/ht_lossy.j2k" --ht --rate 8 --levels 2
enc -o "$corpus/codestream/ht_precincts.j2k" --ht --lossless --precincts 8x8 --codeblock 4x4 --sop --eph --levels 2
enc -o "$corpus/codestream/ht_file.jph" --ht --lossless --levels 1
# Samples of 38 bits (64-bit planes), made from the lossless seed by its markers as
# tests/support/deepened_stream.h makes them: SIZ 38 bits, QCD/QCC guard bits 7, exponents + 20.
python3 - "$corpus/codestream/lossless.j2k" "$corpus/codestream/deep.j2k" <<'PY'
import sys
s = bytearray(open(sys.argv[1], "rb").read())
pos = 2
while pos + 4 <= len(s):
    marker, length = s[pos] << 8 | s[pos + 1], s[pos + 2] << 8 | s[pos + 3]
    if marker == 0xFF90:
        break
    if marker == 0xFF51:
        for c in range(s[pos + 38] << 8 | s[pos + 39]):
            s[pos + 40 + 3 * c] = 37
    if marker in (0xFF5C, 0xFF5D):
        at = pos + (4 if marker == 0xFF5C else 5)
        s[at] = 7 << 5 | (s[at] & 31)
        for k in range(at + 1, pos + 2 + length):
            s[k] = ((s[k] >> 3) + 20) << 3
    pos += 2 + length
open(sys.argv[2], "wb").write(s)
PY
rm -f "$seed_image"
# The conformance streams that are small enough to mutate quickly.
if [ -d ../shared/conformance/streams ]; then
  find ../shared/conformance/streams -type f -size -64k -exec cp {} "$corpus/codestream/" \;
fi

# The fuzzers run side by side, as many at a time as there are cores (each is one process on one
# core): on a 2-core machine the five take three turns of FUZZ_SECONDS instead of five. Each one's
# lines are printed once all have finished, in a fixed order.
fuzz_one() {
  local reader=$1
  echo "fuzzing the $reader reader for ${seconds} s"
  # -artifact_prefix keeps any crash input next to the build, where the report points.
  (cd "$dir" && "bin/${reader}_fuzz" "corpus/$reader" -max_total_time="$seconds" -max_len="$([ "$reader" = codestream ] && echo 65536 || echo 8192)" \
    -artifact_prefix="crash-$reader-" -print_final_stats=1 2>&1 | grep -E "^(stat::number_of_executed_units|==|SUMMARY|ERROR|Done)" || true)
}
readers=(pfm pnm bvh rhubarb codestream)
rm -f "$dir"/crash-* "$dir"/fuzz-*.log
for reader in "${readers[@]}"; do
  while (($(jobs -rp | wc -l) >= $(nproc))); do wait -n || true; done
  fuzz_one "$reader" >"$dir/fuzz-$reader.log" 2>&1 &
done
wait
for reader in "${readers[@]}"; do
  cat "$dir/fuzz-$reader.log"
  # libFuzzer's exit status is lost in the pipe above; a crash leaves its input behind instead.
  if ls "$dir"/crash-"$reader"-* >/dev/null 2>&1; then
    echo "the $reader fuzzer found a failing input: $(ls "$dir"/crash-"$reader"-*)" >&2
    exit 1
  fi
done
