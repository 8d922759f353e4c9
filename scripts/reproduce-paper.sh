#!/usr/bin/env bash
# Reproduce the tables and figures of Sun et al. (2022): runs the paper's four
# examples (about 40 runs, each well under a second in Release) and writes
# out/paper/paper-reproduction.md and out/paper/figures/ (give --out docs to update the
# tracked docs/paper-reproduction.md and docs/figures/).  Installs nothing: it needs the
# Python environment of scripts/install-deps.sh (.venv) and builds Release if
# build/vemcontact is missing.
#   usage: scripts/reproduce-paper.sh [options of python -m vctools.paper]
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
  echo "reproduce-paper: no .venv: run bash scripts/install-deps.sh (or scripts/run-main.sh) first" >&2
  exit 1
fi
[ -x build/vemcontact ] || bash scripts/build.sh Release
PYTHONPATH=postprocess exec .venv/bin/python -m vctools.paper --exe build/vemcontact "$@"
