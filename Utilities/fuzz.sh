#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan, engine only: build-fuzz/) and runs each
# for SECONDS seconds, starting from seed corpora made of the bundled data and the regression
# inputs in Testing/Fuzz/Regressions/<harness>/ (which are also run once, first). Prints the
# executions of each harness; exits non-zero when a harness finds a crash (the input is kept
# in build-fuzz/crashes/<harness>/).
#   Utilities/fuzz.sh [SECONDS]     default 20
# MSYNTH_FUZZ_HARNESSES="FuzzGltf FuzzVoxModel" runs only those.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
case "${1:-}" in
  -h | --help)
    sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
    exit 0 ;;
esac
seconds="${1:-20}"
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number" >&2; exit 2 ;; esac

bash "$here/install-dependencies.sh" --tests
# ccache: paths relative to the checkout, so clones in other folders (CI) reuse the cache.
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true
dir="$root/build-fuzz"
if [ ! -f "$dir/build.ninja" ]; then
  cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMSYNTH_FUZZ_ONLY=ON >/dev/null
fi
cmake --build "$dir" --parallel "$(nproc)"

data="$root/Data"
regressions="$root/Testing/Fuzz/Regressions"
# harness: seed files (globs under Data)
declare -A seeds=(
  [FuzzTextModel]="Examples/*.txt Malformed/text-*.txt"
  [FuzzVoxModel]="Examples/*.vox Malformed/vox-*.vox"
  [FuzzTileset]="Tilesets/*.xml"
  [FuzzPolyhedral]=""
  [FuzzImage]="Tilesets/*/*.png Samples/*.png"
  [FuzzVTKXML]="Examples/*.vti Malformed/*.vti Continuous/*-guide.vti"
  [FuzzVDB]=""
  [FuzzSynthesis]=""
  [FuzzPatterns]=""
  [FuzzOutputFolder]=""
  [FuzzGltf]=""
)
export ASAN_OPTIONS="detect_leaks=0:allocator_may_return_null=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
total=0
failed=0
printf '%-16s %12s %s\n' harness executions result
for harness in ${MSYNTH_FUZZ_HARNESSES:-FuzzTextModel FuzzVoxModel FuzzTileset FuzzPolyhedral FuzzImage FuzzVTKXML FuzzVDB FuzzSynthesis FuzzPatterns FuzzOutputFolder FuzzGltf}; do
  corpus="$dir/corpus/$harness"
  crashes="$dir/crashes/$harness"
  mkdir -p "$corpus" "$crashes"
  for pattern in ${seeds[$harness]}; do
    for f in $data/$pattern; do [ -f "$f" ] && cp "$f" "$corpus/"; done
  done
  if [ "$harness" = FuzzPolyhedral ]; then # the first byte picks OBJ (0), PLY (1) or STL (2)
    for f in "$data"/Continuous/*.obj; do { printf '\0'; cat "$f"; } > "$corpus/$(basename "$f")"; done
  fi
  if [ "$harness" = FuzzVDB ] && [ -x "$root/build/bin/msynth" ]; then
    "$root/build/bin/msynth" analyze "$data/Examples/Village.vti" --out "$dir/vdb-seed" >/dev/null 2>&1 \
      && cp "$dir/vdb-seed/example.vdb" "$corpus/village.vdb" || true
  fi
  if [ "$harness" = FuzzGltf ] && [ -x "$root/build/bin/msynth" ]; then # a mesh.glb msynth writes
    "$root/build/bin/msynth" synthesize "$data/Examples/Village.vti" --size 8 8 5 --outputs glb \
      --out "$dir/glb-seed" >/dev/null 2>&1 && cp "$dir/glb-seed/mesh.glb" "$corpus/village.glb" || true
  fi
  if [ -d "$regressions/$harness" ] && ls "$regressions/$harness"/* >/dev/null 2>&1; then
    if ! "$dir/bin/$harness" "$regressions/$harness"/* >"$dir/$harness-regressions.log" 2>&1; then
      echo "$harness: a regression input fails (see $dir/$harness-regressions.log)"
      failed=1
      continue
    fi
    cp "$regressions/$harness"/* "$corpus/"
  fi
  log="$dir/$harness.log"
  if "$dir/bin/$harness" "$corpus" -max_total_time="$seconds" -max_len=65536 \
      -rss_limit_mb=3072 -timeout=20 -artifact_prefix="$crashes/" -print_final_stats=1 >"$log" 2>&1; then
    result=ok
  else
    result="CRASH (see $log and $crashes)"
    failed=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo 0)
  total=$((total + ${runs:-0}))
  printf '%-16s %12s %s\n' "$harness" "${runs:-0}" "$result"
done
echo "fuzz.sh: $total executions in total"
exit "$failed"
