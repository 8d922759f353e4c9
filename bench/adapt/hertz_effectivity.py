"""Effectivity of the error estimate on the Hertz contact (the paper's half model, VEM quads,
NTS penalty: bench/accuracy's Hertz decks), against a reference solution on the finest mesh
of the family (the 600-element mesh with 8 times the divisions).  The point load at the top of
the disc has infinite energy in the continuum, so both the estimate and the reference error
are taken over the cells below y = 25 (the disc's lower half and the block: the contact zone
and everything it loads), away from the load point at y = 30.

    PYTHONPATH=postprocess .venv/bin/python bench/adapt/hertz_effectivity.py [--exe build/vemcontact]

"True" error: sqrt(sum over the reference cells in the region of area * (s_h - s_ref)^T C^-1
(s_h - s_ref)), s_h the coarse cell stress at the reference cell's centroid; the reference's
own error (about 1/8 of the coarsest's at the same rate) is left in."""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys

import h5py
import numpy as np
from scipy.spatial import cKDTree

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "accuracy"))
import cases  # noqa: E402
import fields  # noqa: E402

from vctools import adapt  # noqa: E402

Y_CUT = 25.0


def compliance_of(h5, deck_text):
    """Per cell compliance from the deck's materials (element_material index, 1-based)."""
    mats = []
    lines = deck_text.splitlines()
    for i, ln in enumerate(lines):
        if ln.upper().startswith("*ELASTIC"):
            e, nu = (float(v) for v in lines[i + 1].split(",")[:2])
            mats.append(fields.compliance(e, nu, "strain"))
    with h5py.File(h5) as f:
        mat = f["mesh/element_material"][...]
    return np.array([mats[m - 1] for m in mat])


def inside(p, poly):
    n = len(poly)
    s = [(poly[(k + 1) % n, 0] - poly[k, 0]) * (p[1] - poly[k, 1]) - (poly[(k + 1) % n, 1] - poly[k, 1]) * (p[0] - poly[k, 0])
         for k in range(n)]
    return min(s) >= -1e-12


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", default=os.path.join(ROOT, "build", "vemcontact"))
    p.add_argument("-o", "--output", default="/tmp/vc-bench-hertz-eff")
    a = p.parse_args()
    work = a.output
    os.makedirs(work + "/decks", exist_ok=True)
    runs = {}
    for run in cases.hertz(work):
        if run.family != "vem-quad":
            continue
        deck = f"{work}/decks/hz_{run.level}.inp"
        with open(deck, "w") as f:
            f.write(run.deck)
        subprocess.run([a.exe, "-q", deck, "-o", work + "/out"], check=True, capture_output=True)
        runs[run.level] = (f"{work}/out/hz_{run.level}.h5", run.deck)
    ref_h5, ref_deck = runs["600x8"]
    r = fields.read_result(ref_h5)
    cen_r, area_r = adapt.cell_geometry(r["x"], r["off"], r["conn"])
    C_r = compliance_of(ref_h5, ref_deck)
    sel = cen_r[:, 1] < Y_CUT
    print("level   cells  unknowns  estimate(y<25)  error vs ref  effectivity")
    for level in ("389", "600", "1155", "600x2", "600x4"):
        h5, _ = runs[level]
        c = fields.read_result(h5)
        cen, area = adapt.cell_geometry(c["x"], c["off"], c["conn"])
        with h5py.File(h5) as f:
            eta = f["steps"][sorted(f["steps"])[-1]]["ERROR_INDICATOR"][...]
        est = math.sqrt((eta[cen[:, 1] < Y_CUT] ** 2).sum())
        tree = cKDTree(cen)
        _, cand = tree.query(cen_r[sel], k=8)
        owner = np.empty(sel.sum(), int)
        for i, (pt, cs) in enumerate(zip(cen_r[sel], cand)):
            owner[i] = next((k for k in cs if inside(pt, c["x"][c["conn"][c["off"][k]:c["off"][k + 1]]])), cs[0])
        d = c["Se"][owner][:, [0, 1, 3]] - r["Se"][sel][:, [0, 1, 3]]
        err = math.sqrt((area_r[sel] * np.einsum("ij,ijk,ik->i", d, C_r[sel], d)).sum())
        print(f"{level:>6} {len(area):7d} {2 * len(c['x']):9d} {est:15.4e} {err:13.4e} {est / err:12.3f}")


if __name__ == "__main__":
    main()
