#!/usr/bin/env python3
"""Write the linear cantilever of the CalculiX comparison as two decks on one mesh.

    make_cantilever.py N OUTDIR [--residual U.npy]

An N x N structured mesh of CPE4 quads on the square [0, L] x [0, L] (L = 10,
E = 1000, nu = 0.3, plane strain, thickness 1), clamped at x = 0 (u = v = 0 on
every node of that edge) and loaded by a total tip shear P = -1 on x = L as the
consistent nodal loads of a uniform traction (P/N per interior node, half at the
two corners).  Written:

    OUTDIR/mesh.inp     nodes, elements and node sets (shared by both decks)
    OUTDIR/vc.inp       the vemcontact deck
    OUTDIR/ccx.inp      the CalculiX deck: the same lines plus *NODE PRINT, U

The two decks differ only in that output request (vemcontact has no *NODE PRINT;
it writes every field).  Node ids are i + (N+1) j + 1, element ids row by row,
counter-clockwise (S1 on y = 0).

With --residual U.npy (an array (nnode, 2) of displacements, e.g. vemcontact's)
a third deck OUTDIR/ccx_res.inp prescribes those displacements (to 14 digits, the most a 20-character field of CalculiX holds) on
every node except one dof, and asks CalculiX for the nodal forces RF = K u: the
difference from the applied loads is the residual of our solution in CalculiX's
stiffness, a check at machine precision that CalculiX's printed 7 digits of U
cannot give.
"""
import argparse
import pathlib

import numpy as np

L = 10.0
E, NU = 1000.0, 0.3
P = -1.0


def mesh_lines(n):
    h = L / n
    out = ["*NODE, NSET=NALL"]
    for j in range(n + 1):
        for i in range(n + 1):
            out.append(f"{i + (n + 1) * j + 1}, {float(i * h)!r}, {float(j * h)!r}")
    out.append("*ELEMENT, TYPE=CPE4, ELSET=EALL")
    e = 0
    for j in range(n):
        for i in range(n):
            e += 1
            a = i + (n + 1) * j + 1
            out.append(f"{e}, {a}, {a + 1}, {a + n + 2}, {a + n + 1}")
    out.append("*NSET, NSET=CLAMP, GENERATE")
    out.append(f"1, {n * (n + 1) + 1}, {n + 1}")
    out.append("*NSET, NSET=TIP, GENERATE")
    out.append(f"{n + 1}, {(n + 1) ** 2}, {n + 1}")
    return out


def tip_loads(n):
    """(node id, fy) of the consistent loads of a uniform shear traction."""
    return [((n + 1) * (j + 1), P / n * (0.5 if j in (0, n) else 1.0)) for j in range(n + 1)]


def model_lines(n):
    return [
        "*MATERIAL, NAME=STEEL",
        "*ELASTIC",
        f"{float(E)!r}, {float(NU)!r}",
        "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
        "1.0",
        "*BOUNDARY",
        "CLAMP, 1, 2",
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", type=int)
    ap.add_argument("outdir", type=pathlib.Path)
    ap.add_argument("--residual", type=pathlib.Path)
    a = ap.parse_args()
    n = a.n
    a.outdir.mkdir(parents=True, exist_ok=True)
    (a.outdir / "mesh.inp").write_text("\n".join(mesh_lines(n)) + "\n")
    head = [
        f"** cantilever {n} x {n} CPE4, L = {L}, E = {E}, nu = {NU}, tip shear {P}",
        "*INCLUDE, INPUT=mesh.inp",
    ] + model_lines(n)
    step = ["*STEP", "*STATIC", "*CLOAD"] + [f"{k}, 2, {float(f)!r}" for k, f in tip_loads(n)]
    (a.outdir / "vc.inp").write_text("\n".join(head + step + ["*END STEP"]) + "\n")
    (a.outdir / "ccx.inp").write_text(
        "\n".join(head + step + ["*NODE PRINT, NSET=NALL", "U", "*END STEP"]) + "\n")
    if a.residual:
        u = np.load(a.residual)
        nn = (n + 1) ** 2
        assert u.shape == (nn, 2), u.shape
        free = n + 1  # the tip's bottom node keeps its x dof free (CalculiX needs one unknown)
        lines = ["** residual check: vemcontact's displacements prescribed", "*INCLUDE, INPUT=mesh.inp"]
        lines += model_lines(n) + ["*STEP", "*STATIC", "*BOUNDARY"]
        for k in range(1, nn + 1):
            for d in (1, 2):
                if k == free and d == 1:
                    continue
                lines.append(f"{k}, {d}, {d}, {u[k - 1, d - 1]:.13e}")  # CalculiX reads 20 characters
        lines += ["*NODE PRINT, NSET=NALL", "RF", "*END STEP"]
        (a.outdir / "ccx_res.inp").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
