"""The linear solvers side by side (issue 15): time per phase of cholmod, gamg, hypre
and mumps on the peers' Timoshenko cantilever (L = 8, D = 4, E = 1e7, nu = 0.3, plane
strain, parabolic end shear P = -1000, exact displacements on x = 0), meshed as
structured quads (VEM) and as Lloyd-Voronoi cells (VEM), at about 1e5 and 1e6
unknowns; the tip deflection's error against the exact -2.9120e-3 and the largest
difference of the displacements from CHOLMOD's.  Writes bench/results/solvers.csv and
prints it as a Markdown table for docs/performance.md.

    usage: PYTHONPATH=postprocess .venv/bin/python bench/solvers.py [--sizes 1e5,1e6]
           [--solvers cholmod,gamg,hypre,mumps] [--work DIR] [--exe build/vemcontact]

Meshes come from `vctools.mesh` (seed 7, 20 Lloyd iterations below 2e4 cells, 10
above: bench/accuracy/meshes.py).  Each run is single (the machine is shared: see the
load column); the Release build is used.
"""
from __future__ import annotations

import argparse
import csv
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "accuracy"))
import cases   # noqa: E402
import fields  # noqa: E402
import meshes  # noqa: E402

ROOT = os.path.dirname(HERE)
PHASES = ("read", "pattern", "assemble", "analyze", "factorize", "solve", "write", "total")
_PHASE = re.compile(r"^\s*(\w+)\s+([0-9.Ee+-]+)\s*s\s*$", re.M)


class Peers(fields.Timoshenko):
    """The peers' cantilever in plane strain: Timoshenko's plane-stress solution with
    E' = E/(1 - nu^2), nu' = nu/(1 - nu); the deck gets E and nu."""
    L, D, P = 8.0, 4.0, -1000.0
    E_deck, nu_deck = 1.0e7, 0.3
    E, nu = E_deck / (1 - nu_deck ** 2), nu_deck / (1 - nu_deck)


def deck_text(work, shape, ndof):
    """A Timoshenko cantilever deck of about ndof unknowns; returns (deck path, description)."""
    case = Peers()
    L, D = case.L, case.D
    box = (0.0, -D / 2, L, D / 2)
    if shape == "voronoi":
        cells = int(round(ndof / 4))          # about 2 nodes per Voronoi cell
        mp = meshes.rectangle(work + "/meshes", f"sv_{cells}", box, "voronoi", cells, plane="strain",
                              lloyd=20 if cells <= 20000 else 10)
        desc = f"{cells} Voronoi cells"
    else:
        k = int(round((ndof / 8) ** 0.5))      # 4k x k quads, (4k+1)(k+1) nodes
        mp = meshes.rectangle(work + "/meshes", f"sq_{k}", box, "quad", (4 * k, k), plane="strain")
        desc = f"{4 * k}x{k} quads"
    m = meshes.read_inp(mp)
    os.makedirs(work + "/decks", exist_ok=True)
    deck = cases._header("Timoshenko cantilever, solvers", os.path.relpath(mp, work + "/decks"),
                         case.E_deck, case.nu_deck, "VEM")
    tol = 1e-9 * L
    clamp = cases._boundary_nodes(m, lambda x, y: x < tol)
    tip = cases._boundary_nodes(m, lambda x, y: x > L - tol)
    tip.sort(key=lambda i: m.xy[m.index[i], 1])
    ys = np.array([m.xy[m.index[i], 1] for i in tip])
    f = cases._edge_forces(ys, lambda y: case.P / (2 * case.I) * (D * D / 4 - y * y))
    u = case.u(m.xy[:, 0], m.xy[:, 1])
    lines = ["*BOUNDARY"]
    for i in clamp:
        kk = m.index[i]
        lines += [f"{i}, 1, 1, {float(u[kk, 0])!r}", f"{i}, 2, 2, {float(u[kk, 1])!r}"]
    lines += ["*STEP", "*STATIC", "*CLOAD"]
    lines += [f"{i}, 2, {float(fi)!r}" for i, fi in zip(tip, f) if fi != 0.0]
    deck += "\n".join(lines) + "\n*NODE FILE\nU\n*END STEP\n"
    path = os.path.join(work, "decks", f"{shape}_{ndof:.0e}.inp".replace("+", ""))
    with open(path, "w") as fh:
        fh.write(deck)
    return path, desc, 2 * len(m.ids), case


