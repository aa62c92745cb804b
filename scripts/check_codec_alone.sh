#!/usr/bin/env bash
# The codec as a library, the way a user embeds it (issue 15): configure without the performer and
# with TinyGLTF hidden from CMake, build and install the codec library, tools and Python module
# into a prefix, check that nothing GPL was looked for or linked, build examples/ as a separate
# CMake project against the installed package, run it, and decode its output with OpenJPEG; then
# run the Python module's tests against the installed module. This is CI's Release build: one file
# per compiler run, so a source that compiles only thanks to its neighbours in a unity batch fails.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build-codec
prefix="$PWD/$dir/prefix"
cmake --no-warn-unused-cli -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPUJ2K_BUILD_PERFORMER=OFF -DGPUJ2K_BUILD_TESTS=OFF -DGPUJ2K_BUILD_PYTHON=ON \
  -DGPUJ2K_BUILD_BENCH=OFF -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON >/dev/null
cmake --build "$dir" --parallel "$(nproc)" --target gpuj2k j2kenc j2kdec dwtool imgpsnr gentestimage gpuj2k_imageio_oiio \
  gpuj2k_python
rm -rf "$prefix"
cmake --install "$dir" --prefix "$prefix" >/dev/null

fail() { echo "check_codec_alone: $*" >&2; exit 1; }
# Nothing GPL looked for: the performer's packages never reached the cache.
looked_for=$(grep -vE '^//|CMAKE_DISABLE_FIND_PACKAGE|GPUJ2K_BUILD_PERFORMER' "$dir/CMakeCache.txt" |
  grep -iE 'espeak|tinygltf|avcodec|avformat|swscale|x264' || true)
[[ -z "$looked_for" ]] || fail "the codec-only configuration looked for a performer package: $looked_for"
# Nothing GPL linked into the installed library, module or tools.
for file in "$prefix"/lib/libgpuj2k.so "$prefix"/lib/libgpuj2k_imageio_oiio.so "$prefix"/bin/*; do
  if readelf -d "$file" | grep NEEDED | grep -qiE 'espeak|avcodec|avformat|avutil|swscale|swresample|x264'; then
    fail "$file links a GPL library: $(readelf -d "$file" | grep NEEDED | grep -iE 'espeak|av|sw|x264')"
  fi
done
[[ ! -e "$prefix/bin/performer" ]] || fail "the performer was installed although it is off"

# A separate project against the installed package.
rm -rf "$dir/example"
cmake -S examples -B "$dir/example" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$dir/example" >/dev/null
"$dir/example/encode_buffer" "$dir/example/out.j2k"
opj_decompress -i "$dir/example/out.j2k" -o "$dir/example/out.ppm" >/dev/null
[[ -s "$dir/example/out.ppm" ]] || fail "opj_decompress wrote nothing for the example's codestream"
# The installed tools find the library and the OpenImageIO module from where they are.
"$dir/prefix/bin/gentestimage" --pattern mix --size 64x48 --channels 3 -o "$dir/example/in.png" >/dev/null
"$prefix/bin/j2kenc" -i "$dir/example/in.png" -o "$dir/example/in.j2k" --lossless -q
opj_decompress -i "$dir/example/in.j2k" -o "$dir/example/back.png" >/dev/null
"$prefix/bin/imgpsnr" "$dir/example/in.png" "$dir/example/back.png" | grep -q inf || fail "installed j2kenc's lossless encode is not exact"
# The Python module as installed (the sanitizer build leaves it out: a Python interpreter would need
# the sanitizer runtimes preloaded).
PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -m unittest discover -s python/tests -q ||
  fail "the installed Python module's tests failed"
echo "check_codec_alone: codec built and installed without the performer (no GPL package looked for or linked); examples/ built against it, ran, and OpenJPEG decoded its output; the installed Python module passed its tests"
