#!/usr/bin/env bash
# Whole-process times of four of WaveFunctionCollapse's overlapping samples at their own
# samples.xml options (issue 45): Font (N 5, symmetry 2, periodic, 90²), BrownFox (N 4,
# symmetry 1, 90²), Lake (N 3, periodic, 60²), Cat (N 3, symmetry 2, periodic, 80²), minimum
# entropy, seeds 1..S; with a fast-wfc build, also its example program on the same entries (one
# per folder: a samples.xml of that entry and samples/NAME.png), same run. Prints a Markdown
# table of seconds (median, min–max: wall, and CPU = user + system, which a loaded machine
# inflates less) and, for msynth, the distinct patterns and whether `msynth check` finds the
# picture valid.
#   Testing/Benchmarks/wfc-samples.sh [--msynth BIN] [--fast-wfc BIN] [--seeds S]
#                                     [--samples DIR] [--only NAME]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
msynth="$root/build/bin/msynth"
fastwfc=""
seeds=3
samples="$root/../shared/data/WaveFunctionCollapse/samples"
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --msynth) msynth="$2"; shift 2 ;;
    --fast-wfc) fastwfc="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --samples) samples="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    *) echo "wfc-samples.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
# name N symmetry periodic size (samples.xml)
entries=("Font 5 2 1 90" "BrownFox 4 1 0 90" "Lake 3 8 1 60" "Cat 3 2 1 80")
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
stats() { sort -g | awk '{ v[NR] = $1 } END { printf "%.2f (%.2f–%.2f)", v[int((NR + 1) / 2)], v[1], v[NR] }'; }
echo "| sample | msynth s | msynth CPU s | patterns | valid | fast-wfc s | fast-wfc CPU s |"
echo "|---|---|---|---|---|---|---|"
for e in "${entries[@]}"; do
  read -r name n sym periodic size <<<"$e"
  if [ -n "$only" ] && [ "$only" != "$name" ]; then continue; fi
  translate=()
  [ "$periodic" = 1 ] && translate=(--translate xy)
  : >"$tmp/ms"
  : >"$tmp/msc"
  valid=yes
  patterns=""
  for seed in $(seq 1 "$seeds"); do
    out="$tmp/$name-$seed"
    /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$msynth" synthesize "$samples/$name.png" --pattern "$n" \
      --symmetry "$sym" "${translate[@]}" --size "$size" "$size" 1 --order entropy \
      --seed "$seed" --out "$out" >"$tmp/log" 2>&1 || valid=no
    awk '{ print $1 }' "$tmp/t" >>"$tmp/ms"
    awk '{ print $2 + $3 }' "$tmp/t" >>"$tmp/msc"
    patterns="$(sed -n 's/.* \([0-9,]*\) distinct pattern.*/\1/p' "$tmp/log" | head -1)"
    "$msynth" check "$samples/$name.png" "$out/picture.png" --pattern "$n" --symmetry "$sym" \
      "${translate[@]}" >/dev/null 2>&1 || valid=no
  done
  fw="–"
  fwc="–"
  if [ -n "$fastwfc" ]; then
    dir="$tmp/fw-$name"
    mkdir -p "$dir/samples" "$dir/results"
    cp "$samples/$name.png" "$dir/samples/"
    p=False
    [ "$periodic" = 1 ] && p=True
    echo "<samples><overlapping name=\"$name\" N=\"$n\" symmetry=\"$sym\" periodic=\"$p\"" \
      "width=\"$size\" height=\"$size\" screenshots=\"1\"/></samples>" >"$dir/samples.xml"
    : >"$tmp/fw"
    : >"$tmp/fwc"
    for _ in $(seq 1 "$seeds"); do
      (cd "$dir" && /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$fastwfc" >/dev/null 2>&1)
      awk '{ print $1 }' "$tmp/t" >>"$tmp/fw"
      awk '{ print $2 + $3 }' "$tmp/t" >>"$tmp/fwc"
    done
    fw="$(stats <"$tmp/fw")"
    fwc="$(stats <"$tmp/fwc")"
  fi
  echo "| $name (N $n, symmetry $sym$([ "$periodic" = 1 ] && echo ", periodic"), ${size}²) |" \
    "$(stats <"$tmp/ms") | $(stats <"$tmp/msc") | $patterns | $valid | $fw | $fwc |"
done
