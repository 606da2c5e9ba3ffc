#!/usr/bin/env bash
# What a user sees: `openplx2mjcf model.openplx -o model.xml` as a whole process, against MuJoCo's own
# compiler (`mujoco-compile model.xml model.mjb`) on the file we wrote, in the same run, interleaved by
# hyperfine. Prints medians, their ratio, and each process's peak memory (GNU time).
#
#   bench/whole_process.sh [BUILD_DIR]     default: build
#   RUNS=N (default 7) sets hyperfine's runs per command.
#
# Models: 1,000 and 10,000 hinged boxes on the world (generated here), the README's wide tree of trunks with
# nine branches (1,000 bodies), small corpus models and two of bullet3's URDF robots.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
converter=$(realpath "$build/tools/openplx2mjcf")
runs=${RUNS:-7}
for tool in hyperfine mujoco-compile /usr/bin/time; do
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

# One model: convert once (the MJCF is MuJoCo's input), then time both processes interleaved.
measure() {
  local label=$1 model=$2
  local xml=$work/$(basename "${model%.*}").xml
  "$converter" "$model" -o "$xml" 2>/dev/null
  # Both write fresh files (mujoco-compile would ask before overwriting; replacing a file makes ext4 flush it).
  hyperfine -N --style none --warmup 2 --runs "$runs" --export-json "$work/h.json" \
    --prepare "rm -f $work/out.mjb $work/out.xml $work/out.signals.json" \
    "$converter $model -o $work/out.xml" "mujoco-compile $xml $work/out.mjb" >/dev/null 2>&1
  local ours theirs
  ours=$(sed -n 's/.*"median": *\([0-9.e-]*\).*/\1/p' "$work/h.json" | sed -n 1p)
  theirs=$(sed -n 's/.*"median": *\([0-9.e-]*\).*/\1/p' "$work/h.json" | sed -n 2p)
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

echo "openplx2mjcf against mujoco-compile of its own output: medians of $runs interleaved runs, peak RSS"
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
awk -v a="$t1000" -v b="$t10000" 'BEGIN {
  printf "Growth from 1,000 to 10,000 boxes: %.2fx the time for 10x the bodies (linear: 10x; %+.0f%%)\n",
    b / a, (b / a / 10 - 1) * 100
}'
