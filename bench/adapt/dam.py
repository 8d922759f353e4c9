"""Adaptive against uniform refinement on the dam's joint tip (inputs/dam_joint.inp,
postprocess/scenes/ex4_dam.toml): estimated relative energy error (the larger of the two
steps) against unknowns, and wall time (meshing + run) per mesh.

    PYTHONPATH=postprocess .venv/bin/python bench/adapt/dam.py [--exe build/vemcontact] [-o DIR]

Adaptive: vc-adapt with theta = 0.5 from the scene's mesh to --max-unknowns.  Uniform: the
scene's own sizing rule (grading toward the joint tip and along the joint) with the cell
targets times 4^k, the refinement a user makes by hand.  Every mesh after the scene's own
has --lloyd Lloyd iterations (default 10, the scene 40: the mesher's time dominates).  Writes bench/results/adapt_dam.csv."""
from __future__ import annotations

import argparse
import copy
import csv
import subprocess
import time
from pathlib import Path

from vctools import adapt
from vctools.mesh.deck import write_deck
from vctools.mesh.scene import build, load

ROOT = Path(__file__).resolve().parents[2]


def uniform(exe, out, levels, lloyd=None):
    deck = ROOT / "inputs" / "dam_joint.inp"
    scene = load(ROOT / "postprocess" / "scenes" / "ex4_dam.toml")
    rows = []
    for k in range(levels):
        sc = copy.deepcopy(scene)
        for b in sc["body"]:
            b["cells"] = int(b["cells"]) * 4 ** k
        if lloyd is not None and k > 0:
            sc["mesh"]["lloyd"] = lloyd
        d = Path(out) / f"uniform_{k}"
        d.mkdir(parents=True, exist_ok=True)
        t0 = time.perf_counter()
        m = build(sc, processes=2)
        write_deck(m, str(d / "mesh.inp"), ["vemcontact mesh written by vctools.mesh (bench/adapt/dam.py)"])
        t_mesh = time.perf_counter() - t0
        cdeck = adapt.write_cycle_deck(deck, 0, d)
        t0 = time.perf_counter()
        subprocess.run([exe, "-q", str(cdeck), "-o", str(d)], check=True, capture_output=True)
        t_run = time.perf_counter() - t0
        steps, x, off, _ = adapt.read_estimate(d / "dam_joint.h5")
        worst = max(steps, key=lambda s: s[1])
        rows.append({"kind": "uniform", "cycle": k, "cells": len(off) - 1, "unknowns": 2 * len(x),
                     "relative_error": worst[1], "estimate": worst[2], "step": worst[0], "mesh_s": t_mesh, "run_s": t_run})
        print(rows[-1], flush=True)
    return rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", default=str(ROOT / "build" / "vemcontact"))
    p.add_argument("-o", "--output", default="/tmp/vc-bench-adapt")
    p.add_argument("--max-unknowns", type=float, default=1.5e5)
    p.add_argument("--uniform-levels", type=int, default=3)
    p.add_argument("--lloyd", type=int, default=10,
                   help="Lloyd iterations of every mesh but the scene's own (default 10; the scene has 40)")
    p.add_argument("--adaptive-table", help="adapt.csv of an earlier vc-adapt run of the dam (skips that part)")
    a = p.parse_args()
    if a.adaptive_table:
        with open(a.adaptive_table) as f:
            rows = [{"kind": "adaptive", **r} for r in csv.DictReader(f)]
    else:
        rows = [{"kind": "adaptive", **r} for r in
                adapt.adapt(ROOT / "inputs" / "dam_joint.inp", ROOT / "postprocess" / "scenes" / "ex4_dam.toml", 1e-3,
                            Path(a.output) / "adaptive", max_unknowns=a.max_unknowns, max_cycles=20, exe=a.exe,
                            processes=2, lloyd=a.lloyd)]
    rows += uniform(a.exe, a.output, a.uniform_levels, a.lloyd)
    res = ROOT / "bench" / "results" / "adapt_dam.csv"
    with open(res, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(res)


if __name__ == "__main__":
    main()
