#!/usr/bin/env bash
# scripts/check_format.sh -- checks that every C++ source of layers (apps,
# bench, libs, plugins, tests) is formatted as .clang-format says; lists the
# files that are not and exits 1. With --fix, formats them in place.
# Exits 77 (ctest: skipped) when clang-format is not installed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
fix=0
case "${1:-}" in
  --fix) fix=1 ;;
  "") ;;
  *) echo "usage: $0 [--fix]" >&2; exit 2 ;;
esac
formatter="${CLANG_FORMAT:-clang-format}"
if ! command -v "$formatter" >/dev/null; then
  echo "check_format: $formatter not found; install Debian's clang-format to check the style" >&2
  exit 77
fi
cd "$root"
mapfile -d '' files < <(find apps bench libs plugins tests -type f \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
if [ "$fix" = 1 ]; then
  "$formatter" --style=file -i "${files[@]}"
  exit 0
fi
# One formatter process for the whole tree; it names each file that differs.
report="$("$formatter" --style=file --dry-run "${files[@]}" 2>&1 || true)"
mapfile -t bad < <(printf '%s\n' "$report" | sed -n 's/^\(.*\):[0-9]*:[0-9]*: warning: code should be clang-formatted.*/\1/p' | sort -u)
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} of ${#files[@]} files differ from .clang-format ($("$formatter" --version | head -1)):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "check_format: run 'bash scripts/check_format.sh --fix'" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted as .clang-format says"
