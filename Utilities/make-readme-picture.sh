#!/usr/bin/env bash
# Makes the README's first picture from the main job's own output: runs Utilities/run-example.sh
# with its defaults (--no-build: build first), renders its mesh.vtp to
# Documentation/images/village.png (render-model.py) and writes the model's measures and the
# picture's SHA-256 to Documentation/images/village.json. Python.test_readme runs the main job
# again and requires the same measures and that picture, so rerun this after anything that changes
# the main job's model.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case "${1:-}" in
  "") ;;
  -h | --help)
    echo "Usage: Utilities/make-readme-picture.sh [-h | --help]"
    echo
    sed -n '2,7p' "${BASH_SOURCE[0]}" | cut -c3-
    exit 0 ;;
  *) echo "make-readme-picture.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
esac
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
bash "$root/Utilities/run-example.sh" --no-build --out "$scratch/output/main" >/dev/null
picture="$root/Documentation/images/village.png"
pvpython "$root/Utilities/render-model.py" "$scratch/output/main/mesh.vtp" "$picture" --size 900 600
/usr/bin/python3 "$root/Testing/Python/village_measures.py" "$root/Data/Examples/Houses.vox" \
  "$scratch/output/main/labels.vti" --json "$scratch/measures.json" >/dev/null
/usr/bin/python3 - "$scratch/measures.json" "$picture" "$root/Documentation/images/village.json" <<'PY'
import hashlib, json, sys
measures = json.load(open(sys.argv[1]))
record = {"command": "Utilities/run-example.sh", "measures": measures,
          "picture": "Documentation/images/village.png",
          "picture_sha256": hashlib.sha256(open(sys.argv[2], "rb").read()).hexdigest()}
with open(sys.argv[3], "w") as f:
    json.dump(record, f, indent=1, sort_keys=True)
    f.write("\n")
PY
echo "wrote $picture and Documentation/images/village.json"
