#!/usr/bin/env bash
# Accuracy against cost (issue 6): error against unknowns and wall time for VEM on
# Voronoi meshes, VEM on quads, FEM quads and FEM triangles on five cases with known
# answers.  Writes bench/results/accuracy*.csv, docs/figures/accuracy_*.png and
# docs/accuracy-vs-speed.md.  Work files (meshes, decks, results) in out/accuracy/.
#   usage: bash bench/accuracy/run.sh [--quick] [--repeat N] [--cases manufactured,...]
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x build/vemcontact ] || bash scripts/build.sh Release >/dev/null
[ -x .venv/bin/python ] || { echo "no .venv: run scripts/run-main.sh or scripts/run-tests.sh once" >&2; exit 1; }
PYTHONPATH=postprocess .venv/bin/python bench/accuracy/main.py "$@"
