#!/usr/bin/env bash
# Fails when a C++ source file (.h, .cpp) of the libraries and tools is not named in a README.md: the one in
# its own folder or in a parent folder up to the top-level folder (frontend/syntax/lexer.h may be named in
# frontend/syntax/README.md or frontend/README.md). A file counts as named when its file name appears as a
# word (`lexer.h`, `include/openplx/runtime/simulation.h`) or as `stem.{h,cpp}` / `stem.{cpp,h}`.
#   tools/check-readmes.sh            checks the folders below
#   tools/check-readmes.sh DIR...     checks those folders instead
set -euo pipefail
cd "$(dirname "$0")/.."

roots=("$@")
[[ ${#roots[@]} -eq 0 ]] &&
  roots=(frontend snap mjcf_emitter contract mujoco_support runtime tools/cli tools/sim)

# named FILE: 0 when a README.md from FILE's folder up to its top-level folder names it.
named() {
  local file=$1 dir name stem ext pattern
  name=$(basename "$file")
  stem=${name%.*}
  ext=${name##*.}
  # Word boundaries: no letter, digit or underscore right before or after the name.
  pattern="(^|[^A-Za-z0-9_])${stem}\.(${ext}|\{h,cpp\}|\{cpp,h\})([^A-Za-z0-9_]|$)"
  dir=$(dirname "$file")
  while :; do
    if [[ -f "$dir/README.md" ]] && grep -Eq "$pattern" "$dir/README.md"; then return 0; fi
    [[ "$dir" != */* ]] && return 1  # the top-level folder was the last to look in
    dir=$(dirname "$dir")
  done
}

missing=()
for root in "${roots[@]}"; do
  [[ -d "$root" ]] || { echo "error: no folder $root" >&2; exit 2; }
  while IFS= read -r file; do
    named "$file" || missing+=("$file")
  done < <(find "$root" -type f \( -name '*.h' -o -name '*.cpp' \) | sed 's|^\./||' | sort)
done

if [[ ${#missing[@]} -gt 0 ]]; then
  echo "error: these files are named in no README.md of their folder or a parent folder:" >&2
  printf '  %s\n' "${missing[@]}" >&2
  exit 1
fi
echo "== README check: OK (every .h/.cpp under ${roots[*]} is named in a README.md)"
