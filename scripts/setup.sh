#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing (Debian 12 packages; clang and libclang-rt-dev for scripts/fuzz.sh),
# configures and builds MesoLens in ./build.
# Idempotent: packages already installed are not touched; the build is incremental.
#   BUILD_DIR=...   build folder (default: build)
#   CMAKE_ARGS=...  extra CMake arguments (e.g. -DMESOLENS_ENABLE_SANITIZERS=ON)
set -eu
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}

# ParaView 5.11 brings the VTK 9.2 everything builds on (and vtkmodules for /usr/bin/python3);
# it replaces Debian's separate VTK 9.1 packages, which cannot be installed beside it.
# paraview-dev does not pull in the -dev packages its CMake configuration looks for (MPI,
# double-conversion, LZ4, HDF5, NetCDF, ...): they are listed here.
packages="cmake g++ make pkg-config zlib1g-dev
  paraview-dev python3-paraview libglew-dev libfreetype-dev openmpi-bin libopenmpi-dev
  libdouble-conversion-dev liblz4-dev liblzma-dev libexpat1-dev libxml2-dev libpng-dev
  libjpeg-dev libtiff-dev libutfcpp-dev libgl2ps-dev libnetcdf-dev libhdf5-openmpi-dev
  libtheora-dev libogg-dev libx11-dev libxt-dev libgl-dev
  python3-numpy python3-mdanalysis libeigen3-dev libcgal-dev libopenmesh-dev
  libgtest-dev gemmi-dev tao-pegtl-dev libgromacs-dev dssp freesasa edtsurf python3-pymol
  xvfb xauth mesa-utils libgl1-mesa-dri
  clang libclang-rt-dev"
missing=""
for package in $packages; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $package"
  fi
done
if [ -n "$missing" ]; then
  echo "Installing:$missing"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends $missing
fi

# shellcheck disable=SC2086
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 ${CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" -j "$(nproc)"
