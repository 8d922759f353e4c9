"""Scale runs (issue 15): the peers' Timoshenko cantilever (bench/solvers.py: L = 8, D = 4,
E = 1e7, nu = 0.3, plane strain, parabolic end shear P = -1000, exact displacements on
x = 0) on a structured 4k x k quad mesh (VEM), solved with --solver gamg on one process or
under `mpiexec -n R`, with the peak resident memory of every process and the time of every
phase (JOB_phases.csv).  The mesh is written here with numpy (nodes and VPE quads), not by
vctools.mesh, so that a 1e7-unknown deck takes seconds to generate.

    usage: PYTHONPATH=postprocess .venv/bin/python bench/scale.py --sizes 1e5,1e6
           [--ranks 1] [--solver gamg] [--work out/scale] [--exe build/vemcontact]
           [--csv bench/results/scale.csv] [--compare DIR_A DIR_B]

Every run is started under `nice -n 19` and single (the machine is shared).  Peak RSS:
`/usr/bin/time -f '%M %U %S'` wraps every rank (one file per rank), which also gives the
processor time (user + system, summed over ranks: steadier than wall time on a loaded
machine); CG's iteration count comes from PETSc's -ksp_converged_reason.  Rows are appended to the CSV:
one per run with the phases as columns (summed over steps), the tip deflection's error
against the exact plane-strain value and the peak RSS of the largest rank and of all.
`--compare A B` prints max|U_A - U_B| / max|U_B| of two result folders' HDF5 files.
"""
from __future__ import annotations

import argparse
import csv
import glob
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "accuracy"))
import cases                      # noqa: E402
from solvers import Peers, tip_error   # noqa: E402

ROOT = os.path.dirname(HERE)


def write_deck(work, ndof):
    """A 4k x k quad mesh of the cantilever with about ndof unknowns; returns (deck, k, unknowns)."""
    case = Peers()
    k = int(round((ndof / 8) ** 0.5))
    nx, ny = 4 * k, k
    path = os.path.join(work, f"quad_{nx}x{ny}.inp")
    n_nodes = (nx + 1) * (ny + 1)
    if os.path.exists(path):
        return path, f"{nx}x{ny} quads", 2 * n_nodes
    os.makedirs(work, exist_ok=True)
    xs = np.linspace(0.0, case.L, nx + 1)
    ys = np.linspace(-case.D / 2, case.D / 2, ny + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")             # node (i, j) -> id i*(ny+1)+j+1
    ids = np.arange(1, n_nodes + 1)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    n0 = (i * (ny + 1) + j + 1).ravel()
    conn = np.column_stack([n0, n0 + ny + 1, n0 + ny + 2, n0 + 1])   # counter-clockwise
    u = case.u(X[0, :], Y[0, :])                              # exact displacements on x = 0
    tip = ids.reshape(nx + 1, ny + 1)[nx, :]
    f = cases._edge_forces(ys, lambda y: case.P / (2 * case.I) * (case.D ** 2 / 4 - y * y))
    with open(path, "w") as fh:
        fh.write(f"** bench/scale.py: Timoshenko cantilever, {nx}x{ny} VEM quads\n*HEADING\nscale {nx}x{ny}\n")
        fh.write("*NODE\n")
        np.savetxt(fh, np.column_stack([ids, X.ravel(), Y.ravel()]), fmt="%d, %.17g, %.17g")
        fh.write("*ELEMENT, TYPE=VPE, ELSET=B\n")
        np.savetxt(fh, np.column_stack([np.arange(1, nx * ny + 1), conn]), fmt="%d, %d, %d, %d, %d")
        fh.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{float(case.E_deck)!r}, {float(case.nu_deck)!r}\n"
                 "*SOLID SECTION, ELSET=B, MATERIAL=M, FORMULATION=VEM\n1.0\n*BOUNDARY\n")
        for jj in range(ny + 1):
            fh.write(f"{jj + 1}, 1, 1, {float(u[jj, 0])!r}\n{jj + 1}, 2, 2, {float(u[jj, 1])!r}\n")
        fh.write("*STEP\n*STATIC\n*CLOAD\n")
        for n, fi in zip(tip, f):
            if fi != 0.0:
                fh.write(f"{n}, 2, {float(fi)!r}\n")
        fh.write("*NODE FILE\nU\n*END STEP\n")
    return path, f"{nx}x{ny} quads", 2 * n_nodes


