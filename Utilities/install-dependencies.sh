#!/usr/bin/env bash
# Installs ModelSynth's dependencies from Debian 12's packages, by purpose (see usage below).
# Idempotent: only packages that are missing are installed; nothing happens when all are present.
# See Documentation/building.md for why the build uses ParaView's SDK (and its VTK).
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: Utilities/install-dependencies.sh [--runtime | --gui | --tests | --all] [--list]

Installs the Debian 12 packages ModelSynth needs that are missing (apt-get; root or sudo).
Idempotent: does nothing when every package of the chosen set is installed.

  --runtime  build and run msynth, the Python package and the ParaView plugin: compilers, CMake,
             Ninja, ccache, the ParaView 5.11 SDK (its VTK and MPI), OpenVDB 10, CGAL 5.5,
             CLI11, tinygltf, numpy (what Utilities/run-example.sh and build.sh --no-tests use)
  --gui      --runtime plus what drawing needs: the GUI's toolbar icons (libqt5svg5), an X server
             for pictures without a display (xvfb, xauth: render-model.py), screen grabs
             (x11-apps, netpbm: make-tutorial-pictures.py)
  --tests    --gui plus the test tools: GoogleTest, Google Benchmark, clang with libFuzzer
             (fuzz.sh), clang-format (check-style.sh), Node.js with the Khronos glTF validator
             from npm (into ~/.cache/modelsynth/npm; MSYNTH_NPM_PREFIX elsewhere) (what
             run-tests.sh and build.sh use)
  --all      every package (the same as --tests); the default
  --list     print the chosen set's packages, one a line, and install nothing
  -h, --help this help
EOF
}

# Toolchain and build
build=(build-essential cmake ninja-build ccache pkg-config git)
# What the build of msynth, the modules and the plugin links against, and the scripts use.
runtime=(
  # ParaView 5.11 SDK: its bundled VTK 9.2, Python wrapping and the plugin machinery
  paraview paraview-dev python3-paraview mpi-default-dev mpi-default-bin
  # third-party headers that ParaView's VTK CMake config looks for (the modules we use)
  libdouble-conversion-dev libutfcpp-dev libexpat1-dev liblz4-dev liblzma-dev zlib1g-dev libeigen3-dev
  libpng-dev libjpeg-dev python3-dev # IOImage (tile pictures) and the Python wrapping
  # RemotingViews (the plugin's colour map keeps the legend's labels current): the rendering
  # modules' third-party CMake targets (GLEW, Freetype, OpenGL, X11)
  libglew-dev libfreetype-dev libgl-dev libx11-dev libxt-dev
  # OpenVDB 10 (library, vdb_print, Python module for optional checks)
  libopenvdb-dev libopenvdb-tools python3-openvdb libboost-iostreams-dev libtbb-dev
  python3-imath # OpenVDB pulls Imath, whose CMake config names this package's library
  # CGAL 5.5 (exact geometry for continuous synthesis)
  libcgal-dev
  # the command line parser (header-only); numpy for the scripts and vtkmodules.numpy_interface
  libcli11-dev python3-numpy
  # glTF output (mesh.glb)
  libtinygltf-dev
)
# Drawing: the GUI's toolbar icons are SVG (blank without the Qt SVG plugin); rendering without a
# display (render-model.py, the GUI test); screen grabs of the GUI (make-tutorial-pictures.py).
gui=(libqt5svg5 xvfb xauth x11-apps netpbm)
tests=(
  # Tests and benchmarks
  libgtest-dev googletest libbenchmark-dev
  # Fuzzing (Utilities/fuzz.sh): clang with libFuzzer
  clang libclang-rt-14-dev
  # Style (Utilities/check-style.sh)
  clang-format
  # A real renderer imports and renders the exports (Testing/Python/test_blender.py)
  blender
)
# The glTF validator's runtime (Testing/Python/test_gltf_validator.py), only where no node or npm
# is on the PATH already (a NodeSource nodejs brings its own npm, which Debian's npm conflicts with).
command -v node > /dev/null || tests+=(nodejs)
command -v npm > /dev/null || tests+=(npm)
# The Khronos glTF validator (npm; a JavaScript library), pinned.
gltf_validator="gltf-validator@2.0.0-dev.3.10"
npm_prefix="${MSYNTH_NPM_PREFIX:-$HOME/.cache/modelsynth/npm}"

set_name=all
list=0
for arg in "$@"; do
  case "$arg" in
    --runtime | --gui | --tests | --all) set_name="${arg#--}" ;;
    --list) list=1 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "install-dependencies.sh: unknown option '$arg' (see --help)" >&2; exit 2 ;;
  esac
done

packages=("${build[@]}" "${runtime[@]}")
case "$set_name" in
  gui) packages+=("${gui[@]}") ;;
  tests | all) packages+=("${gui[@]}" "${tests[@]}") ;;
esac

if [ "$list" = 1 ]; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The glTF validator from npm, for the test sets; a failure (no network) only warns: its test is
# then reported as not run.
install_validator() {
  case "$set_name" in tests | all) ;; *) return 0 ;; esac
  if [ -f "$npm_prefix/node_modules/gltf-validator/package.json" ]; then return 0; fi
  echo "install-dependencies: installing $gltf_validator into $npm_prefix (npm)"
  mkdir -p "$npm_prefix"
  if ! npm install --prefix "$npm_prefix" --no-audit --no-fund --no-save "$gltf_validator" > /dev/null; then
    echo "install-dependencies: warning: npm could not install $gltf_validator; the glTF validator test will not run" >&2
  fi
}

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages of --$set_name present"
  install_validator
  exit 0
fi

echo "install-dependencies: installing ${#missing[@]} missing package(s) of --$set_name: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
install_validator
