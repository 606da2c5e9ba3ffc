#!/usr/bin/env bash
# Installs what is missing, builds, and runs a sample model through openplx2mjcf.
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
sample=samples/pendulum.openplx
echo "== openplx2mjcf $sample --dump=ast"
build/tools/openplx2mjcf "$sample" --dump=ast
echo "== checked $sample: OK (MJCF output and simulation arrive with the emitter and runtime issues)"
