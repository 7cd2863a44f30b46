#!/usr/bin/env bash
# Install everything stickslip needs from Debian 12 (bookworm) packages.
#   scripts/install-deps.sh          build, test and figure dependencies
#   scripts/install-deps.sh --peers  also the comparison peers used by bench/ (Octave, SUNDIALS)
# Idempotent: packages already present are skipped by apt-get.
set -euo pipefail

core=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libcli11-dev libfmt-dev libtomlplusplus-dev librandom123-dev
  libnetcdf-c++4-dev libnetcdf-dev netcdf-bin libhdf5-dev hdf5-tools
  libgtest-dev libgmock-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin
  libsleef-dev libxsimd-dev xtl-dev libhwy-dev libboost-dev zlib1g-dev
  clang libclang-rt-14-dev
  gnuplot-nox python3 python3-numpy python3-netcdf4
  python3-dev pybind11-dev python3-pandas python3-xarray python3-matplotlib python3-tqdm
  python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-openturns
  python3-hypothesis
)
peers=(octave libsundials-dev)

want=("${core[@]}")
[[ "${1:-}" == "--peers" ]] && want+=("${peers[@]}")

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#want[@]} packages already installed"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
