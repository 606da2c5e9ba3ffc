#!/bin/sh
# A screenshot of each sample as mujoco-simulate first shows it, under a virtual X server (Xvfb), to see that
# the emitted file frames and lights the machine (mjcf_emitter/viewer_defaults.h). Written to OUT_DIR as
# <sample>.png beside the converted <sample>.xml; nothing is compared, the pictures are for looking at.
#   viewer_screenshots.sh CONVERTER SAMPLES_DIR OUT_DIR
# Exits 77 (skipped) when Xvfb, mujoco-simulate, xwd or convert is missing.
set -e
converter=$1
samples=$2
out=$3
for tool in Xvfb mujoco-simulate xwd convert; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "skipped: $tool is not installed (apt-get install xvfb x11-apps imagemagick libmujoco-samples)"
    exit 77
  fi
done
mkdir -p "$out"
# A display number of our own: the process id keeps parallel runs apart.
display=":$(($$ % 500 + 100))"
Xvfb "$display" -screen 0 1920x1200x24 -nolisten tcp >"$out/xvfb.log" 2>&1 &
xvfb=$!
simulate=
cleanup() {
  [ -n "$simulate" ] && kill "$simulate" 2>/dev/null || true
  kill "$xvfb" 2>/dev/null || true
}
trap cleanup EXIT
sleep 1
for model in "$samples"/*.openplx; do
  name=$(basename "$model" .openplx)
  "$converter" "$model" -o "$out/$name.xml" 2>/dev/null
  DISPLAY=$display mujoco-simulate "$out/$name.xml" >"$out/$name.simulate.log" 2>&1 &
  simulate=$!
  sleep 4
  # Without the side panels where xdotool is there to press Tab and Shift+Tab (simulate's own keys).
  if command -v xdotool >/dev/null 2>&1; then
    DISPLAY=$display xdotool search --sync --name Simulate windowfocus --sync key Tab key shift+Tab \
      >/dev/null 2>&1 || true
    sleep 1
  fi
  DISPLAY=$display xwd -root -silent | convert xwd:- "$out/$name.png"
  kill "$simulate" 2>/dev/null || true
  wait "$simulate" 2>/dev/null || true
  simulate=
  echo "$out/$name.png"
done
