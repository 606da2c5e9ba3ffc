#!/usr/bin/env bash
# Installs what is missing, builds with -Werror and runs every test (gcc, Release, build/); then builds the
# same suite and the libFuzzer targets in one clang build with ASan+UBSan (build-asan/: the libraries compiled
# once, with libFuzzer's coverage instrumentation, for both) and runs the suite there. Each suite runs in
# random order with an empty TMPDIR of its own, so a test that needs another to run first, or leaves files
# behind, fails here. tools/fuzz.sh runs the fuzz targets (in build-asan/, configured as here).
#   OPENPLX_SKIP_SANITIZERS=1 ./test.sh   skips the sanitizer pass (and the fuzz targets)
#   OPENPLX_SKIP_FUZZ_BUILD=1 ./test.sh   the sanitizer pass without the fuzz targets
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh --fuzz --tests
jobs=$(nproc)

# run_suite BUILD_DIR [VAR=VALUE]...: ctest in random order with a fresh empty TMPDIR, which must be empty again
# afterwards.
run_suite() {
  local build=$1 tmp
  shift
  tmp=$(mktemp -d)
  (cd "$build" && env TMPDIR="$tmp" "$@" ctest --output-on-failure -j"$jobs" --schedule-random)
  if [[ -n "$(ls -A "$tmp")" ]]; then
    echo "error: the tests left files in their TMPDIR $tmp:" >&2
    ls -A "$tmp" >&2
    exit 1
  fi
  rmdir "$tmp"
  # MuJoCo writes MUJOCO_LOG.TXT into the working folder unless its handlers are replaced: ours are, everywhere.
  local logs
  logs=$(find "$build" . -maxdepth 4 -name MUJOCO_LOG.TXT 2>/dev/null || true)
  if [[ -n "$logs" ]]; then
    echo "error: a test made MuJoCo write its log file (its warning/error handlers were not ours):" >&2
    echo "$logs" >&2
    exit 1
  fi
}

# ./run.sh configures build/ without the tests and benchmarks: they are turned on again here.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DOPENPLX_BUILD_TESTS=ON -DOPENPLX_BUILD_BENCH=ON \
  -DOPENPLX_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
run_suite build

if [[ "${OPENPLX_SKIP_SANITIZERS:-0}" != "1" ]]; then
  fuzz=ON
  [[ "${OPENPLX_SKIP_FUZZ_BUILD:-0}" != "1" ]] || fuzz=OFF
  echo "== sanitizer pass (clang, ASan + UBSan; fuzz targets: $fuzz)"
  # A build-asan/ configured with another compiler (gcc, before the fuzz targets moved here) starts afresh.
  if [[ -f build-asan/CMakeCache.txt ]] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt; then
    rm -rf build-asan
  fi
  # tools/fuzz.sh configures build-asan/ with the same options (keep them in step).
  CXX=clang++ CC=clang cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DOPENPLX_SANITIZE=ON \
    -DOPENPLX_FUZZ="$fuzz" -DOPENPLX_BUILD_TESTS=ON -DOPENPLX_BUILD_BENCH=OFF -DOPENPLX_WERROR=ON >/dev/null
  cmake --build build-asan -j"$jobs"
  run_suite build-asan ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$PWD/tools/lsan.supp" \
    UBSAN_OPTIONS=print_stacktrace=1
fi
tools/check-format.sh
tools/check-readmes.sh
echo "== all tests passed"
