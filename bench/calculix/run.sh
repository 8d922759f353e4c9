#!/usr/bin/env bash
# vemcontact against CalculiX on the same CPE4 decks (issue 6, part 4): linear
# cantilever and Hertz contact, wall time, peak memory and agreement.  One command:
#   bash bench/calculix/run.sh [--sizes N ...] [--hertz MESH ...] [--residual-max N]
# installs calculix-ccx and time (Debian packages) if missing, builds vemcontact
# Release if needed, and writes bench/results/calculix_{linear,hertz}.csv,
# bench/calculix/figures/calculix_scaling.png and docs/calculix-comparison.md.
# About 5 minutes on 2 cores; ccx needs about 8 GB at 500 x 500.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v ccx >/dev/null || ! [ -x /usr/bin/time ]; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq calculix-ccx time >/dev/null
fi
[ -x .venv/bin/python ] || bash scripts/install-deps.sh
bash scripts/build.sh Release >/dev/null   # incremental: rebuilds what changed, if anything
PYTHONPATH=postprocess .venv/bin/python bench/calculix/compare.py "$@"
