#!/usr/bin/env bash
# Byte-compares what two builds of openplx2mjcf write for every model we have: the MJCF, the signal manifest,
# the diagnostics and the exit status, for each top-level model of every .openplx file and every URDF under
# tests/, samples/ and ../shared/corpus. A refactor must print "identical"; a behaviour change shows up as a
# diff of exactly the outputs it touches.
#
#   tools/compare-outputs.sh BASE [NEW]
#     BASE  a git revision (built into build-compare/<rev>, openplx2mjcf only) or a path to an openplx2mjcf
#     NEW   the same; default: build/tools/openplx2mjcf of this checkout (build it first)
#   OPENPLX_COMPARE_KEEP=1 keeps the two output trees (printed) for a closer look.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

# A runnable openplx2mjcf for a path or a git revision, then a tab and the source tree whose bundles it uses.
binary_for() {
  local what=$1
  if [[ -x $what && ! -d $what ]]; then
    printf '%s\t%s\n' "$(realpath "$what")" "$root"
    return
  fi
  local rev
  rev=$(git rev-parse --short --verify "$what^{commit}") || { echo "error: $what is neither an executable nor a git revision" >&2; exit 2; }
  local tree=$root/build-compare/$rev
  if [[ ! -x $tree/build/tools/openplx2mjcf ]]; then
    rm -rf "$tree"
    mkdir -p "$tree"
    git archive "$rev" | tar -x -C "$tree"
    cmake -S "$tree" -B "$tree/build" -DCMAKE_BUILD_TYPE=Release -DOPENPLX_BUILD_BENCH=OFF >/dev/null
    cmake --build "$tree/build" --target openplx2mjcf -j"$(nproc)" >/dev/null
  fi
  [[ -x $tree/build/tools/openplx2mjcf ]] || { echo "error: building $what failed" >&2; exit 2; }
  printf '%s\t%s\n' "$tree/build/tools/openplx2mjcf" "$tree"
}

base=$(binary_for "$1") || exit 2
new=$(binary_for "${2:-build/tools/openplx2mjcf}") || exit 2

# Inputs by path relative to the repository, so both runs print the same names.
mapfile -t inputs < <(
  {
    find tests samples -type f \( -name '*.openplx' -o -name '*.urdf' \) -not -path 'tests/corpus/*'
    find tests/corpus -type f \( -name '*.openplx' -o -name '*.urdf' \)
    [[ -d ../shared/corpus ]] && find ../shared/corpus -type f \( -name '*.openplx' -o -name '*.urdf' \)
  } | LC_ALL=C sort
)

work=$(mktemp -d)
trap '[[ "${OPENPLX_COMPARE_KEEP:-0}" == 1 ]] || rm -rf "$work"' EXIT

# One run of a binary over every input into $work/out, then moved to $work/$2. Output paths are the same in
# both runs, so mesh paths written relative to the output agree; diagnostics located in a bundle file name
# the binary's own source tree, which is replaced by <source>.
snapshot() {
  local bin=${1%%$'\t'*} source=${1#*$'\t'} label=$2
  rm -rf "$work/out"
  mkdir -p "$work/out"
  local file models model key
  for file in "${inputs[@]}"; do
    models=("")  # the default model (the last one declared)
    if [[ $file == *.openplx ]]; then
      mapfile -t -O 1 models < <(grep -oE '^[A-Za-z_][A-Za-z0-9_]* is ' "$file" | cut -d' ' -f1 | LC_ALL=C sort -u)
    fi
    for model in "${models[@]}"; do
      key=$(echo "$file${model:+@$model}" | sed 's#^\.\./#up/#; s#/#__#g')
      local args=("$file" -o "$work/out/$key.xml")
      [[ -n $model ]] && args+=(--model "$model")
      # TestBundle-style folders beside a model are extra bundle directories.
      [[ -d $(dirname "$file")/TestBundle ]] && args+=(-B "$(dirname "$file")")
      local status=0
      timeout 120 "$bin" "${args[@]}" >"$work/out/$key.stdout" 2>"$work/out/$key.stderr" || status=$?
      echo "$status" >"$work/out/$key.status"
    done
  done
  find "$work/out" -type f -exec sed -i "s#$source/bundles/#<source>/bundles/#g" {} +
  mv "$work/out" "$work/$label"
}

snapshot "$base" base
snapshot "$new" new
count=$(find "$work/base" -name '*.status' | wc -l)
outputs=$(find "$work/base" -name '*.xml' -o -name '*.signals.json' | wc -l)
if diff -r "$work/base" "$work/new" >"$work/diff.txt"; then
  echo "identical: $count runs over ${#inputs[@]} files ($outputs MJCF and manifest files, plus every run's diagnostics and exit status)"
else
  cat "$work/diff.txt"
  echo "DIFFERENT: $(grep -c '^diff \|^Only in' "$work/diff.txt") of the outputs of $count runs over ${#inputs[@]} files differ" >&2
  [[ "${OPENPLX_COMPARE_KEEP:-0}" == 1 ]] && echo "outputs kept in $work" >&2
  exit 1
fi
[[ "${OPENPLX_COMPARE_KEEP:-0}" == 1 ]] && echo "outputs kept in $work"
exit 0
