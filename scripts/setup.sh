#!/usr/bin/env bash
# Installs everything the project needs on a fresh Debian 12 machine (Debian packages only).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev            # image input (PNG, PNM, TIFF, BMP, JPEG, ...)
  libegl-dev libgl-dev          # EGL and the GL headers (functions are loaded at run time)
  libegl-mesa0 libgl1-mesa-dri  # Mesa's EGL and llvmpipe, the headless renderer where no GPU is present
  libosmesa6 libosmesa6-dev     # OSMesa, the last-resort headless context
  libhwy-dev                    # Highway SIMD with run-time dispatch
  libcli11-dev                  # command-line parsing
  libglm-dev                    # vector maths for the performer
  libespeak-ng-dev espeak-ng-data  # the performer's text to speech (GPL-3.0: linked by the performer only)
  libtinygltf-dev               # glTF 2.0 avatars (morph targets, skins) for the performer
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev  # the performer's video (H.264 via libx264: GPL, performer only)
  ffmpeg                        # ffprobe, which the render tests read the videos back with
  libgtest-dev                  # tests
  clang libclang-rt-14-dev      # the sanitizer build and its libFuzzer targets (scripts/test.sh, fuzz.sh)
  clang-format                  # the C++ style check (scripts/check_format.sh)
  libopenjp2-tools grokj2k-tools  # reference decoders the codec's output is checked against
  openjph-tools                 # ojph_compress and ojph_expand, the HTJ2K references in bench/speed and bench/decode
  python3 python3-matplotlib    # bench/table41, bench/psnr and Figure 4.13
  python3-dev pybind11-dev python3-numpy  # the Python bindings (python/) and their tests
)
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends "${PACKAGES[@]}"
