#!/usr/bin/env bash
# The grounded-proportions matrix at full sizes (issue 29 item 1), a benchmark rather than a
# timed test: every bundled multi-type example (house, box building, cottage, domed building,
# town) x {--grounded, --grounded + its documented constraints} x seeds 1-5 at the sizes of the
# README and the gallery (the town at 100 x 100 x 10, a few minutes a run), each object type's
# share of the solid volume of model.vtp against the example's (Testing/Python/proportions.py).
# Prints the table and the seconds per run; exits 1 when a share is outside 25 %.
#   Testing/Benchmarks/proportions.sh [BUILD] [proportions.py options, e.g. --examples house]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
shift || true
export PYTHONPATH="$build/lib/python3.11/site-packages${PYTHONPATH:+:$PYTHONPATH}"
export MSYNTH_DATA="$root/Data" MSYNTH_BIN="$build/bin"
export MSYNTH_TMP="${MSYNTH_TMP:-$(mktemp -d)}"
exec /usr/bin/python3 "$root/Testing/Python/proportions.py" --size full "$@"
