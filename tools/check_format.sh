#!/usr/bin/env bash
# Check that every C++ source of the project is as clang-format (.clang-format) writes it.
# Prints the first differences and exits 1 when a file differs; `tools/check_format.sh --fix`
# rewrites them instead.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(find src tests bench fuzz python -type f \( -name '*.cpp' -o -name '*.hpp' \
  -o -name '*.h' -o -name '*.cc' \) | LC_ALL=C sort)
if [ "${1:-}" = --fix ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
if ! out=$(clang-format --dry-run -Werror "${files[@]}" 2>&1); then
  echo "$out" | head -40
  echo "check_format: $(echo "$out" | grep -c 'error:') places differ from .clang-format; run tools/check_format.sh --fix"
  exit 1
fi
echo "check_format: ${#files[@]} files as .clang-format writes them"
