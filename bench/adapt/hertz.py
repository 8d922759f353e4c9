"""Adaptive against uniform refinement on the Hertz contact (postprocess/scenes/ex2_hertz.toml,
VEM quads, the 389-element mesh of the paper to start): estimated relative energy error
against unknowns, and wall time (mesh + run) per cycle.

    PYTHONPATH=postprocess .venv/bin/python bench/adapt/hertz.py [--exe build/vemcontact] [-o DIR]

The deck is inputs/hertz_389_vem.inp with its load spread: the paper's point load of 100 at
the disc's top has infinite energy in the continuum (the estimate there never converges), so
here the same resultant is a pressure of 10 on the upper quarter arc (DISC_UPPER_ARC: its
vertical resultant is 10 times the arc's horizontal span 10; the horizontal one goes to the
symmetry line).  What is left to refine is the contact zone, the end of the pressure at
(10, 20) and the block's corners.  Adaptive: vc-adapt, splitting the marked cells (--theta, default
0.5; the published run: --theta 0.4).  Uniform: every cell split in every cycle (vc-adapt
--uniform), the structured mesh with twice the divisions per cycle (the published run: --only
uniform --max-unknowns 8e5, five levels).  --only runs one kind and keeps the other's rows of the
existing CSV.  Writes bench/results/adapt_hertz.csv.

--effectivity: afterwards, the estimate of every cycle divided by its "true" energy error
against a reference, the start mesh with every cell split --reference-levels times (nested:
every cycle's cells are unions of its cells, but for the arc), sqrt(sum over the reference
cells of area * (s_h - s_ref)^T C^-1 (s_h - s_ref)), s_h the stress of the cycle's cell
holding the reference cell's centroid (the nearest cell's for the few at the arc outside
every cell); only cycles with at least 3 times the reference's estimate (its own error is
left in).  Writes bench/results/adapt_hertz_effectivity.csv."""
from __future__ import annotations

import argparse
import csv
import math
import re
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

from vctools import adapt

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench" / "accuracy"))
import fields  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def setup(out):
    """The scene (389-element divisions, no variants) and the deck with the spread load."""
    out.mkdir(parents=True, exist_ok=True)
    text = (ROOT / "postprocess" / "scenes" / "ex2_hertz.toml").read_text().split("[[variant]]")[0]
    text = text.replace("divisions = [12, 12, 6]", "divisions = [10, 10, 4]").replace(
        "divisions = [16, 15]", "divisions = [13, 13]")
    (out / "hertz.toml").write_text(text)
    deck = (ROOT / "inputs" / "hertz_389_vem.inp").read_text()
    deck = re.sub(r"\*INCLUDE, INPUT=\S+", "*INCLUDE, INPUT=mesh.inp", deck)
    deck, n = re.subn(r"\*CLOAD\nDISC_TOP, 2, -100.0\n", "*DSLOAD\nDISC_UPPER_ARC, P, 10.0\n", deck)
    assert n == 1, "the Hertz deck's *CLOAD changed"
    (out / "hertz.inp").write_text(deck)
    return out / "hertz.inp", out / "hertz.toml"


def compliance_of(h5, deck_text):
    """Per cell compliance from the deck's *ELASTIC lines (element_material, 1-based)."""
    lines = deck_text.splitlines()
    mats = [fields.compliance(*(float(v) for v in lines[i + 1].split(",")[:2]), "strain")
            for i, ln in enumerate(lines) if ln.upper().startswith("*ELASTIC")]
    with h5py.File(h5) as f:
        return np.array([mats[m - 1] for m in f["mesh/element_material"][...]])


