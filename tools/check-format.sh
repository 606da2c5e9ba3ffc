#!/usr/bin/env bash
# Fails when a C++ file in the tree is not formatted by the root .clang-format.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "clang-format not found; skipping format check"; exit 0; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find . -name '*.cpp' -o -name '*.h')
[[ ${#files[@]} -eq 0 ]] && exit 0
# A log of our own, so two checks at once do not share one.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! clang-format --dry-run --Werror "${files[@]}" 2>"$log"; then
  echo "error: files are not clang-formatted (run: clang-format -i \$(git ls-files '*.cpp' '*.h')):" >&2
  sed -n 's/^\([^:]*\.\(cpp\|h\)\):[0-9].*/\1/p' "$log" | sort -u >&2
  exit 1
fi
echo "== format check: OK"
