"""`--solver auto`'s fallback: when the CG + GAMG that auto chose does not converge,
the step is solved again with CHOLMOD and the results say so.

    usage: solver_fallback.py EXE OUTDIR

Writes a plane-stress bar of 320 x 320 VEM quads (103 041 nodes, 206 082 unknowns:
above auto_gamg_unknowns, so `auto` picks gamg), x in [0, 1], y in [0, 1], E = 1,
nu = 0.25, under uniaxial stretch: u_x = 0 on x = 0, u_x = d on x = 1, u_y = 0 at
the origin.  The exact field u_x = d x, u_y = -nu d y is linear, so the VEM
reproduces it up to the solver's round-off.  The run gets PETSc's option
`-ksp_max_it 2`, which CG cannot meet.

Asserted: exit status 0, the HDF5 root attribute `solver` is cholmod's, and the
displacements are the exact field within 1e-8 relative (CHOLMOD's backward error
times the condition number of this matrix, about 1e5 for h = 1/320, is ~1e-11; a
CG stopped after 2 iterations is off by far more than 1e-8).
"""
from __future__ import annotations

import os
import subprocess
import sys

import h5py
import numpy as np

N = 320
D = 1.0e-3
NU = 0.25
# see the module's docstring
TOL = 1.0e-8


def write_deck(path: str) -> None:
    n1 = N + 1
    i, j = np.meshgrid(np.arange(n1), np.arange(n1), indexing="xy")
    x, y = (i / N).ravel(), (j / N).ravel()
    ids = np.arange(1, n1 * n1 + 1)
    ei, ej = np.meshgrid(np.arange(N), np.arange(N), indexing="xy")
    a = (ej * n1 + ei + 1).ravel()
    conn = np.stack([a, a + 1, a + 1 + n1, a + n1], axis=1)
    left = ids[np.isclose(x, 0.0)]
    right = ids[np.isclose(x, 1.0)]
    with open(path, "w") as f:
        f.write("** solver_fallback.py: plane-stress bar under uniaxial stretch\n*NODE\n")
        np.savetxt(f, np.column_stack([ids, x, y]), fmt=["%d", "%.17g", "%.17g"], delimiter=", ")
        f.write("*ELEMENT, TYPE=VPS, ELSET=ALL\n")
        np.savetxt(f, np.column_stack([np.arange(1, N * N + 1), conn]), fmt="%d", delimiter=", ")
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n1.0, {NU!r}\n*SOLID SECTION, ELSET=ALL, MATERIAL=M\n")
        f.write("*STEP\n*STATIC\n*BOUNDARY\n")
        f.write("1, 2, 2, 0.0\n")
        f.writelines(f"{k}, 1, 1, 0.0\n" for k in left)
        f.writelines(f"{k}, 1, 1, {D!r}\n" for k in right)
        f.write("*END STEP\n")


def main() -> int:
    exe, outdir = sys.argv[1:3]
    os.makedirs(outdir, exist_ok=True)
    deck = os.path.join(outdir, "bar.inp")
    write_deck(deck)
    run = subprocess.run([exe, "-q", "--petsc-options", "-ksp_max_it 2", "-o", outdir, deck],
                         check=False, capture_output=True, text=True)
    if run.returncode != 0:
        print(f"FAIL: exit status {run.returncode}\n{run.stdout}{run.stderr}")
        return 1
    with h5py.File(os.path.join(outdir, "bar.h5"), "r") as f:
        solver = f.attrs["solver"]
        solver = solver.decode() if isinstance(solver, bytes) else str(solver)
        xy = f["mesh/coordinates"][...]
        u = f["steps/0001/U"][...]
    ok = True
    if solver.split()[0] != "cholmod":
        print(f"FAIL: solver attribute {solver!r}, expected cholmod after the fallback")
        ok = False
    exact = np.column_stack([D * xy[:, 0], -NU * D * xy[:, 1]])
    err = np.abs(u - exact).max() / D
    print(f"solver {solver!r}, max |u - exact| / d = {err:.2e} (tolerance {TOL:.0e})")
    if not err <= TOL:
        print("FAIL: the displacements are not the exact field")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
