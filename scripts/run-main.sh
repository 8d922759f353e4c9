#!/usr/bin/env bash
# The main job: install what is missing, build, run the default example deck,
# and say where the results are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh Release
deck=${1:-inputs/example1_cantilever.inp}
out=out/$(basename "$deck" .inp)
echo "== running $deck"
./build/vemcontact -o "$out" "$deck"
echo "== results of $deck are in $PWD/$out (open the .pvd in ParaView)"
