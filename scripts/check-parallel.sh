#!/usr/bin/env bash
# Runs the whole test suite with `ctest -j 8` N times in a row (default 20) and stops at the first
# failure: the check that the suite is deterministic and its tests do not share files.
#   scripts/check-parallel.sh [N]      (BUILD_DIR defaults to build/; build it first)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-20}
cd "${BUILD_DIR:-$root/build}"
for i in $(seq 1 "$runs"); do
  if ! ctest -j 8 --timeout 900 --output-on-failure >"ctest-parallel-$i.log" 2>&1; then
    echo "run $i of $runs failed; log: $PWD/ctest-parallel-$i.log"
    grep -E "tests failed|\(Failed\)|\(Timeout\)" "ctest-parallel-$i.log" || true
    exit 1
  fi
  echo "run $i of $runs passed ($(grep -o '[0-9]* tests failed out of [0-9]*' "ctest-parallel-$i.log" | head -1 || true))"
  rm -f "ctest-parallel-$i.log"
done
echo "all $runs runs passed"
