#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test; then the same suite under ASan+UBSan.
#   OPENPLX_SKIP_SANITIZERS=1 ./test.sh   skips the sanitizer pass
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")

if [[ "${OPENPLX_SKIP_SANITIZERS:-0}" != "1" ]]; then
  echo "== sanitizer pass (ASan + UBSan)"
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DOPENPLX_SANITIZE=ON -DOPENPLX_BUILD_BENCH=OFF >/dev/null
  cmake --build build-asan -j"$jobs"
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$PWD/../tools/lsan.supp" \
    UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j"$jobs")
fi
tools/check-format.sh
echo "== all tests passed"