def run(exe, deck, out, solver, ranks):
    os.makedirs(out, exist_ok=True)
    for f in glob.glob(os.path.join(out, "rss.*")):
        os.remove(f)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    # peak RSS (kB), user and system processor time (s) of each rank; CG's iteration count
    inner = (f"/usr/bin/time -f '%M %U %S' -o {out}/rss.${{OMPI_COMM_WORLD_RANK:-0}} {exe} -q --solver {solver}"
             f" --petsc-options -ksp_converged_reason -o {out} {deck}")
    cmd = ["nice", "-n", "19"] + (["mpiexec", "-n", str(ranks)] if ranks > 1 else []) + ["sh", "-c", inner]
    load = os.getloadavg()[0]
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.time() - t0
    if r.returncode != 0:
        raise RuntimeError(f"run failed: {r.stdout}\n{r.stderr}")
    rss, cpu = [], []
    for f in sorted(glob.glob(os.path.join(out, "rss.*"))):
        with open(f) as fh:
            kb, user, system = fh.read().split()[-3:]
        rss.append(int(kb) / 1024 ** 2)
        cpu.append(float(user) + float(system))
    its = [int(m) for m in re.findall(r"CONVERGED_\w+ iterations (\d+)", r.stdout)]
    job = os.path.splitext(os.path.basename(deck))[0]
    ph = {}
    with open(os.path.join(out, job + "_phases.csv")) as fh:
        for row in csv.DictReader(fh):
            if row["within"] == "":
                ph[row["phase"]] = ph.get(row["phase"], 0.0) + float(row["seconds"])
    with h5py.File(os.path.join(out, job + ".h5"), "r") as fh:
        x = fh["mesh/coordinates"][()]
        u = fh["steps/0001/U"][()]
    return dict(phases=ph, wall=wall, rss=rss, cpu=cpu, its=its[0] if its else "", load=load, x=x, u=u)


def compare(a, b):
    def load(d):
        (h5,) = glob.glob(os.path.join(d, "*.h5"))
        with h5py.File(h5, "r") as fh:
            return fh["steps/0001/U"][()]
    ua, ub = load(a), load(b)
    print(f"max|U_A - U_B| / max|U_B| = {np.max(np.abs(ua - ub)) / np.max(np.abs(ub)):.2e}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--solver", default="gamg")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "scale"))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "vemcontact"))
    ap.add_argument("--csv", default=os.path.join(ROOT, "bench", "results", "scale.csv"))
    ap.add_argument("--compare", nargs=2)
    a = ap.parse_args()
    if a.compare:
        compare(*a.compare)
        return
    case = Peers()
    for size in [int(float(s)) for s in a.sizes.split(",")]:
        t0 = time.time()
        deck, desc, ndof = write_deck(os.path.join(a.work, "decks"), size)
        print(f"deck {deck}: {ndof} unknowns, written in {time.time() - t0:.1f} s", flush=True)
        out = os.path.join(a.work, "out", f"{os.path.basename(deck)[:-4]}_{a.solver}_np{a.ranks}")
        res = run(a.exe, deck, out, a.solver, a.ranks)
        row = dict(mesh=desc, unknowns=ndof, solver=a.solver, ranks=a.ranks,
                   **{k: round(v, 3) for k, v in res["phases"].items()}, wall=round(res["wall"], 2),
                   peak_rss_gb_max=round(max(res["rss"]), 2), peak_rss_gb_sum=round(sum(res["rss"]), 2),
                   cpu_s_sum=round(sum(res["cpu"]), 1), cg_iterations=res["its"],
                   tip_error=f"{tip_error(res['x'], res['u'], case):.3e}", load=round(res["load"], 1),
                   utc=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()))
        print(row, flush=True)
        new = not os.path.exists(a.csv)
        fields = ["mesh", "unknowns", "solver", "ranks", "start", "read", "validate", "pattern", "assemble",
                  "analyze", "set-up", "write mesh", "factorize", "solve", "system", "stresses", "estimate",
                  "write", "finish", "total", "wall", "peak_rss_gb_max", "peak_rss_gb_sum", "cpu_s_sum",
                  "cg_iterations", "tip_error",
                  "load", "utc"]
        with open(a.csv, "a", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=fields, extrasaction="ignore", restval="")
            if new:
                w.writeheader()
            w.writerow(row)


if __name__ == "__main__":
    main()
