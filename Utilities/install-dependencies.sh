#!/usr/bin/env bash
# Installs ModelSynth's build and test dependencies from Debian 12's packages.
# Idempotent: only packages that are missing are installed; nothing happens when all are present.
# See Documentation/building.md for why the build uses ParaView's SDK (and its VTK).
set -euo pipefail

packages=(
  # Toolchain and build
  build-essential cmake ninja-build ccache pkg-config git
  # ParaView 5.11 SDK: its bundled VTK 9.2, Python wrapping and the plugin machinery
  paraview paraview-dev python3-paraview mpi-default-dev mpi-default-bin
  # third-party headers that ParaView's VTK CMake config looks for (the modules we use)
  libdouble-conversion-dev libutfcpp-dev libexpat1-dev liblz4-dev liblzma-dev zlib1g-dev libeigen3-dev
  libpng-dev libjpeg-dev python3-dev  # IOImage (tile pictures) and the Python wrapping
  # OpenVDB 10 (library, vdb_print, Python module for optional checks)
  libopenvdb-dev libopenvdb-tools python3-openvdb libboost-iostreams-dev libtbb-dev
  python3-imath  # OpenVDB pulls Imath, whose CMake config names this package's library
  # CGAL 5.5 (exact geometry for continuous synthesis)
  libcgal-dev
  # Tests and benchmarks
  libgtest-dev googletest libbenchmark-dev python3-numpy
  # Rendering without a display; screen grabs of the GUI (make-tutorial-pictures.py: xwd, netpbm)
  xvfb xauth x11-apps netpbm
  # Fuzzing (Utilities/fuzz.sh): clang with libFuzzer, and the format libraries the engine reads
  clang libclang-rt-14-dev liblz4-dev liblzma-dev zlib1g-dev libpng-dev
  # Style (Utilities/check-style.sh) and the command line parser (header-only)
  clang-format libcli11-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-dependencies: installing ${#missing[@]} missing package(s): ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
