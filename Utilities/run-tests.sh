#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, checks the house style
# (Utilities/check-style.sh: formatting, function and file sizes), and runs every test with ctest
# (engine, VTK, Python, pvbatch serial and MPI, ParaView GUI under Xvfb), first in the Release
# build, then in the ASan + UBSan build, then every libFuzzer harness for a bounded time (the
# regression inputs first). Exits non-zero when anything fails.
#   Utilities/run-tests.sh                  all of it
#   Utilities/run-tests.sh --no-sanitizers  the Release build only (no fuzzing either)
#   Utilities/run-tests.sh --no-fuzz        both builds, no fuzzing
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

sanitizers=1
fuzz=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0; fuzz=0 ;;
    --no-fuzz) fuzz=0 ;;
    *) echo "run-tests.sh: unknown option '$arg'" >&2; exit 2 ;;
  esac
done

bash "$here/build.sh"
bash "$here/check-style.sh"
(cd "$root/build" && ctest --output-on-failure --parallel "$(nproc)")

if [ "$sanitizers" = 1 ]; then
  bash "$here/build.sh" --asan
  (cd "$root/build-asan" && ctest --output-on-failure --parallel "$(nproc)")
fi
if [ "$fuzz" = 1 ]; then
  # 10 s per harness in CI; Documentation/reliability.md gives longer runs.
  bash "$here/fuzz.sh" "${MSYNTH_FUZZ_SECONDS:-10}"
fi
echo "run-tests.sh: all tests passed"
