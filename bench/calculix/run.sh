#!/usr/bin/env bash
# vemcontact against CalculiX (issue 6, part 4; issue 15): the linear CPE4 cantilever,
# the Voronoi cantilever (VEM polygons against the same mesh as CPE3 triangles) and
# Hertz contact: wall time, peak memory, agreement and tip errors.  One command:
#   bash bench/calculix/run.sh [--sizes N ...] [--voronoi CELLS ...] [--hertz MESH ...]
#                              [--rounds R] [--residual-max N]   (compare.py --help)
# installs calculix-ccx and time (Debian packages) if missing, builds vemcontact
# Release if needed, and writes bench/results/calculix_*.csv,
# bench/calculix/figures/calculix_scaling.png and docs/calculix-comparison.md.
# About 15 minutes on 2 cores; ccx needs about 8 GB at 500 x 500 CPE4 and about
# 15 GB on the 125 000-cell Voronoi mesh as CPE3.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v ccx >/dev/null || ! [ -x /usr/bin/time ]; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq calculix-ccx time >/dev/null
fi
[ -x .venv/bin/python ] || bash scripts/install-deps.sh
bash scripts/build.sh Release >/dev/null   # incremental: rebuilds what changed, if anything
PYTHONPATH=postprocess .venv/bin/python bench/calculix/compare.py "$@"
