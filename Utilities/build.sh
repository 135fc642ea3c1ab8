#!/usr/bin/env bash
# Builds ModelSynth (installing missing dependencies first). Incremental: reruns only what changed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

usage() {
  cat <<'EOF'
Usage: Utilities/build.sh [--no-tests | --asan]

Installs the missing Debian packages (install-dependencies.sh), configures with CMake and Ninja
(warnings as errors) and builds incrementally, with ccache when present.

  (none)       Release build in ./build with the tests and benchmarks; installs the --tests set
               (GoogleTest, Google Benchmark, clang, clang-format, Xvfb, ...)
  --no-tests   Release build in ./build of msynth, the Python package and the ParaView plugin
               only; installs just the --runtime set (what Utilities/run-example.sh uses). A
               build folder already configured with the tests keeps them.
  --asan       ASan + UBSan Debug build of the tests in ./build-asan; installs the --tests set
  -h, --help   this help
EOF
}

variant=release
tests=ON
for arg in "$@"; do
  case "$arg" in
    --asan) variant=asan ;;
    --no-tests) tests=OFF ;;
    -h | --help) usage; exit 0 ;;
    *) echo "build.sh: unknown option '$arg' (see --help)" >&2; exit 2 ;;
  esac
done
if [ "$variant" = asan ] && [ "$tests" = OFF ]; then
  echo "build.sh: --asan builds the tests; it cannot go with --no-tests" >&2
  exit 2
fi

if [ "$tests" = ON ]; then
  bash "$here/install-dependencies.sh" --tests
else
  bash "$here/install-dependencies.sh" --runtime
fi
# ccache: paths relative to the checkout, so clones in other folders (CI) reuse the cache.
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true

if [ "$variant" = asan ]; then
  dir="$root/build-asan"
  flags=(-DCMAKE_BUILD_TYPE=Debug -DMSYNTH_ENABLE_SANITIZERS=ON -DMSYNTH_BUILD_TESTING=ON
    -DMSYNTH_BUILD_BENCHMARKS=OFF)
else
  dir="$root/build"
  flags=(-DCMAKE_BUILD_TYPE=Release -DMSYNTH_BUILD_TESTING="$tests" -DMSYNTH_BUILD_BENCHMARKS="$tests")
fi
# The value of a cache entry of an existing build folder (empty when unconfigured).
cached() { sed -n "s/^$1:[A-Z]*=//p" "$dir/CMakeCache.txt" 2>/dev/null; }
if [ ! -f "$dir/build.ninja" ]; then
  cmake -S "$root" -B "$dir" -G Ninja -DMSYNTH_WARNINGS_AS_ERRORS=ON "${flags[@]}"
elif [ "$tests" = ON ] && [ "$(cached MSYNTH_BUILD_TESTING)" != ON ]; then
  # Configured by --no-tests (run-example.sh) before: turn the tests and benchmarks on.
  cmake -S "$root" -B "$dir" "${flags[@]}"
fi
cmake --build "$dir" --parallel "$(nproc)"
echo "build.sh: built $dir"
