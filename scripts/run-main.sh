#!/usr/bin/env bash
# The main job: install what is missing, build, run the default example deck,
# draw its pictures, and say where the results are.
#   usage: scripts/run-main.sh [DECK]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh Release
deck=${1:-inputs/dam_joint.inp}
job=$(basename "$deck" .inp)
out=out/$job
echo "== running $deck"
./build/vemcontact -o "$out" "$deck"
echo "== pictures"
plot=(.venv/bin/vc-plot "$out/$job.pvd" -o "$out/pictures")
if [ "$deck" = inputs/dam_joint.inp ]; then
  # the paper's figures 13 and 14: displacements and principal stresses of the
  # full-reservoir step, with the joint drawn
  "${plot[@]}" --field U:x --field U:y --field S1 --field S3 --units m,Pa --line 4,10,10,4
else
  "${plot[@]}" --deformed auto
fi
echo "== results of $deck: $PWD/$out ($job.pvd for ParaView, $job.h5, $job.log, pictures/)"
