#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs every test with ctest
# (engine, VTK, Python, pvbatch serial and MPI, ParaView GUI under Xvfb), first in the Release
# build, then in the ASan + UBSan build. Exits non-zero when anything fails.
#   Utilities/run-tests.sh                  both builds
#   Utilities/run-tests.sh --no-sanitizers  the Release build only
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

sanitizers=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0 ;;
    *) echo "run-tests.sh: unknown option '$arg'" >&2; exit 2 ;;
  esac
done

bash "$here/build.sh"
(cd "$root/build" && ctest --output-on-failure --parallel "$(nproc)")

if [ "$sanitizers" = 1 ]; then
  bash "$here/build.sh" --asan
  (cd "$root/build-asan" && ctest --output-on-failure --parallel "$(nproc)")
fi
echo "run-tests.sh: all tests passed"
