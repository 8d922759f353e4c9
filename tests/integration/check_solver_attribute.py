"""Run a deck with vemcontact's default solver choice (--solver auto) and check the
solver that ran, read from the HDF5 results' root attribute `solver` (its first word
is the --solver name).

    usage: check_solver_attribute.py EXE OUTDIR DECK EXPECTED

Exit status 0 when the first word of the attribute is EXPECTED, 1 otherwise.
"""
from __future__ import annotations

import os
import subprocess
import sys

import h5py


def main() -> int:
    exe, outdir, deck, expected = sys.argv[1:5]
    subprocess.run([exe, "-q", "-o", outdir, deck], check=True)
    job = os.path.splitext(os.path.basename(deck))[0]
    with h5py.File(os.path.join(outdir, job + ".h5"), "r") as f:
        solver = f.attrs["solver"]
    solver = solver.decode() if isinstance(solver, bytes) else str(solver)
    print(f"{deck}: solver attribute {solver!r}, expected {expected}")
    return 0 if solver.split()[0] == expected else 1


if __name__ == "__main__":
    sys.exit(main())
