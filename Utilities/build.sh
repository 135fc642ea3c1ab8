#!/usr/bin/env bash
# Builds ModelSynth (installing missing dependencies first). Incremental: reruns only what changed.
#   Utilities/build.sh            Release build in ./build
#   Utilities/build.sh --asan     ASan + UBSan build of the tests in ./build-asan
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

variant=release
for arg in "$@"; do
  case "$arg" in
    --asan) variant=asan ;;
    *) echo "build.sh: unknown option '$arg'" >&2; exit 2 ;;
  esac
done

bash "$here/install-dependencies.sh"
# ccache: paths relative to the checkout, so clones in other folders (CI) reuse the cache.
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true

if [ "$variant" = asan ]; then
  dir="$root/build-asan"
  flags=(-DCMAKE_BUILD_TYPE=Debug -DMSYNTH_ENABLE_SANITIZERS=ON -DMSYNTH_BUILD_BENCHMARKS=OFF)
else
  dir="$root/build"
  flags=(-DCMAKE_BUILD_TYPE=Release)
fi
if [ ! -f "$dir/build.ninja" ]; then
  cmake -S "$root" -B "$dir" -G Ninja -DMSYNTH_WARNINGS_AS_ERRORS=ON "${flags[@]}"
fi
cmake --build "$dir" --parallel "$(nproc)"
echo "build.sh: built $dir"