def effectivity(exe, out, deck, scene, levels):
    """[(kind, cycle, unknowns, estimate, true error, effectivity)] of the cycles in out/."""
    import shapely
    from vctools.mesh.deck import write_deck
    from vctools.mesh.refine import refine
    from vctools.mesh.scene import build, load
    m = build(load(scene))
    for _ in range(levels):
        m = refine(m, np.ones(m.ncell, bool))[0]
    d = out / "reference"
    d.mkdir(exist_ok=True)
    write_deck(m, d / "mesh.inp", ["vemcontact mesh written by vctools.mesh (bench/adapt/hertz.py reference)"])
    cdeck = adapt.write_cycle_deck(deck, 0, d)
    subprocess.run([exe, "-q", str(cdeck), "-o", str(d)], check=True, capture_output=True)
    h5 = d / "hertz.h5"
    r = fields.read_result(h5)
    cen_r, area_r = adapt.cell_geometry(r["x"], r["off"], r["conn"])
    C_r = compliance_of(h5, deck.read_text())
    with h5py.File(h5) as f:
        est_ref = float(f["steps"][sorted(f["steps"])[-1]].attrs["error_estimate"])
    print(f"reference: {2 * len(r['x'])} unknowns, estimate {est_ref:.4e}", flush=True)
    rows = []
    for kind in ("adaptive", "uniform"):
        for cdir in sorted((out / kind).glob("cycle_*")):
            h5 = cdir / "hertz.h5"
            with h5py.File(h5) as f:
                est = float(f["steps"][sorted(f["steps"])[-1]].attrs["error_estimate"])
            if est < 3 * est_ref:
                continue
            c = fields.read_result(h5)
            polys = [shapely.Polygon(c["x"][c["conn"][c["off"][k]:c["off"][k + 1]]]) for k in range(len(c["off"]) - 1)]
            pi, ci = shapely.STRtree(polys).query(shapely.points(cen_r), predicate="within")
            owner = np.full(len(cen_r), -1)
            owner[pi] = ci
            # nested but for the arc: a reference cell at the disc's arc bulges beyond the
            # coarser chord; its centroid may lie outside: the nearest cell's stress there
            out_ = owner < 0
            if out_.any():
                from scipy.spatial import cKDTree
                cen_c, _ = adapt.cell_geometry(c["x"], c["off"], c["conn"])
                owner[out_] = cKDTree(cen_c).query(cen_r[out_])[1]
            dS = c["Se"][owner][:, [0, 1, 3]] - r["Se"][:, [0, 1, 3]]
            err = math.sqrt((area_r * np.einsum("ij,ijk,ik->i", dS, C_r, dS)).sum())
            rows.append({"kind": kind, "cycle": int(cdir.name[6:]), "unknowns": 2 * len(c["x"]), "estimate": est,
                         "true_error": err, "effectivity": est / err})
            print(rows[-1], flush=True)
    return rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", default=str(ROOT / "build" / "vemcontact"))
    p.add_argument("-o", "--output", default="/tmp/vc-bench-adapt-hertz")
    p.add_argument("--max-unknowns", type=float, default=2.5e5)
    p.add_argument("--effectivity", action="store_true", help="only the effectivity of the cycles already in -o")
    p.add_argument("--reference-levels", type=int, default=4)
    p.add_argument("--theta", type=float, default=0.5, help="vc-adapt's bulk (Doerfler) fraction")
    p.add_argument("--only", choices=("adaptive", "uniform"),
                   help="run only these cycles; keep the other kind's rows of the existing CSV")
    a = p.parse_args()
    out = Path(a.output)
    deck, scene = setup(out)
    if a.effectivity:
        rows = effectivity(a.exe, out, deck, scene, a.reference_levels)
        res = ROOT / "bench" / "results" / "adapt_hertz_effectivity.csv"
        with open(res, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        print(res)
        return
    rows = []
    res = ROOT / "bench" / "results" / "adapt_hertz.csv"
    kinds = [(k, u) for k, u in (("adaptive", False), ("uniform", True)) if a.only in (None, k)]
    for kind, uniform in kinds:
        rows += [{"kind": kind, "theta": a.theta if not uniform else "", **r} for r in
                 adapt.adapt(deck, scene, 1e-4, out / kind, max_unknowns=a.max_unknowns, max_cycles=30, exe=a.exe,
                             theta=a.theta, uniform=uniform, refine="split")]
    if a.only:
        with open(res) as f:
            rows += [{"theta": "", **r} for r in csv.DictReader(f) if r["kind"] != a.only]
    with open(res, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(res)


if __name__ == "__main__":
    main()