def run(exe, deck, out, solver, ranks=1):
    os.makedirs(out, exist_ok=True)
    load = os.getloadavg()[0]
    launch = [] if ranks == 1 else ["mpiexec", "-n", str(ranks)]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    t0 = time.time()
    # peak RSS: of rank 0 (the one /usr/bin/time starts) with one rank; of mpiexec's
    # children, the largest, with several
    r = subprocess.run(["/usr/bin/time", "-f", "%M", *launch, exe, "-q", "--solver", solver, "-o", out, deck],
                       capture_output=True, text=True, env=env)
    wall = time.time() - t0
    if r.returncode != 0:
        print(f"{solver} failed on {deck}: {r.stderr}", file=sys.stderr)
        return None
    rss = int(r.stderr.strip().splitlines()[-1]) / 1024 ** 2
    job = os.path.splitext(os.path.basename(deck))[0]
    with open(os.path.join(out, job + ".log")) as fh:
        log = fh.read()
    ph = {k: 0.0 for k in PHASES}
    for name, val in _PHASE.findall(log):
        if name in ph:
            ph[name] += float(val)
    with h5py.File(os.path.join(out, job + ".h5"), "r") as fh:
        x = fh["mesh/coordinates"][()]
        u = fh["steps/0001/U"][()]
    return dict(phases=ph, wall=wall, rss=rss, load=load, x=x, u=u)


def tip_error(x, u, case):
    on = np.abs(x[:, 0] - case.L) < 1e-9 * case.L
    srt = np.argsort(x[on, 1])
    uy = np.interp(0.0, x[on, 1][srt], u[on, 1][srt])
    return abs(uy - case.tip()) / abs(case.tip())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--shapes", default="quad,voronoi")
    ap.add_argument("--solvers", default="cholmod,gamg,hypre,mumps")
    ap.add_argument("--ranks", default="1", help="MPI processes, e.g. 1,2 (2: the PETSc solvers only)")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "solvers"))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "vemcontact"))
    ap.add_argument("--csv", default=os.path.join(ROOT, "bench", "results", "solvers.csv"))
    a = ap.parse_args()
    rows = []
    for size in [int(float(s)) for s in a.sizes.split(",")]:
        for shape in a.shapes.split(","):
            deck, desc, ndof, case = deck_text(a.work, shape, size)
            ref = None
            runs = [(s, r) for r in [int(x) for x in a.ranks.split(",")] for s in a.solvers.split(",")
                    if r == 1 or s != "cholmod"]
            for solver, ranks in runs:
                res = run(a.exe, deck, os.path.join(a.work, "out", f"{shape}_{size}", f"{solver}_np{ranks}"),
                          solver, ranks)
                if res is None:
                    continue
                if solver == "cholmod":
                    ref = res["u"]
                diff = (np.max(np.abs(res["u"] - ref)) / np.max(np.abs(ref))) if ref is not None else float("nan")
                row = dict(case=shape, mesh=desc, unknowns=ndof, solver=solver, ranks=ranks,
                           **{k: round(v, 3) for k, v in res["phases"].items()},
                           wall=round(res["wall"], 2), peak_rss_gb=round(res["rss"], 2),
                           tip_error=f"{tip_error(res['x'], res['u'], case):.3e}", diff_cholmod=f"{diff:.1e}",
                           load=round(res["load"], 1))
                rows.append(row)
                print(row, flush=True)
    os.makedirs(os.path.dirname(a.csv), exist_ok=True)
    with open(a.csv, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("| case | unknowns | solver | ranks | assemble | analyze | factorize | solve | total | peak RSS GB |"
          " tip error | vs CHOLMOD | load |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['case']} ({r['mesh']}) | {r['unknowns']} | {r['solver']} | {r['ranks']} | {r['assemble']} | {r['analyze']} |"
              f" {r['factorize']} | {r['solve']} | {r['total']} | {r['peak_rss_gb']} | {r['tip_error']} |"
              f" {r['diff_cholmod']} | {r['load']} |")


if __name__ == "__main__":
    main()
