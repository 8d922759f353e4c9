#!/usr/bin/env bash
# Every test: install what is missing, build with runtime checks, run CTest
# (Fortran unit tests, deck runs, Python tests) and print the summary.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh Debug
ctest --test-dir build-debug --output-on-failure -j2 "$@"
