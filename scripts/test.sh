#!/usr/bin/env bash
# The test command: installs what is missing, builds everything (library, fitcli, tests,
# benchmarks), runs every test (unit, integration, notebooks) with ctest.
#   scripts/test.sh              all tests
#   scripts/test.sh --sanitize   unit and integration tests under address+undefined sanitizers
#                                (about 57 min cold build + 7 min tests on the loaded 2-core machine)
#   scripts/test.sh --sanitize-readers   the reader modules' tests and the integration tests only
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
# Sanitizer runs (gcc, address + undefined, build-sanitize/): --sanitize builds everything and runs
# every unit and integration test; --sanitize-readers (a lighter check) builds the library, fitcli and
# the reader modules' tests (core, data, card, surface) and runs those plus the integration tests
# (the malformed-input corpus through a sanitized fitcli). Times: docs/reliability.md.
if [ "${1:-}" = "--sanitize" ] || [ "${1:-}" = "--sanitize-readers" ]; then
  export BUILD_DIR=${BUILD_DIR:-$root/build-sanitize}
  export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  cmake -S "$root" -B "$BUILD_DIR" -DFITLIB_SANITIZE=ON -DFITLIB_BENCH=OFF -DFITLIB_PYTHON=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  if [ "$1" = "--sanitize" ]; then
    cmake --build "$BUILD_DIR" -j "${JOBS:-$(nproc)}"
    cd "$BUILD_DIR"
    # Not under the sanitizers: the notebooks, and the package test (its consumer project is built
    # without -fsanitize, so it cannot link the sanitized library). The MPI sweep tests run without
    # leak detection: Open MPI's own allocations (libmpi, its plug-ins) are reported as leaks at
    # exit (docs/reliability.md §5).
    ctest -j "$(nproc)" --output-on-failure -LE 'notebook|package' -E SweepMpi
    ASAN_OPTIONS=detect_leaks=0 ctest -j "$(nproc)" --output-on-failure -R SweepMpi
    exit 0
  fi
  tests=(test_core test_data test_card test_surface test_integration)
  cmake --build "$BUILD_DIR" -j "${JOBS:-$(nproc)}" --target fitcli "${tests[@]}"
  cd "$BUILD_DIR"
  for t in "${tests[@]}"; do
    "./$t" --gtest_brief=1 || { echo "sanitize: $t failed" >&2; exit 1; }
  done
  echo "sanitize: ${#tests[@]} test binaries passed under address+undefined"
  exit 0
fi
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/scripts/build.sh" -DFITLIB_TESTS=ON -DFITLIB_BENCH=ON
cd "$BUILD_DIR"
ctest -j "$(nproc)" --output-on-failure --timeout 900
# Fuzzing: the data-module harnesses (table, pyvisco, waveform, waveform_analysis), each for
# FITLIB_FUZZ_RUNS executions (default 2000; 0 skips) with a fixed seed and at most 30 s, when
# clang with its libFuzzer runtime is installed. They build only core and data with clang (no
# Ceres-heavy module): 4–6 minutes on the loaded 2-core machine, ccache does not help across build
# folders (docs/reliability.md). FITLIB_FUZZ_HARNESSES="..." picks others.
fuzz_runs=${FITLIB_FUZZ_RUNS:-2000}
if [ "$fuzz_runs" != 0 ] && command -v clang++ >/dev/null &&
   [ -f "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  # shellcheck disable=SC2086  # a list of harness names
  FUZZ_RUNS=$fuzz_runs FUZZ_SEED=1 "$root/scripts/fuzz.sh" 30 ${FITLIB_FUZZ_HARNESSES:-table pyvisco waveform waveform_analysis eplexor_sheets}
else
  echo "test: fuzzing skipped (no clang++ with libFuzzer, or FITLIB_FUZZ_RUNS=0)"
fi
