#!/usr/bin/env bash
# Install what vemcontact needs on Debian (bookworm), as root: the compilers and
# libraries from Debian's packages, and the pinned Python packages into .venv.
# Safe to run again: it installs only what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

debs=(ca-certificates gfortran gcc make cmake ninja-build pkg-config libopenblas-dev liblapack-dev
      libsuitesparse-dev libmetis-dev libhdf5-dev libdeflate-dev hdf5-tools python3 python3-venv
      calculix-ccx   # ccx: the CalculiX decks of tests/data/calculix are also run in CalculiX
      calculix-ccx-test   # CalculiX's own test decks and their reference results (postprocess/tests/test_calculix_suite.py)
      petsc-dev)     # optional at build time: --solver gamg|hypre|mumps (PETSc 3.18 with MUMPS, hypre, Open MPI)
missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then echo "error: run as root to install ${missing[*]}" >&2; exit 1; fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Python: Debian's interpreter, pinned packages in a project-local venv.  pip is
# pointed at the system's certificate store so that a site's own CAs (installed
# in /usr/local/share/ca-certificates) are trusted, not only pip's bundled ones.
if [ -z "${PIP_CERT:-}" ] && [ -f /etc/ssl/certs/ca-certificates.crt ]; then
  export PIP_CERT=/etc/ssl/certs/ca-certificates.crt
fi
# The package itself goes in as an editable install (the checkout's postprocess/ is what
# runs), which puts its console scripts vc-plot, vc-curves, vc-compare, vc-adapt, vc-mesh
# and vc-paper into .venv/bin: `source .venv/bin/activate` puts them on the PATH.
req=postprocess/requirements.txt
stamp=.venv/.requirements.sha256
want=$(cat "$req" postprocess/pyproject.toml | sha256sum | cut -d' ' -f1)
if [ ! -x .venv/bin/python ] || [ ! -x .venv/bin/vc-plot ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "== installing Python packages from $req and vctools (editable) into .venv"
  /usr/bin/python3 -m venv .venv
  .venv/bin/python -m pip install -q --disable-pip-version-check -r "$req"
  .venv/bin/python -m pip install -q --disable-pip-version-check --no-deps -e ./postprocess
  echo "$want" > "$stamp"
fi
