#!/usr/bin/env bash
# The test job on a fresh Debian 12 machine: set up, then build and run the whole suite twice, as a
# Release build and under AddressSanitizer + UndefinedBehaviorSanitizer. GPU tests run on whatever
# the GL layer finds (Mesa llvmpipe on machines without a GPU): they are never skipped for that.
# Test programs run side by side (ctest -j): many wait on outside decoders, and no test times itself.
# First, the C++ sources must be formatted as .clang-format says (check_format.sh).
# Then the codec is built alone and installed, and examples/ is built against it (check_codec_alone.sh).
# Last, every file reader is fuzzed for FUZZ_SECONDS (default 30) each (scripts/fuzz.sh).
# Each phase's time is printed as it ends ("test.sh: PHASE took N s"), so that a slow CI run says where.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
phase() {
  local name=$1 t0=$SECONDS
  shift
  "$@"
  echo "test.sh: $name took $((SECONDS - t0)) s (job so far $((SECONDS - started)) s)"
}
run_ctest() { (cd "$1" && ctest --output-on-failure --timeout "$2" -j "$(nproc)"); }

phase setup bash scripts/setup.sh
phase "format check" bash scripts/check_format.sh

# The two full builds are unity builds (CMAKE_UNITY_BUILD: a few sources per compiler run, so that
# the heavy headers, GoogleTest, CLI11, glm, OpenImageIO, are parsed once per batch rather than once
# per file); the codec-alone build below stays one file per compiler run, so that a source that only
# compiles thanks to its neighbours in a batch still fails CI.
phase "Release build" bash scripts/build.sh build -DCMAKE_UNITY_BUILD=ON
phase "Release tests" run_ctest build 900

# The codec alone, as a library user gets it: built without the performer (nothing GPL looked for or
# linked), installed into a prefix, and examples/ built against the installed package and run.
phase "codec-alone build and check" bash scripts/check_codec_alone.sh

# -O1 and line tables only (-g1): sanitizer reports still name file and line, and the instrumented
# build, the job's longest phase, compiles in 672 s instead of 1109 s at -O2 -g1 on a 2-core machine
# (the sanitizer suite ran in 361 s against 372 s, so -O2 bought the tests nothing).
phase "ASan+UBSan build" bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGPUJ2K_SANITIZE=ON -DCMAKE_UNITY_BUILD=ON
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
phase "ASan+UBSan tests" run_ctest build-asan 1800

phase "fuzzing" env FUZZ_SEED_BIN="$PWD/build/bin" bash scripts/fuzz.sh
