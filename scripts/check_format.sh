#!/usr/bin/env bash
# Checks that every C++ source of the modules is formatted as .clang-format says (Debian's
# clang-format). Fails listing the files that are not; `scripts/check_format.sh --fix` formats
# them in place.
#   scripts/check_format.sh [--fix] [CLANG_FORMAT]
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
if [ "${1:-}" = "--fix" ]; then fix=1; shift; fi
tool=${1:-clang-format}
command -v "$tool" > /dev/null || { echo "check_format: $tool not found (Debian package clang-format)" >&2; exit 1; }
mapfile -t files < <(find core garbing skeletonize evaluate render python cmake/consumer -name '*.cpp' -o -name '*.h' | sort)
if [ "$fix" = 1 ]; then
  "$tool" -i --style=file "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  "$tool" --dry-run --Werror --style=file "$f" > /dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} of ${#files[@]} files are not formatted ($tool, .clang-format):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "run scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
