#!/usr/bin/env bash
# Builds a libFuzzer target with clang (ASan+UBSan) and runs it.
#   tools/fuzz.sh [SECONDS] [TARGET]   (default 600 s, lex_parse_fuzzer; or evaluate_fuzzer, urdf_fuzzer,
#                                       manifest_fuzzer, runtime_input_fuzzer, mesh_fuzzer).
# Crashes land in fuzz-out/TARGET/crashes; add fixed ones to tests/fuzz/regressions.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
target=${2:-lex_parse_fuzzer}
tools/install-deps.sh --fuzz
# The sanitizer build ./test.sh makes (build-asan/, the same options: keep them in step), which holds the
# fuzz targets: after ./test.sh, only the target's link is left to do.
if [[ -f build-asan/CMakeCache.txt ]] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt; then
  rm -rf build-asan
fi
CXX=clang++ CC=clang cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DOPENPLX_SANITIZE=ON \
  -DOPENPLX_FUZZ=ON -DOPENPLX_BUILD_TESTS=ON -DOPENPLX_BUILD_BENCH=OFF -DOPENPLX_WERROR=ON >/dev/null
cmake --build build-asan --target "$target" -j"$(nproc)"
corpus_dir=$(sed -n 's/^OPENPLX_CORPUS_DIR:PATH=//p' build-asan/CMakeCache.txt)
out=fuzz-out/$target
mkdir -p "$out/corpus" "$out/crashes"
# Seeds: the real files, the reconstructed seed snippets and the saved regressions.
dict=
extra=()
if [ "$target" = urdf_fuzzer ]; then
  find "$corpus_dir/urdf" tests/fuzz/regressions -name '*.urdf' -exec cp {} "$out/corpus/" \;
  dict=tests/fuzz/urdf.dict
elif [ "$target" = manifest_fuzzer ]; then
  # The emitter's manifests and the hostile ones (empty names, laws short of actuators, another model's).
  find tests/golden/mjcf tests/fuzz/regressions -name '*.signals.json' -exec cp {} "$out/corpus/" \;
elif [ "$target" = mesh_fuzzer ]; then
  # A sound tetrahedron in each format, and the hostile files (tests/fuzz/fuzz_mesh.h lays out their
  # neighbours). The reader's children may ask for more than the parent's RSS limit: that is theirs to fail
  # on (a problem), not an out-of-memory report of the fuzzer's. Every input forks a reader: a small
  # quarantine keeps the fuzzer small and its forks cheap (about twice the executions).
  find tests/fuzz/mesh_seeds -type f ! -name README.md -exec cp {} "$out/corpus/" \;
  find tests/fuzz/regressions -name 'mesh_*' -exec cp {} "$out/corpus/" \;
  dict=tests/fuzz/mesh.dict
  extra=(-malloc_limit_mb=1048576)
  export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}quarantine_size_mb=16
elif [ "$target" = runtime_input_fuzzer ]; then
  # Programs of input sets and steps (gears of 2^31 and 1e300, fractions of 5, NaN, huge velocities).
  find tests/fuzz/regressions -name '*.runtime' -exec cp {} "$out/corpus/" \;
else
  find "$corpus_dir" tests/seed_snippets tests/fuzz/regressions -name '*.openplx' -exec cp {} "$out/corpus/" \;
  dict=tests/fuzz/openplx.dict
fi
# urdfdom leaks its half-built tree on the URDFs it rejects, assimp parts of a scene (tools/lsan.supp says
# more): not ours to report, nor to list after every input that leaks.
LSAN_OPTIONS=suppressions="$PWD/tools/lsan.supp":print_suppressions=0 \
  "build-asan/tests/fuzz/$target" "$out/corpus" ${dict:+-dict="$dict"} \
  -max_total_time="$seconds" -timeout=2 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
  -artifact_prefix="$out/crashes/" ${extra[@]+"${extra[@]}"}
