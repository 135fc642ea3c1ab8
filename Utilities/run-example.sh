#!/usr/bin/env bash
# The README's main-job command: installs what is missing, builds if needed, and runs ModelSynth
# on the bundled default example (Data/Examples/Village.vti), writing into ./output
# (or the folder given with --out). Other arguments: an EXAMPLE file to use instead.
#   Utilities/run-example.sh [EXAMPLE] [--out DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

example="$root/Data/Examples/Village.vti"
out="$PWD/output"
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    *) example="$1"; shift ;;
  esac
done

bash "$here/build.sh" >/dev/null
"$root/build/bin/msynth" info "$example"
"$root/build/bin/msynth" analyze "$example" --out "$out"
echo "outputs are in $out"
