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
