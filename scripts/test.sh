#!/usr/bin/env bash
# The test job on a fresh Debian 12 machine: set up, check the format, build the codec alone as a
# Release build (installed, with its examples and Python module tested against the installed
# package), then build everything under AddressSanitizer + UndefinedBehaviorSanitizer and run the
# whole suite there, and last fuzz every file reader. GPU tests run on whatever the GL layer finds
# (Mesa llvmpipe on machines without a GPU): they are never skipped for that.
# Test programs run side by side (ctest -j): many wait on outside decoders, and no test times itself.
# The suite runs once, instrumented: until the seventh session it also ran as a Release build, and
# that build and run took 647 of the job's 2175 s on a 2-core machine (README, Tests), for no
# check the instrumented run lacks (it too is optimised, -O1, with NDEBUG).
# Every file reader is fuzzed for FUZZ_SECONDS (here 15 by default) each (scripts/fuzz.sh).
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

# The codec alone, as a library user gets it: a Release build without the performer (nothing GPL
# looked for or linked), one file per compiler run, installed into a prefix; examples/ built against
# the installed package and run; the installed Python module's tests.
phase "codec-alone Release build and check" bash scripts/check_codec_alone.sh

# The whole project, instrumented, as a unity build (CMAKE_UNITY_BUILD: a few sources per compiler
# run, so that the heavy headers, GoogleTest, CLI11, glm, OpenImageIO, are parsed once per batch).
# -O1 and line tables only (-g1): sanitizer reports still name file and line, and the instrumented
# build, the job's longest phase, compiles in 672 s instead of 1109 s at -O2 -g1 on a 2-core machine
# (the sanitizer suite ran in 361 s against 372 s, so -O2 bought the tests nothing).
# The light test, tool and benchmark programs (the top CMakeLists.txt, gpuj2k_program_options) are
# compiled at -O0: their GoogleTest and CLI11 code was most of this build's time.
# With Clang, and with the libFuzzer targets in the same tree (GPUJ2K_FUZZ), which the fuzzing phase
# then runs: GCC 12's UndefinedBehaviorSanitizer more than doubles a file's compile time where
# Clang's adds half, and the fuzzers' separate tree built the libraries a second time. On a 2-vCPU
# VM the build's compile work fell from 1,478 s (GCC's tree and the fuzz tree) to 974 s (README, Tests).
phase "ASan+UBSan build" env CC=clang CXX=clang++ bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGPUJ2K_SANITIZE=ON -DCMAKE_UNITY_BUILD=ON \
  -DGPUJ2K_PROGRAM_COMPILE_OPTIONS=-O0 -DGPUJ2K_FUZZ=ON
# intercept_tls_get_addr=0: LeakSanitizer then scans no thread's dynamic TLS (the blocks of libraries
# loaded with dlopen, here only Mesa's). At exit its tracer had crashed reading a garbage dynamic-TLS
# entry ("DTLS 38 at 0x000000002aff-0x001800003c01", then "Tracer caught signal 11") in 13 of 30 runs of
# `j2kdec --dwt gpu` on llvmpipe beside a busy test, and in none of 30 with the option. Our libraries'
# thread_local buffers are static TLS, which is still scanned.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
# Should LeakSanitizer's own tracer still crash at exit ("Tracer caught signal 11", then
# "LeakSanitizer has encountered a fatal error": no finding, a failure to look; before the option
# above it did in a process that used Mesa's llvmpipe on a loaded machine), and should that be the
# only kind of failure, the failed tests run once more; any sanitizer finding or failed test fails
# the job at once.
run_sanitizer_ctest() {
  local log
  log=$(mktemp)
  if run_ctest build-asan 1800 2>&1 | tee "$log"; then
    rm -f "$log"
    return 0
  fi
  # A test that runs a program and reports only its last line of stderr (bench_smoke_test) shows
  # the tracer's crash by the hint that ends its message instead.
  if grep -qE "LeakSanitizer has encountered a fatal error|HINT: LeakSanitizer does not work under ptrace" "$log" &&
    ! grep -qE "ERROR: AddressSanitizer|ERROR: LeakSanitizer: detected|runtime error:|\[  FAILED  \]|Timeout" "$log"; then
    rm -f "$log"
    echo "test.sh: LeakSanitizer's tracer crashed (no finding); the failed tests run once more"
    (cd build-asan && ctest --rerun-failed --output-on-failure --timeout 1800)
  else
    rm -f "$log"
    return 1
  fi
}
phase "ASan+UBSan tests" run_sanitizer_ctest

# The fuzzers were built with the suite; the seeds are made by the installed codec tools of the
# Release build above.
phase "fuzzing" env FUZZ_BUILD_DIR=build-asan FUZZ_SEED_BIN="$PWD/build-codec/prefix/bin" FUZZ_SECONDS="${FUZZ_SECONDS:-15}" \
  bash scripts/fuzz.sh
