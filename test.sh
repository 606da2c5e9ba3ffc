#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test; then the same suite under ASan+UBSan; then builds
# (does not run) the libFuzzer targets with clang. Each suite runs in random order with an empty TMPDIR of its
# own, so a test that needs another to run first, or leaves files behind, fails here.
#   OPENPLX_SKIP_SANITIZERS=1 ./test.sh   skips the sanitizer pass
#   OPENPLX_SKIP_FUZZ_BUILD=1 ./test.sh   skips the fuzz targets' build
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

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
run_suite build

if [[ "${OPENPLX_SKIP_SANITIZERS:-0}" != "1" ]]; then
  echo "== sanitizer pass (ASan + UBSan)"
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DOPENPLX_SANITIZE=ON -DOPENPLX_BUILD_BENCH=OFF >/dev/null
  cmake --build build-asan -j"$jobs"
  run_suite build-asan ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$PWD/tools/lsan.supp" \
    UBSAN_OPTIONS=print_stacktrace=1
fi

if [[ "${OPENPLX_SKIP_FUZZ_BUILD:-0}" != "1" ]]; then
  # Only the fuzzer targets, configured as tools/fuzz.sh does; tools/fuzz.sh runs them.
  echo "== fuzz targets build (clang, libFuzzer + ASan + UBSan)"
  CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOPENPLX_FUZZ=ON \
    -DOPENPLX_BUILD_BENCH=OFF >/dev/null
  cmake --build build-fuzz -j"$jobs" --target lex_parse_fuzzer evaluate_fuzzer urdf_fuzzer manifest_fuzzer \
    runtime_input_fuzzer
fi
tools/check-format.sh
echo "== all tests passed"
