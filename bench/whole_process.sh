#!/usr/bin/env bash
# What a user sees: `openplx2mjcf model.openplx -o model.xml` as a whole process, against MuJoCo's own
# compiler (`mujoco-compile model.xml model.mjb`) on the file we wrote, in the same run. Prints medians, their
# ratio, and each process's peak memory (GNU time).
#
# The two commands take turns, run by run (A B B A ...): a virtual machine's speed drifts by tens of percent
# over seconds, and a harness that runs all of one command before the other (hyperfine does) then compares
# two different machines. Each run is timed by bash's own clock around the process (no helper process).
#
#   bench/whole_process.sh [BUILD_DIR]     default: build
#   RUNS=N (default 7) sets the runs per command (after two warm-up rounds).
#
# Models: 1,000 and 10,000 hinged boxes on the world (generated here), docs/performance.md's wide tree of trunks with
# nine branches (1,000 bodies), small corpus models and two of bullet3's URDF robots.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
converter=$(realpath "$build/tools/openplx2mjcf")
runs=${RUNS:-7}
for tool in mujoco-compile /usr/bin/time; do
  command -v "$tool" >/dev/null || { echo "error: $tool is missing (tools/install-deps.sh installs it)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# N boxes, each hanging from its own world connector by a hinge: a plain model, nothing shared but types.
boxes() {
  local n=$1 out=$2
  {
    printf 'Link is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n'
    printf '    geometry is Physics3D.Geometries.Box:\n        size: {0.1, 0.1, 1}\n'
    printf '    top is Physics3D.Interactions.MateConnector:\n        position: {0, 0, 0.5}\n'
    printf '        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.Z_AXIS()\n'
    printf 'Scene is Physics3D.System:\n'
    awk -v n="$n" 'BEGIN {
      for (i = 0; i < n; ++i) {
        printf "    l%d is Link\n", i
        printf "    w%d is Physics3D.Interactions.MateConnector:\n", i
        printf "        position: {%d, %d, 2}\n", i % 32, int(i / 32)
        printf "        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.Z_AXIS()\n"
        printf "    h%d is Physics3D.Interactions.Hinge:\n        connectors: [l%d.top, w%d]\n", i, i, i
      }
    }'
  } >"$out"
}

# The wide tree of bench/model_generator.h (generate_mechanism): trunks on the world, nine branches each.
tree() {
  local bodies=$1 out=$2
  {
    printf 'Link is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n'
    printf '    geometry is Physics3D.Geometries.Box:\n        size: {0.1, 0.1, 1}\n'
    printf '    bottom is Physics3D.Interactions.MateConnector:\n'
    printf '        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.Z_AXIS()\n'
    printf '    top is Physics3D.Interactions.MateConnector:\n        position: {0, 0, 1}\n'
    printf '        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.Z_AXIS()\n'
    printf 'Scene is Physics3D.System:\n'
    awk -v n="$bodies" 'BEGIN {
      for (t = 0; t < n / 10; ++t) {
        printf "    base%d is Physics3D.Interactions.MateConnector:\n", t
        printf "        position: {%d, 0, 0}\n        main_axis: Math.Vec3.Y_AXIS()\n", 2 * t
        printf "        normal: Math.Vec3.Z_AXIS()\n"
        printf "    t%d is Link\n    ht%d is Physics3D.Interactions.Hinge:\n", t, t
        printf "        connectors: [t%d.bottom, base%d]\n", t, t
        for (b = 0; b < 9; ++b) {
          printf "    b%d_%d is Link\n    hb%d_%d is Physics3D.Interactions.Hinge:\n", t, b, t, b
          printf "        connectors: [b%d_%d.bottom, t%d.top]\n", t, b, t
        }
      }
    }'
  } >"$out"
}

peak_kb() { /usr/bin/time -f '%M' "$@" 2>&1 >/dev/null | tail -1; }

# Wall-clock milliseconds of one run of a command (its output files removed first, as a user's run finds them).
time_ms() {
  rm -f "$work/out.mjb" "$work/out.xml" "$work/out.signals.json"
  local start=$EPOCHREALTIME
  "$@" >/dev/null 2>&1
  local end=$EPOCHREALTIME
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f\n", (b - a) * 1000 }'
}

