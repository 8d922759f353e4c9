#!/usr/bin/env bash
# The main job: install what is missing, build, run the default example deck,
# draw its pictures, and say where the results are.
#   usage: scripts/run-main.sh [DECK]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh Release
deck=${1:-inputs/block_selfweight.inp}
job=$(basename "$deck" .inp)
out=out/$job
echo "== running $deck"
./build/vemcontact -o "$out" "$deck"
echo "== pictures"
PYTHONPATH=postprocess .venv/bin/python -m vctools.plot "$out/$job.pvd" --deformed auto -o "$out/pictures"
echo "== results of $deck: $PWD/$out ($job.pvd for ParaView, $job.h5, $job.log, pictures/)"
