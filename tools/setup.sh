#!/usr/bin/env bash
# Installs everything Talus needs to build, test and plot on a fresh Debian 12 machine.
# Safe to run again: apt-get skips what is already installed.
set -euo pipefail

packages=(
  build-essential cmake ccache git pkg-config
  libeigen3-dev libboost-dev nlohmann-json3-dev libhdf5-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  python3 python3-numpy python3-matplotlib python3-h5py python3-jsonschema
  # GDAL headers: the runout plugin reads GeoTIFF DEMs through GDAL (CMake requires it
  # unless -DTALUS_WITH_GDAL=OFF).
  libgdal-dev
  # Clang and its OpenMP runtime: one test builds an out-of-tree plugin with clang and checks
  # that a GCC-built talus loads it (the test skips, saying so, without them).
  clang libomp-dev
  # Runs over MPI ranks (CMake's TALUS_WITH_MPI=AUTO builds it when these are present):
  # Open MPI for the messages, Zoltan for the partition, parallel HDF5 for the one
  # output file all ranks write together (the MPI build links it instead of the serial one).
  libopenmpi-dev openmpi-bin libtrilinos-zoltan-dev libhdf5-openmpi-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "talus setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "talus setup: all packages present"
fi
