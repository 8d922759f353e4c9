"""Example of the Python API (docs/python-api.md): the paper's two-element cantilever
(example 1) built from arrays, run for a sweep of the distortion 2d/b with the
second-order virtual element (VPE2) and the bilinear quad (CPE4), the tip
deflection read back as numpy arrays.

    PYTHONPATH=postprocess python postprocess/examples/cantilever_sweep.py [OUT_DIR]

Exact answer M L^2 / (2 E I) = 0.3: VPE2 reproduces pure bending on any straight-sided
mesh (ratio 1 at every distortion); the bilinear quad on the undistorted mesh gives the
closed form 1/(1 + (L_e/b)^2/2) = 1/4.125 of it (postprocess/tests/test_api.py runs
this script).
"""
from __future__ import annotations

import os
import sys
import tempfile

import numpy as np

import vctools

L, B, E, M = 40.0, 8.0, 1000.0, 16.0
EXACT = M * L**2 / (2 * E * B**3 / 12)          # 0.3


def cantilever(db: float, element: str) -> vctools.Deck:
    """Two quadrilaterals whose shared edge runs from (L/2 - d, 0) to (L/2 + d, b)."""
    d = db * B / 2
    corners = np.array([[0, 0], [L / 2 - d, 0], [L, 0], [L, B], [L / 2 + d, B], [0, B]])
    quads = [[0, 1, 4, 5], [1, 2, 3, 4]]
    deck = vctools.Deck(f"cantilever_{element}_{db:g}".replace(".", "p"))
    if element in ("VPE2", "CPE8"):
        # a node at the middle of every side, numbered after the corners
        sides = {}
        for q in quads:
            for k in range(4):
                sides.setdefault(tuple(sorted((q[k], q[(k + 1) % 4]))), len(corners) + len(sides))
        mids = np.array([(corners[a] + corners[b]) / 2 for a, b in sides])
        deck.nodes(np.vstack([corners, mids]))
        cells = [q + [sides[tuple(sorted((q[k], q[(k + 1) % 4])))] for k in range(4)] for q in quads]
        clamp = [0, 5, sides[(0, 5)]]
    else:
        deck.nodes(corners)
        cells, clamp = quads, [0, 5]
    deck.elements(cells, type=element, elset="BEAM")
    deck.nset("CLAMP", clamp)
    deck.material("UNIT", E=E, nu=0.0)
    deck.section("BEAM", "UNIT", thickness=1.0)
    deck.boundary("CLAMP", 1)
    deck.boundary(0, 2)
    with deck.step("MOMENT") as s:
        s.cload(2, 1, M / B)        # the end moment as a couple on the two tip nodes
        s.cload(3, 1, -M / B)
    return deck


def sweep(out: str, distortions=(0.0, 1.0, 2.0, 4.0), elements=("VPE2", "CPE4")) -> dict:
    """Tip deflection over the exact one, per element type and distortion."""
    ratios = {}
    for element in elements:
        for db in distortions:
            deck = cantilever(db, element)
            res = vctools.run(deck, out=os.path.join(out, deck.name))
            u = res.step("MOMENT")["U"]
            ratios[element, db] = float(u[[2, 3], 1].mean()) / EXACT
    return ratios


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="cantilever-sweep-")
    r = sweep(out)
    print("2d/b   VPE2     CPE4")
    for db in sorted({k[1] for k in r}):
        print(f"{db:4.1f}  {r['VPE2', db]:.4f}  {r['CPE4', db]:.4f}")
