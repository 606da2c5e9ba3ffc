#!/usr/bin/env bash
# How the converter's whole process grows with the number of top-level declarations in one file. For each
# shape below and each N, prints the median wall time and the largest peak memory of `openplx2mjcf FILE`
# (checked, nothing written), then the ratio t(4N)/t(N): linear is about 4, quadratic about 16.
#
#   bench/declaration_scaling.sh [BUILD_DIR]     default: build
#   RUNS=R (default 3) runs per input; SIZES="10000 20000 40000 80000" (default) the values of N.
#
# Shapes, N models each, generated in a temporary folder (the converted root is the file's last model):
# - same attribute: `Mi:` declaring `a`, the name every model declares.
# - bundle base: `Mi is Physics3D.Bodies.RigidBody:` with `a`, a nested body and an expression.
# - chain: `Mi is M(i-1):` declaring ai.
# - chain, shared names: the chain, after N unrelated models `Ui:` declaring the chain's names xi.
# - root holding all: N models, then `Root:` holding one of each (N + 1 objects evaluated).
# - imports: N files of one model each, each imported, and `Mi is Fi:`.
# - unknown names: `Mi is Mxi:`, N errors (exit 1); the first 100 printed with a "did you mean".
# The tests (tests/frontend/declaration_scaling_test.cpp) hold the work linear by counting it; this prints
# the seconds, which depend on the machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
converter=$(realpath "$build/tools/openplx2mjcf")
runs=${RUNS:-3}
sizes=${SIZES:-10000 20000 40000 80000}
command -v /usr/bin/time >/dev/null || { echo "error: /usr/bin/time (GNU time) is missing" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# generate SHAPE N OUT
generate() {
  local shape=$1 n=$2 out=$3 folder
  folder=$(basename "$out").d  # the imported files' folder, beside the file
  if [[ $shape == imports ]]; then
    mkdir -p "$out.d"
    awk -v n="$n" -v d="$out.d" 'BEGIN {
      for (i = 0; i < n; ++i) {
        f = d "/f" i ".openplx"
        printf "F%d:\n    f is Real: %d\n", i, i > f
        close(f)
      }
    }'
  fi
  awk -v n="$n" -v shape="$shape" -v d="$folder" 'BEGIN {
    if (shape == "same") for (i = 0; i < n; ++i) printf "M%d:\n    a is Real: %d\n", i, i
    if (shape == "bundle") for (i = 0; i < n; ++i)
      printf "M%d is Physics3D.Bodies.RigidBody:\n    a is Real: %d\n    inner is Physics3D.Bodies.RigidBody:\n        b is Real: 2\n    c is Real: a + 1\n", i, i
    if (shape == "chain" || shape == "shared") {
      if (shape == "shared") for (i = 0; i < n; ++i) printf "U%d:\n    x%d is Real: %d\n", i, i, i
      print "M0:\n    x0 is Real: 0"
      for (i = 1; i < n; ++i) printf "M%d is M%d:\n    x%d is Real: %d\n", i, i - 1, i, i
    }
    if (shape == "root") {
      for (i = 0; i < n; ++i) printf "M%d:\n    a is Real: %d\n", i, i
      print "Root:"
      for (i = 0; i < n; ++i) printf "    m%d is M%d\n", i, i
    }
    if (shape == "imports") {
      for (i = 0; i < n; ++i) printf "import @\"%s/f%d.openplx\"\n", d, i
      for (i = 0; i < n; ++i) printf "M%d is F%d:\n    a is Real: %d\n", i, i, i
    }
    if (shape == "unknown") for (i = 0; i < n; ++i) printf "M%d is Mx%d:\n    a is Real: %d\n", i, i, i
  }' >"$out"
}

# Prints "median_seconds peak_kb exit_status" of RUNS runs.
measure() {
  local times=() peak=0 status t m
  for ((r = 0; r < runs; ++r)); do
    status=0
    /usr/bin/time -f '%e %M' -o "$work/time" "$converter" "$1" >/dev/null 2>&1 || status=$?
    read -r t m < <(tail -1 "$work/time")  # after "Command exited with non-zero status"
    times+=("$t")
    ((m > peak)) && peak=$m
  done
  local median
  median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
  echo "$median $peak $status"
}

declare -A labels=([same]="same attribute" [bundle]="bundle base" [chain]="chain" [shared]="chain, shared names"
  [root]="root holding all" [imports]="imports" [unknown]="unknown names")
declare -A seconds
echo "openplx2mjcf FILE (check only), whole process: median of $runs runs, largest peak RSS"
echo
echo "| shape | models | time | peak memory | exit |"
echo "|---|---|---|---|---|"
for shape in same bundle chain shared root imports unknown; do
  for n in $sizes; do
    generate "$shape" "$n" "$work/$shape$n.openplx"
    read -r t m status < <(measure "$work/$shape$n.openplx")
    seconds[$shape.$n]=$t
    printf '| %s | %d | %.2f s | %.0f MB | %d |\n' "${labels[$shape]}" "$n" "$t" "$(awk -v m="$m" 'BEGIN { print m / 1024 }')" "$status"
    rm -rf "$work/$shape$n.openplx" "$work/$shape$n.openplx.d"
  done
done
echo
echo "t(4N)/t(N), linear: about 4 (times under 0.1 s are mostly start-up)"
for shape in same bundle chain shared root imports unknown; do
  for n in $sizes; do
    [[ -n ${seconds[$shape.$((4 * n))]:-} ]] || continue
    awk -v l="${labels[$shape]}" -v n="$n" -v a="${seconds[$shape.$n]}" -v b="${seconds[$shape.$((4 * n))]}" 'BEGIN {
      printf "%s, %d to %d models: %.1fx\n", l, n, 4 * n, (a > 0 ? b / a : 0)
    }'
  done
done
