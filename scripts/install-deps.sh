#!/usr/bin/env bash
# Installs the Debian packages fitlib needs, only those missing. Safe to re-run.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libceres-dev libnlopt-cxx-dev libeigen3-dev libboost-dev
  libfccp-dev nlohmann-json3-dev libtomlplusplus-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfreexl-dev gnuplot-nox
  python3 python3-matplotlib python3-numpy jupyter-nbconvert python3-nbclient python3-ipykernel
  python3-dev pybind11-dev python3-pybind11
  calculix-ccx
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
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
