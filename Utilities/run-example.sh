#!/usr/bin/env bash
# The README's main-job command: installs what is missing (the runtime packages and the build
# tools only), builds if needed, runs discrete model synthesis on the bundled houses example
# and verifies the result. The README's first picture is made from its output
# (Utilities/make-readme-picture.sh; test_readme checks it). See --help.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

usage() {
  cat <<'EOF'
Usage: Utilities/run-example.sh [--out DIR] [--seed S] [--size NX NY NZ] [--no-build]

Installs the missing Debian packages of the runtime set only (install-dependencies.sh --runtime:
build tools, the ParaView 5.11 SDK, OpenVDB, CGAL; no test tools), builds msynth without the
tests if needed (build.sh --no-tests), synthesizes a village from Data/Examples/Houses.vox (a
MagicaVoxel example: one house on the ground, its walls labelled by side) in 12 x 12 x 5 blocks,
ground label 1 below, empty label 0 around, labels drawn by resemblance to the example, and
checks it (msynth check).

  --out DIR         where the outputs go (default ./output/main): labels.vti (the model: point arrays
                    Label, LastBlock; statistics), mesh.vtp (its voxel surface, coloured by the
                    example's palette), mesh.glb (the same surface as glTF for Blender and game
                    engines), model.vox (for MagicaVoxel), model.vdb (OpenVDB: Int32 grid Label,
                    float copy Label_float), statistics.json
  --seed S          the random seed (default 1)
  --size NX NY NZ   the model's size in sites (default 48 48 5)
  --no-build        use the existing build/bin/msynth (no install, no build)
  -h, --help        this help
EOF
}

example="$root/Data/Examples/Houses.vox"
out="$PWD/output/main"
seed=1
size=(48 48 5)
build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --size) size=("$2" "$3" "$4"); shift 4 ;;
    --no-build) build=0; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "run-example.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msynth="$root/build/bin/msynth"
if [ "$build" = 1 ]; then
  # Shown as it goes: on a fresh machine installing and compiling take several minutes.
  echo "== installing what is missing and building msynth (build.sh --no-tests)"
  bash "$here/build.sh" --no-tests
elif [ ! -x "$msynth" ]; then
  echo "run-example.sh: --no-build, but $msynth is not built" >&2
  exit 1
fi
echo "== the example"
"$msynth" info "$example" | head -3
echo "== synthesizing ${size[*]} in 12 x 12 x 5 blocks, ground (1) below, empty (0) around," \
  "labels by resemblance, seed $seed"
"$msynth" synthesize "$example" --size "${size[@]}" --block 12 12 5 --ground 1 --empty 0 \
  --choice resemblance --seed "$seed" --outputs labels,mesh,glb,vox,vdb --out "$out"
echo "== independent check of the adjacency constraint"
"$msynth" check "$example" "$out/labels.vti"
echo "outputs are in $out"
