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
  "$root/scripts/build.sh" -DFITLIB_SANITIZE=ON -DFITLIB_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
  cd "$BUILD_DIR"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest -j "$(nproc)" --output-on-failure -LE notebook
  exit 0
fi
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/scripts/build.sh" -DFITLIB_TESTS=ON -DFITLIB_BENCH=ON
cd "$BUILD_DIR"
ctest -j "$(nproc)" --output-on-failure --timeout 900
# Fuzzing: each libFuzzer harness for FITLIB_FUZZ_SECONDS when clang with its libFuzzer runtime is
# installed. Off by default (0): it needs a second, sanitized clang build of the whole library that
# would more than double the test command's time on 2 cores (docs/reliability.md); e.g.
# FITLIB_FUZZ_SECONDS=10 scripts/test.sh.
fuzz_seconds=${FITLIB_FUZZ_SECONDS:-0}
if [ "$fuzz_seconds" != 0 ] && command -v clang++ >/dev/null &&
   [ -f "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  "$root/scripts/fuzz.sh" "$fuzz_seconds"
else
  echo "test: fuzzing skipped (no clang++ with libFuzzer, or FITLIB_FUZZ_SECONDS=0)"
fi
