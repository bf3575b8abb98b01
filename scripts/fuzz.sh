#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) with clang into build-fuzz/ and runs each for SECONDS.
#   scripts/fuzz.sh [SECONDS] [HARNESS...]   default 60 s, every harness
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 3600 table   stop after that many executions (or SECONDS)
#   FUZZ_SEED=N fixes libFuzzer's seed (the test command's short runs); FUZZ_NO_BUILD=1 skips the
#   build (harnesses already built)
# Seeds: datasets/, tests/data/ (incl. the malformed corpus tests/data/bad/) and fuzz/seeds/.
# The growing corpus stays in build-fuzz/corpus/<harness>; a finding (crash, sanitizer report,
# unexpected exception type, accepted non-finite value) is saved in build-fuzz/findings/ and
# makes the script exit 1. One line per harness: executions, time, coverage (edges), features.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2
  exit 2
fi
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] ||
  harnesses=(table pyvisco card scene schedule_json schedule_toml surface constraints waveform waveform_analysis eplexor eplexor_sheets)
# Only the harnesses asked for are built, with the library modules they link (fuzz/CMakeLists.txt):
# the data-module harnesses alone need no Ceres-heavy module.
if [ "${FUZZ_NO_BUILD:-0}" != 1 ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DFITLIB_FUZZ=ON -DFITLIB_TESTS=OFF -DFITLIB_BENCH=OFF >/dev/null
  cmake --build "$build" -j "${JOBS:-$(nproc)}" --target "${harnesses[@]/#/fuzz_}" >/dev/null
fi
runs=()
[ -n "${FUZZ_RUNS:-}" ] && runs=(-runs="$FUZZ_RUNS")
[ -n "${FUZZ_SEED:-}" ] && runs+=(-seed="$FUZZ_SEED")

# Seed files of a harness (globs relative to the repository).
seeds() {
  case "$1" in
    table) echo datasets/materials/material-*.csv datasets/materials/synthetic-*.csv tests/data/malformed/*.csv tests/data/bad/table/* ;;
    pyvisco) echo datasets/materials/pyvisco-*.csv tests/data/bad/pyvisco/* ;;
    card) echo datasets/cards/*.json tests/data/surface/*card*.json tests/data/bad/card/* ;;
    scene) echo datasets/drives/*.toml tests/data/scenes/*.toml tests/data/bad/scene/* ;;
    schedule_json) echo datasets/schedules/*.json tests/data/bad/schedule/*.json ;;
    schedule_toml) echo datasets/schedules/*.toml tests/data/bad/schedule/*.toml ;;
    surface) echo tests/data/bad/surface/* ;;
    constraints) echo tests/data/bad/constraints/* ;;
    waveform | waveform_analysis) echo tests/data/waveforms/*.csv tests/data/bad/waveform/* ;;
    eplexor) echo datasets/materials/pyvisco-eplexor-*.xls tests/data/eplexor/*.xls tests/data/bad/xls/* ;;
  esac
}

# Longest input libFuzzer makes: the .xls seeds are 84–95 kB; the waveform harnesses get a few
# hundred (analysis) or thousand (reading) samples: their cost grows with the sample count
# (docs/reliability.md); longer waveform files are in the corpus (tests/data/bad).
max_len() {
  case "$1" in
    eplexor) echo 131072 ;;
    waveform) echo 16384 ;;
    waveform_analysis) echo 8192 ;;
    *) echo 65536 ;;
  esac
}

# libfreexl's own leaks are suppressed (fuzz/lsan.supp says why); fitlib's are findings.
export LSAN_OPTIONS=suppressions=$root/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}
status=0
passed=0
failed=0
mkdir -p "$build/findings" "$build/tmp"
printf '%-14s %10s %6s %7s %7s %s\n' harness executions s edges features result
for h in "${harnesses[@]}"; do
  corpus=$build/corpus/$h
  mkdir -p "$corpus"
  (cd "$root" && for f in $(seeds "$h") fuzz/seeds/$h/*; do [ -f "$f" ] && cp -n "$f" "$corpus/" || true; done)
  dict=()
  [ -f "$root/fuzz/dict/$h.dict" ] && dict=(-dict="$root/fuzz/dict/$h.dict")
  log=$build/fuzz-$h.log
  start=$(date +%s)
  if TMPDIR=$build/tmp "$build/fuzz/fuzz_$h" "$corpus" "${dict[@]}" "${runs[@]}" -max_total_time="$seconds" \
      -max_len="$(max_len "$h")" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/findings/$h-" >"$log" 2>&1; then
    result=ok
    passed=$((passed + 1))
  else
    result="FINDING (see $log)"
    status=1
    failed=$((failed + 1))
  fi
  elapsed=$(( $(date +%s) - start ))
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  edges=$(echo "$last" | grep -o 'cov: [0-9]*' | grep -o '[0-9]*' || true)
  features=$(echo "$last" | grep -o 'ft: [0-9]*' | grep -o '[0-9]*' || true)
  printf '%-14s %10s %6s %7s %7s %s\n' "$h" "${execs:-?}" "$elapsed" "${edges:-?}" "${features:-?}" "$result"
done
echo "fuzz: $passed passed, $failed failed"
exit $status
