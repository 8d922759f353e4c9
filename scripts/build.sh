#!/usr/bin/env bash
# Configure and build vemcontact.  usage: scripts/build.sh [Release|Debug] (default Release)
# Release goes to build/, Debug (strict flags, runtime checks) to build-debug/.
set -euo pipefail
cd "$(dirname "$0")/.."
type=${1:-Release}
dir=build; [ "$type" = Debug ] && dir=build-debug
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$type" -DVC_PYTHON="$PWD/.venv/bin/python" >/dev/null
cmake --build "$dir"
