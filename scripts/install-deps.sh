#!/usr/bin/env bash
# Installs the Debian packages fitlib needs, only those missing. Safe to re-run.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libceres-dev libnlopt-cxx-dev libeigen3-dev libboost-dev
  nlohmann-json3-dev libtomlplusplus-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfreexl-dev gnuplot-nox libsuitesparse-dev
  python3 python3-matplotlib python3-numpy jupyter-nbconvert python3-nbclient python3-ipykernel
  python3-dev pybind11-dev python3-pybind11
  calculix-ccx
  libopenmpi-dev openmpi-bin
  help2man
)
# Optional: clang and its libFuzzer runtime for the fuzz harnesses (scripts/fuzz.sh); the build
# and every test work without them (gcc only), the test command then skips the fuzzing step.
optional=(clang-14 libclang-rt-14-dev)
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
missing_optional=()
for p in "${optional[@]}"; do
  installed "$p" || missing_optional+=("$p")
done
if [ ${#missing_optional[@]} -gt 0 ] && [ "${FITLIB_NO_OPTIONAL:-0}" != 1 ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "install-deps: optional ${missing_optional[*]}"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${missing_optional[@]}" >/dev/null 2>&1 || echo "install-deps: optional packages not installed (fuzzing skipped)"
fi
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
