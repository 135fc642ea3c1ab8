#!/usr/bin/env bash
# The README's main-job command: installs what is missing, builds if needed, and runs discrete
# model synthesis on the bundled default example (Data/Examples/Village.vti), then verifies the
# result. Outputs go to ./output (or the folder given with --out):
#   labels.vti        the synthesized model (point array Label, LastBlock; statistics)
#   model.vdb         the model as OpenVDB (Int32 grid Label, float copy Label_float)
#   statistics.json   the run statistics
#   Utilities/run-example.sh [--out DIR] [--seed S] [--size NX NY NZ]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

example="$root/Data/Examples/Village.vti"
out="$PWD/output"
seed=1
size=(48 48 5)
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --size) size=("$2" "$3" "$4"); shift 4 ;;
    *) echo "run-example.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done

bash "$here/build.sh" >/dev/null
msynth="$root/build/bin/msynth"
echo "== example: $example"
"$msynth" info "$example" | head -3
echo "== synthesizing ${size[*]} in 12 x 12 x 5 blocks, ground (1) below, empty (0) around, seed $seed"
"$msynth" synthesize "$example" --size "${size[@]}" --block 12 12 5 --ground 1 --empty 0 \
  --seed "$seed" --out "$out"
echo "== independent check of the adjacency constraint"
"$msynth" check "$example" "$out/labels.vti"
echo "outputs are in $out"
