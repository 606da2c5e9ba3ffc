#!/usr/bin/env bash
# URDF robots: our whole process (`openplx2mjcf robot.urdf -o robot.xml`) against MuJoCo's own URDF importer
# (`mujoco-compile robot.urdf robot.mjb`) on the same files, side by side in one run.
#
#   bench/urdf_import_speed.sh [BUILD_DIR] [URDF_OR_FOLDER...]    default: build, and the URDFs below
#   RUNS=N (default 5): timed runs per command and file, after one untimed round that also decides "loads".
#   TASKSET=CPU: both commands pinned to that CPU (TASKSET=0: "on one core").
#   MESHDIR=0: MuJoCo reads every URDF as it is (see below).
#
# URDFs: tests/urdf/robots, tests/corpus/urdf and ../shared/corpus/urdf (every *.urdf below them); a file
# whose bytes are those of one already listed is left out (tests/corpus/urdf is a copy of the shared corpus).
# Some are urdfdom's deliberately broken test files: both tools refuse them, and they still count (a user
# waits for a refusal too), but the totals over the files both load are printed apart.
#
# Meshes: MuJoCo's URDF importer drops the folder of a mesh's file name (`meshes/link_0.stl` is looked for as
# `link_0.stl` beside the URDF, `package://` the same), so it fails at once on most robots with meshes and a
# time for that failure says nothing. Where all of a URDF's meshes lie in one folder, MuJoCo is given a copy
# of the URDF with `<mujoco><compiler meshdir="that folder"/></mujoco>` (MuJoCo's own URDF extension), which
# is what its users write; the "MuJoCo reads" column says so ("meshdir"). MESHDIR=0 turns this off.
#
# The two commands take turns, file by file and run by run (A B B A ...), and each run is timed by bash's own
# clock (EPOCHREALTIME) around the process, with its output files removed first: a virtual machine's speed
# drifts by tens of percent over seconds, so a harness that runs all of one before the other compares two
# different machines. CPU time (user + system, bash's `time`, 1 ms resolution) is printed too: on a machine
# shared with other work, wall time also holds the waits for a CPU, and a process that hands work to another
# thread and waits for it can wait twice.
#
# "Loads": ours exits 0 and wrote the MJCF; MuJoCo's prints "Done" and no "Error" (mujoco-compile exits 0 even
# when it fails) and wrote the .mjb. Exits 0 unless a binary is missing (2): a bench, not a test.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 2
root=$PWD
build=build
if (($# > 0)) && [[ -d $1 ]] && [[ -e $1/tools/openplx2mjcf || -e $1/CMakeCache.txt ]]; then
  build=$1
  shift
fi
runs=${RUNS:-5}
meshdir_help=${MESHDIR:-1}
converter=$build/tools/openplx2mjcf
if [[ ! -x $converter ]]; then
  echo "error: $converter is missing or not executable: build it (cmake --build $build --target openplx2mjcf)" >&2
  echo "       or pass the build folder as the first argument" >&2
  exit 2
fi
converter=$(realpath "$converter")
mujoco=$(command -v mujoco-compile || true)
if [[ -z $mujoco ]]; then
  echo "error: mujoco-compile is missing (package libmujoco-samples; tools/install-deps.sh installs it)" >&2
  exit 2
fi
pin=()
if [[ -n ${TASKSET:-} ]]; then
  command -v taskset >/dev/null || { echo "error: TASKSET is set but taskset is missing" >&2; exit 2; }
  pin=(taskset -c "$TASKSET")
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The URDFs, deduplicated by content (the first path found is kept).
sources=("$@")
((${#sources[@]})) || sources=(tests/urdf/robots tests/corpus/urdf ../shared/corpus/urdf)
files=()
declare -A seen=()
for source in "${sources[@]}"; do
  [[ -e $source ]] || { echo "note: $source does not exist; skipped" >&2; continue; }
  while IFS= read -r f; do
    sum=$(sha1sum <"$f" | cut -d' ' -f1)
    [[ -n ${seen[$sum]:-} ]] && continue
    seen[$sum]=1
    files+=("$f")
  done < <(find "$source" -name '*.urdf' -type f | LC_ALL=C sort)
done
if ((${#files[@]} == 0)); then
  echo "no URDF found under: ${sources[*]}" >&2
  exit 0
fi

# What MuJoCo reads for URDF $1: the file itself, or (see "Meshes" above) a copy in $2 with a meshdir.
mujoco_input() {
  local f=$1 copy=$2 dir name rest found d folder meshdir=""
  dir=$(cd "$(dirname "$f")" && pwd)
  if [[ $meshdir_help != 1 ]] || grep -q '<mujoco' "$f"; then echo "$f"; return; fi
  while IFS= read -r name; do
    name=${name#file://}
    found=""
    if [[ $name == package://* ]]; then  # the first of the URDF's folder and those above it holding the rest
      rest=${name#package://}
      rest=${rest#*/}
      d=$dir
      while :; do
        [[ -e $d/$rest ]] && { found=$d/$rest; break; }
        [[ $d == / ]] && break
        d=$(dirname "$d")
      done
    elif [[ $name == /* ]]; then
      found=$name
    else
      found=$dir/$name
    fi
    [[ -n $found && -e $found ]] || { echo "$f"; return; }
    folder=$(cd "$(dirname "$found")" && pwd)
    [[ -z $meshdir || $meshdir == "$folder" ]] || { echo "$f"; return; }
    meshdir=$folder
  done < <(grep -o 'filename="[^"]*"' "$f" | sed 's/^filename="//; s/"$//' | sort -u)
  if [[ -z $meshdir || $meshdir == "$dir" ]]; then echo "$f"; return; fi
  sed "0,/<robot\\b[^>]*>/s||&<mujoco><compiler meshdir=\"$meshdir\"/></mujoco>|" "$f" >"$copy"
  if grep -q '<mujoco><compiler meshdir' "$copy"; then echo "$copy"; else echo "$f"; fi
}

clean() { rm -rf "$work/out"; mkdir "$work/out"; }
# "wall_ms cpu_ms" of one run; the command's outputs are removed first, as a user's run finds none.
timed() {
  clean
  local start end cpu TIMEFORMAT='%3U %3S'
  start=$EPOCHREALTIME
  { time "${pin[@]}" "$@" >/dev/null 2>&1 </dev/null; } 2>"$work/cpu"
  end=$EPOCHREALTIME
  cpu=$(tail -1 "$work/cpu")
  awk -v a="$start" -v b="$end" -v c="$cpu" 'BEGIN { split(c, t, " "); printf "%.3f %.0f\n", (b - a) * 1000, (t[1] + t[2]) * 1000 }'
}
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print 0; else print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "URDF import: openplx2mjcf FILE -o X.xml against mujoco-compile FILE X.mjb"
echo "converter: $converter (built $(date -r "$converter" '+%Y-%m-%d %H:%M'))"
echo "mujoco-compile: $mujoco; $(nproc) CPUs, $(uname -r), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); ${pin[*]:-not pinned}; load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "date: $(date '+%Y-%m-%d %H:%M %Z'); commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' (working tree differs)')"
echo "medians of $runs runs taking turns (A B B A ...), after one untimed round; ${#files[@]} URDFs"
echo
echo "| URDF | ours loads | MuJoCo's loads | MuJoCo reads | ours ms | MuJoCo's ms | ratio | ours CPU ms | MuJoCo's CPU ms |"
echo "|---|---|---|---|---:|---:|---:|---:|---:|"

results=$work/results  # one line per file: both_load ours_ms theirs_ms ours_cpu theirs_cpu
: >"$results"
for f in "${files[@]}"; do
  input=$(mujoco_input "$f" "$work/$(basename "$f")")
  reads="as is"
  [[ $input != "$f" ]] && reads=meshdir
  # The untimed round: does each load (and the files and binaries are in the page cache).
  clean
  ours_ok=no
  if "${pin[@]}" "$converter" "$f" -o "$work/out/robot.xml" >"$work/ours.log" 2>&1 </dev/null &&
    [[ -s $work/out/robot.xml ]]; then ours_ok=yes; fi
  clean
  theirs_ok=no
  ( "${pin[@]}" "$mujoco" "$input" "$work/out/robot.mjb" >"$work/theirs.log" 2>&1 </dev/null; echo $? >"$work/status" ) 2>/dev/null
  status=$(cat "$work/status")
  if grep -q '^Done' "$work/theirs.log" && ! grep -qi 'error' "$work/theirs.log" &&
    [[ -s $work/out/robot.mjb ]]; then
    theirs_ok=yes
  elif ((status > 128)); then
    theirs_ok="no (signal $((status - 128)))"
  fi

  a=() b=() ac=() bc=()
  for ((i = 0; i < runs; ++i)); do
    if ((i % 2)); then
      read -r tb cb < <(timed "$mujoco" "$input" "$work/out/robot.mjb")
      read -r ta ca < <(timed "$converter" "$f" -o "$work/out/robot.xml")
    else
      read -r ta ca < <(timed "$converter" "$f" -o "$work/out/robot.xml")
      read -r tb cb < <(timed "$mujoco" "$input" "$work/out/robot.mjb")
    fi
    a+=("$ta") b+=("$tb") ac+=("$ca") bc+=("$cb")
  done
  ma=$(printf '%s\n' "${a[@]}" | median)
  mb=$(printf '%s\n' "${b[@]}" | median)
  mac=$(printf '%s\n' "${ac[@]}" | median)
  mbc=$(printf '%s\n' "${bc[@]}" | median)
  both=0
  [[ $ours_ok == yes && $theirs_ok == yes ]] && both=1
  echo "$both $ma $mb $mac $mbc" >>"$results"
  name=${f#../shared/corpus/}
  awk -v n="$name" -v oa="$ours_ok" -v ob="$theirs_ok" -v r="$reads" -v a="$ma" -v b="$mb" -v c="$mac" -v d="$mbc" 'BEGIN {
    printf "| %s | %s | %s | %s | %.1f | %.1f | %.2fx | %g | %g |\n", n, oa, ob, r, a, b, (b > 0 ? a / b : 0), c, d
  }'
done

echo
awk '
  function med(v, n,   i, j, t) {  # median of v[1..n]
    for (i = 2; i <= n; ++i) { t = v[i]; for (j = i - 1; j >= 1 && v[j] > t; --j) v[j + 1] = v[j]; v[j + 1] = t }
    return n == 0 ? 0 : (n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2)
  }
  function row(what, n, a, b) { printf "| %s (%d files) | %.1f ms | %.1f ms | **%.2fx** |\n", what, n, a, b, (b > 0 ? a / b : 0) }
  {
    n++; A += $2; B += $3; AC += $4; BC += $5; a[n] = $2; b[n] = $3; ac[n] = $4; bc[n] = $5
    if ($1) { m++; A2 += $2; B2 += $3; AC2 += $4; BC2 += $5; a2[m] = $2; b2[m] = $3; ac2[m] = $4; bc2[m] = $5 }
  }
  END {
    print "| over | ours | MuJoCo'"'"'s | ratio |"
    print "|---|---:|---:|---:|"
    row("wall, total, all files", n, A, B)
    row("wall, total, files both load", m, A2, B2)
    row("wall, median per robot, all files", n, med(a, n), med(b, n))
    row("wall, median per robot, files both load", m, med(a2, m), med(b2, m))
    row("CPU, total, all files", n, AC, BC)
    row("CPU, total, files both load", m, AC2, BC2)
    row("CPU, median per robot, all files", n, med(ac, n), med(bc, n))
    row("CPU, median per robot, files both load", m, med(ac2, m), med(bc2, m))
  }' "$results"
exit 0
