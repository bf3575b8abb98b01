#!/usr/bin/env bash
# The test command: installs what is missing, builds everything (library, fitcli, tests,
# benchmarks), runs every test (unit, integration, notebooks) with ctest.
#   scripts/test.sh              all tests
#   scripts/test.sh --sanitize   unit and integration tests under address+undefined sanitizers
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
if [ "${1:-}" = "--sanitize" ]; then
  export BUILD_DIR=${BUILD_DIR:-$root/build-sanitize}
  "$root/scripts/build.sh" -DFITLIB_SANITIZE=ON -DFITLIB_BENCH=OFF -DFITLIB_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
  cd "$BUILD_DIR"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest -j "$(nproc)" --output-on-failure -LE notebook
  exit 0
fi
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/scripts/build.sh" -DFITLIB_TESTS=ON -DFITLIB_BENCH=ON
cd "$BUILD_DIR"
ctest -j "$(nproc)" --output-on-failure --timeout 900
# Fuzzing: the data-module harnesses (table, pyvisco, waveform, waveform_analysis) for
# FITLIB_FUZZ_SECONDS each (default 5; 0 skips) when clang with its libFuzzer runtime is
# installed. They build only core and data with clang (no Ceres-heavy module), so the step adds
# about a minute cold (docs/reliability.md); FITLIB_FUZZ_HARNESSES="..." picks others.
fuzz_seconds=${FITLIB_FUZZ_SECONDS:-5}
if [ "$fuzz_seconds" != 0 ] && command -v clang++ >/dev/null &&
   [ -f "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  # shellcheck disable=SC2086  # a list of harness names
  "$root/scripts/fuzz.sh" "$fuzz_seconds" ${FITLIB_FUZZ_HARNESSES:-table pyvisco waveform waveform_analysis}
else
  echo "test: fuzzing skipped (no clang++ with libFuzzer, or FITLIB_FUZZ_SECONDS=0)"
fi
