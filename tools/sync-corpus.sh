#!/usr/bin/env bash
# Refreshes tests/corpus from ../shared/corpus (the source of truth), keeping VENDORED.md.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -d ../shared/corpus ]] || { echo "error: ../shared/corpus not found" >&2; exit 1; }
find tests/corpus -mindepth 1 ! -name VENDORED.md -delete
cp -a ../shared/corpus/. tests/corpus/
echo "tests/corpus refreshed from ../shared/corpus"
