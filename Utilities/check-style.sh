#!/usr/bin/env bash
# The house style, checked in CI (Utilities/run-tests.sh) before any test:
#  - every C++ file formatted with the project's .clang-format (Debian's clang-format 14);
#  - no function under Source/ over 100 lines, no source file over 800 (Utilities/check-sizes.py;
#    Utilities/size-exceptions.txt lists the few allowed for a while);
#  - no bare static_cast<std::size_t> in Source: msynth::ToIndex (Utilities/index-casts.py).
#   Utilities/check-style.sh          check; exit 1 listing what is off
#   Utilities/check-style.sh --fix    format the tree in place first
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
mapfile -t files < <(git ls-files '*.cxx' '*.h' '*.txx')
if [ "${1:-}" = --fix ]; then
  clang-format -i "${files[@]}"
fi
unformatted=()
for f in "${files[@]}"; do
  if ! clang-format --dry-run -Werror "$f" >/dev/null 2>&1; then
    unformatted+=("$f")
  fi
done
status=0
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check-style: ${#unformatted[@]} file(s) not formatted with .clang-format" \
    "(run Utilities/check-style.sh --fix):"
  printf '  %s\n' "${unformatted[@]}"
  status=1
fi
python3 Utilities/check-sizes.py || status=1
python3 Utilities/index-casts.py --check . || status=1
if [ "$status" = 0 ]; then
  echo "check-style: ${#files[@]} files formatted; sizes within limits"
fi
exit "$status"
