#!/usr/bin/env bash
# Installs what is missing, builds, and runs a sample model through openplx2mjcf.
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
sample=samples/pendulum.openplx
echo "== openplx2mjcf $sample --dump=values   (the evaluated model)"
build/tools/openplx2mjcf "$sample" --dump=values | grep -v -e marshalling -e '_output' -e '_input' | head -40
echo "== openplx2mjcf $sample --dump=snap     (world frames after SNAP assembly)"
build/tools/openplx2mjcf "$sample" --dump=snap
echo "== $sample: evaluated and assembled. MJCF output and simulation arrive with the emitter and runtime issues."
