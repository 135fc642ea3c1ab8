#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, checks the house style and runs
# every test, in the Release build, then the ASan + UBSan build, then the fuzzers. See --help.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

usage() {
  cat <<'EOF'
Usage: Utilities/run-tests.sh [--no-sanitizers | --no-fuzz]

Installs the missing Debian packages of the test set (install-dependencies.sh --tests: the
runtime set plus GoogleTest, Google Benchmark, clang, clang-format, Xvfb, libqt5svg5, ...),
builds (build.sh), checks the house style (check-style.sh: formatting, function and file sizes)
and runs every test with ctest (engine, VTK, Python, pvbatch serial and MPI, the ParaView GUI
under Xvfb), first in the Release build (./build), then in the ASan + UBSan build
(./build-asan), then every libFuzzer harness for MSYNTH_FUZZ_SECONDS (default 10) seconds
(fuzz.sh). Exits non-zero when anything fails.

  (none)            all of it
  --no-sanitizers   the Release build only (no fuzzing either)
  --no-fuzz         both builds, no fuzzing
  -h, --help        this help
EOF
}

sanitizers=1
fuzz=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0; fuzz=0 ;;
    --no-fuzz) fuzz=0 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "run-tests.sh: unknown option '$arg' (see --help)" >&2; exit 2 ;;
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
