"""NODE TO SURFACE with the Voronoi-meshed disc as the SLAVE of the stiff block, HARD (issue
22's target: at most 10 contact iterations per increment): the deck of
bench/hertz_voronoi_master.py with the pair DSLAVE (the disc's arc on the block's top),
finite sliding and SMALL SLIDING, at several polygon resolutions (narc sides on the half
circle).  Prints per run the increments' iteration counts, the peak CPRESS against p0,
and the step's iteration records (HDF5, /steps/0001/contact/iterations: one row per
iteration), so that one sees which stage holds the run: active-set changes, the largest
overclosure (the multipliers' convergence), the relative residual, the factorizations.

usage: bench/hertz_voronoi_slave.py EXE OUTDIR [narc ...]    (default: 240 480)
Measured (docs/contact-formulation.md, "The multipliers' step with the residual").
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz_voronoi_master import DECK, P0, increments, mesh

COLUMNS = ("iteration", "active", "changed", "factorized", "max_penetration", "max_pressure", "residual")


def run(exe, d, small):
    name = f"dslave_{'small' if small else 'finite'}"
    deck = os.path.join(d, name + ".inp")
    with open(deck, "w") as f:
        f.write(DECK.format(small=", SMALL SLIDING" if small else "", roles="").replace(
            "DMASTER_SLAVE, DMASTER_MASTER", "DSLAVE_SLAVE, DSLAVE_MASTER"))
    r = subprocess.run([exe, "-q", "-o", os.path.join(d, name), deck], capture_output=True, text=True, check=False)
    print(f"{d} {'SMALL SLIDING' if small else 'finite sliding'}: exit {r.returncode}")
    h5 = os.path.join(d, name, name + ".h5")
    if r.returncode != 0 or not os.path.exists(h5):
        print(r.stderr)
        return
    with h5py.File(h5, "r") as f:
        cp = np.array(f["steps/0001/contact/pair_1/CPRESS"])
        print(f"  increments {increments(f)}, peak {cp.max():.10g} ({cp.max() / P0 - 1:+.3%} of p0)")
        g = f["steps/0001/contact/iterations"]
        rec = {c: np.array(g[c]) for c in COLUMNS}
    print("  " + " ".join(f"{c:>15}" for c in COLUMNS))
    for i in range(rec["iteration"].size):
        print("  " + " ".join(f"{rec[c][i]:15.4g}" for c in COLUMNS))


def main():
    exe, out = sys.argv[1], sys.argv[2]
    for arg in sys.argv[3:] or ["240", "480"]:
        d = os.path.join(out, f"narc{arg}")
        mesh(d, int(arg))
        for small in (False, True):
            run(exe, d, small)


if __name__ == "__main__":
    main()
