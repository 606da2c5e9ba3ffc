#!/usr/bin/env bash
# How the converter's whole process grows with its input: URDF robots of 1,000 and 10,000
# links, inheritance chains of 1,000 and 10,000 models, and 100 MB of random bytes. Prints each run's wall
# time and peak memory (GNU time), and the growth from 1,000 to 10,000 (linear: 10x).
#
#   bench/scaling.sh [BUILD_DIR]     default: build
#   RUNS=N (default 3) runs per input; the median time and the largest peak memory are printed.
#
# Inputs, generated in a temporary folder:
# - URDF chain: each link hangs from the previous one by a revolute joint with limits. MuJoCo 2.2.2 reads at
#   most about 100 nested elements, so beyond 90 links the converter ends in a located `mjcf-too-deep` error
#   (exit 1): the time is the converter's own, up to that error.
# - URDF forest: the same links as chains of 50 hanging from one base link: a robot MuJoCo can load.
# - Inheritance chain: `M0` declares a0, each `Mk is M(k-1)` declares ak, the scene is the last one.
# - Random bytes: /dev/urandom (refused as not text), and the same with its NUL bytes taken out (read as
#   broken text until the error limit).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
converter=$(realpath "$build/tools/openplx2mjcf")
runs=${RUNS:-3}
command -v /usr/bin/time >/dev/null || { echo "error: /usr/bin/time (GNU time) is missing" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# N links; each link's parent is the previous one, or (with a branch length B) the base link at each B-th.
urdf() {
  local n=$1 branch=$2 out=$3
  awk -v n="$n" -v b="$branch" 'BEGIN {
    print "<?xml version=\"1.0\"?>"
    print "<robot name=\"scaling\">"
    for (i = 0; i < n; ++i) {
      printf "  <link name=\"link%d\">\n", i
      print "    <inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>"
      print "    <collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>"
      print "  </link>"
      if (i == 0) continue
      parent = (b > 0 && (i - 1) % b == 0) ? 0 : i - 1
      printf "  <joint name=\"joint%d\" type=\"revolute\">\n", i
      printf "    <parent link=\"link%d\"/><child link=\"link%d\"/>\n", parent, i
      printf "    <origin xyz=\"%s 0 0.1\"/><axis xyz=\"0 1 0\"/>\n", (b > 0 && parent == 0) ? int((i - 1) / b) * 0.2 : 0
      print "    <limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/>"
      print "  </joint>"
    }
    print "</robot>"
  }' >"$out"
}

inheritance() {
  local n=$1 out=$2
  awk -v n="$n" 'BEGIN {
    print "M0:\n    a0 is Real: 0"
    for (i = 1; i < n; ++i) printf "M%d is M%d:\n    a%d is Real: %d\n", i, i - 1, i, i
    printf "Scene is M%d\n", n - 1
  }' >"$out"
}

# "seconds peak_kb exit_status" of one run.
run_once() {
  local status=0
  /usr/bin/time -f '%e %M' -o "$work/time" "$converter" "$1" -o "$work/out.xml" >/dev/null 2>"$work/stderr" ||
    status=$?
  echo "$(tail -1 "$work/time") $status"
}

# Prints one table row; leaves the median time in $work/last.
measure() {
  local label=$1 input=$2 times=() peak=0 status=0
  for ((i = 0; i < runs; ++i)); do
    read -r t m status < <(run_once "$input")
    times+=("$t")
    ((m > peak)) && peak=$m
  done
  local median
  median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
  local outcome="MJCF written"
  if ((status != 0)); then
    outcome=$(grep -a -m1 -o 'error: .*' "$work/stderr" | cut -c1-90)
  fi
  awk -v l="$label" -v s="$(du -k "$input" | cut -f1)" -v t="$median" -v m="$peak" -v o="$outcome" 'BEGIN {
    printf "| %s | %.1f MB | %.2f s | %.0f MB | %s |\n", l, s / 1024, t, m / 1024, o
  }'
  echo "$median" >"$work/last"
}

growth() {
  awk -v a="$2" -v b="$3" -v l="$1" 'BEGIN {
    printf "%s: %.1fx the time for 10x the size (linear: 10x)\n", l, (a > 0 ? b / a : 0)
  }'
}

echo "openplx2mjcf, whole process: median of $runs runs, largest peak RSS"
echo
echo "| input | size | time | peak memory | outcome |"
echo "|---|---|---|---|---|"
for n in 1000 10000; do
  urdf "$n" 0 "$work/chain$n.urdf"
  measure "URDF chain, $n links" "$work/chain$n.urdf"
  cp "$work/last" "$work/chain$n"
done
for n in 1000 10000; do
  urdf "$n" 50 "$work/forest$n.urdf"
  measure "URDF forest, $n links (chains of 50)" "$work/forest$n.urdf"
  cp "$work/last" "$work/forest$n"
done
for n in 1000 10000; do
  inheritance "$n" "$work/inheritance$n.openplx"
  measure "inheritance chain, $n models" "$work/inheritance$n.openplx"
  cp "$work/last" "$work/inheritance$n"
done
head -c 100000000 /dev/urandom >"$work/random.openplx"
measure "random bytes" "$work/random.openplx"
tr -d '\000' <"$work/random.openplx" >"$work/random_no_nul.openplx"
measure "random bytes without NUL" "$work/random_no_nul.openplx"
echo
growth "URDF chain, 1,000 to 10,000 links" "$(cat "$work/chain1000")" "$(cat "$work/chain10000")"
growth "URDF forest, 1,000 to 10,000 links" "$(cat "$work/forest1000")" "$(cat "$work/forest10000")"
growth "Inheritance chain, 1,000 to 10,000 models" "$(cat "$work/inheritance1000")" \
  "$(cat "$work/inheritance10000")"