median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# One model: convert once (the MJCF is MuJoCo's input), then time both processes taking turns.
measure() {
  local label=$1 model=$2
  local xml=$work/$(basename "${model%.*}").xml
  "$converter" "$model" -o "$xml" 2>/dev/null
  local ours_runs=() theirs_runs=()
  for ((i = 0; i < runs + 2; ++i)); do
    local a b
    if ((i % 2)); then
      b=$(time_ms mujoco-compile "$xml" "$work/out.mjb")
      a=$(time_ms "$converter" "$model" -o "$work/out.xml")
    else
      a=$(time_ms "$converter" "$model" -o "$work/out.xml")
      b=$(time_ms mujoco-compile "$xml" "$work/out.mjb")
    fi
    ((i < 2)) && continue  # warm-up: the files and the binaries in the page cache
    ours_runs+=("$a")
    theirs_runs+=("$b")
  done
  local ours theirs
  ours=$(printf '%s\n' "${ours_runs[@]}" | median | awk '{ print $1 / 1000 }')
  theirs=$(printf '%s\n' "${theirs_runs[@]}" | median | awk '{ print $1 / 1000 }')
  rm -f "$work/out.mjb"
  local mem_ours mem_theirs
  mem_ours=$(peak_kb "$converter" "$model" -o "$work/out.xml")
  mem_theirs=$(peak_kb mujoco-compile "$xml" "$work/out.mjb")
  rm -f "$work/out.mjb"
  awk -v l="$label" -v a="$ours" -v b="$theirs" -v ma="$mem_ours" -v mb="$mem_theirs" 'BEGIN {
    printf "| %s | %.1f ms | %.1f ms | %.2fx | %.1f MB | %.1f MB | %.2fx |\n", l, a * 1000, b * 1000, a / b,
      ma / 1024, mb / 1024, ma / mb
  }'
  echo "$ours" >"$work/last"
}

echo "openplx2mjcf against mujoco-compile of its own output: medians of $runs runs taking turns, peak RSS"
echo
echo "| model | openplx2mjcf | mujoco-compile | time ratio | peak memory | MuJoCo's | memory ratio |"
echo "|---|---|---|---|---|---|---|"
boxes 1000 "$work/boxes1000.openplx"
measure "1,000 hinged boxes" "$work/boxes1000.openplx"
t1000=$(cat "$work/last")
boxes 10000 "$work/boxes10000.openplx"
measure "10,000 hinged boxes" "$work/boxes10000.openplx"
t10000=$(cat "$work/last")
tree 1000 "$work/tree1000.openplx"
measure "wide tree, 1,000 bodies" "$work/tree1000.openplx"
for small in signal_test simpler_inverted_pendulum; do
  measure "corpus $small" "tests/corpus/agxunity/$small.openplx"
done
for robot in r2d2 kuka_iiwa/model; do
  measure "URDF $robot" "tests/corpus/urdf/bullet3/$robot.urdf"
done
echo
growth() {
  awk -v a="$1" -v b="$2" -v how="$3" 'BEGIN {
    printf "Growth from 1,000 to 10,000 boxes, %s: %.2fx the time for 10x the bodies (linear: 10x; %+.0f%%)\n",
      how, b / a, (b / a / 10 - 1) * 100
  }'
}
growth "$t1000" "$t10000" "as in the table"

# The same growth with the converter alone, the two models taking turns run after run. In the table each
# 10,000-box conversion follows a mujoco-compile of several seconds; a virtual machine whose host takes back
# guest memory left free for a few seconds (free page reporting) then backs every page the conversion touches
# afresh, at several times the cost. Both figures are printed so that the difference is seen, not hidden.
alone1000=() alone10000=()
for ((i = 0; i < runs + 1; ++i)); do
  a=$(time_ms "$converter" "$work/boxes1000.openplx" -o "$work/out.xml")
  b=$(time_ms "$converter" "$work/boxes10000.openplx" -o "$work/out.xml")
  ((i < 1)) && continue
  alone1000+=("$a")
  alone10000+=("$b")
done
growth "$(printf '%s\n' "${alone1000[@]}" | median)" "$(printf '%s\n' "${alone10000[@]}" | median)" \
  "converter alone, run after run"
