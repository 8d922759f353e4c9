"""Cost of the frictional contact iteration against the same model frictionless
(issue 23, "Cost": a frictional increment at 1e5 and 1e6 unknowns costs at most 2
numeric factorizations of the frictionless matrix; the whole frictional run at most
3x the same model frictionless with the same increments).

usage: python bench/friction_cost.py [--exe build/vemcontact] [--dofs 1e5 1e6]
           [--increments 4] [--dam] [--repeat 1] [--csv bench/results/friction_cost.csv]

Models:
  block  a block (2 x 0.5) pressed on a foundation (4 x 2) by a pressure on its top,
         then its top pushed sideways in `--increments` steps of one increment each
         (the push of each step is absolute: CalculiX's OP=MOD), far enough for the
         joint to slip near its edges and stick in its middle; structured CPE4
         quads, the block's mesh 0.9 times the foundation's size (non-matching
         joint), NODE TO SURFACE SMALL SLIDING, HARD, *FRICTION mu = 0.5 (exact
         stick).  The frictionless run pushes the same top: the block shifts on its
         joint, the same matrix and loads otherwise.
  dam    the paper's example 4 (inputs/dam_joint.inp) with SMALL SLIDING and mu = 0.6
         (docs/paper-reproduction.md), 2 steps, against the same deck frictionless.

Every increment is its own step so that the HDF5 iteration records
(/steps/NNNN/contact/iterations, docs/output-format.md) give the iterations and
numeric factorizations of each increment.  Each pair (frictional, frictionless) runs
back to back under `nice` and `/usr/bin/time -v` (wall time, CPU time and peak memory); the
ratio is within the pair (the machine is shared and noisy).  Not a test: tests never
check wall time.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
E, NU, PRESSURE, MU = 1.0e3, 0.3, 10.0, 0.5
#: the top's final push: with it the joint ends with about a third of its nodes
#: slipping (at the block's ends) and the rest stuck (measured at 1e4-1e5 unknowns)
PUSH = 0.04


def grid(x0, x1, y0, y1, nx, ny, first):
    """Structured quads: node ids from `first`, row by row; (ids, xy, quads)."""
    ids = first + np.arange((nx + 1) * (ny + 1)).reshape(ny + 1, nx + 1)
    xs, ys = np.meshgrid(np.linspace(x0, x1, nx + 1), np.linspace(y0, y1, ny + 1))
    xy = np.column_stack([xs.ravel(), ys.ravel()])
    q = np.column_stack([ids[:-1, :-1].ravel(), ids[:-1, 1:].ravel(), ids[1:, 1:].ravel(), ids[1:, :-1].ravel()])
    return ids, xy, q


def block_deck(path, dofs, increments, friction):
    """The block on its foundation with about `dofs` unknowns (see the module's help)."""
    h = np.sqrt(18.0 / dofs)
    nfx, nfy = max(4, round(4.0 / h)), max(2, round(2.0 / h))
    nbx, nby = max(2, round(2.0 / (0.9 * h))), max(1, round(0.5 / (0.9 * h)))
    fid, fxy, fq = grid(0.0, 4.0, -2.0, 0.0, nfx, nfy, 1)
    bid, bxy, bq = grid(1.0, 3.0, 0.0, 0.5, nbx, nby, fid.size + 1)
    nf = len(fq)
    with open(path, "w") as f:
        f.write("*NODE\n")
        np.savetxt(f, np.column_stack([np.arange(1, fid.size + bid.size + 1), np.vstack([fxy, bxy])]),
                   fmt="%d, %.17g, %.17g")
        f.write("*ELEMENT, TYPE=CPE4, ELSET=FOUND\n")
        np.savetxt(f, np.column_stack([np.arange(1, nf + 1), fq]), fmt="%d", delimiter=", ")
        f.write("*ELEMENT, TYPE=CPE4, ELSET=BLOCK\n")
        np.savetxt(f, np.column_stack([np.arange(nf + 1, nf + len(bq) + 1), bq]), fmt="%d", delimiter=", ")
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{float(E)!r}, {float(NU)!r}\n")
        f.write("*SOLID SECTION, ELSET=FOUND, MATERIAL=M\n1.0\n*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n1.0\n")
        f.write("*SURFACE, NAME=MASTER\n" + "".join(f"{nf - nfx + i + 1}, S3\n" for i in range(nfx)))
        f.write("*SURFACE, NAME=SLAVE\n" + "".join(f"{nf + i + 1}, S1\n" for i in range(nbx)))
        f.write("*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n")
        if friction:
            f.write(f"*FRICTION\n{float(MU)!r}\n")
        f.write("*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE, SMALL SLIDING\nSLAVE, MASTER\n")
        f.write("*NSET, NSET=TOP\n" + "".join(f"{i}\n" for i in bid[-1]))
        f.write("*NSET, NSET=BOTTOM\n" + "".join(f"{i}\n" for i in fid[0]))
        f.write("*BOUNDARY\nBOTTOM, 1, 2\n")
        f.write("*STEP\n*STATIC\n*BOUNDARY\nTOP, 1, 1, 0.0\n*DLOAD\n")
        f.write("".join(f"{nf + len(bq) - nbx + i + 1}, P3, {float(PRESSURE)!r}\n" for i in range(nbx)))
        f.write("*NODE FILE\nU\n*CONTACT FILE\nCSTR, CDIS, CSTATUS\n*END STEP\n")
        f.writelines(f"*STEP\n*STATIC\n*BOUNDARY\nTOP, 1, 1, {float(PUSH * k / increments)!r}\n*END STEP\n"
                     for k in range(1, increments + 1))
    return 2 * (fid.size + bid.size)


def dam_deck(path, friction):
    """inputs/dam_joint.inp with SMALL SLIDING, with or without mu = 0.6 (as
    postprocess/tests/test_friction.py::paper_deck)."""
    inputs = os.path.join(ROOT, "inputs")
    with open(os.path.join(inputs, "dam_joint.inp")) as f:
        text = f.read()
    text = text.replace("TYPE=NODE TO SURFACE", "TYPE=NODE TO SURFACE, SMALL SLIDING")
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(inputs, "meshes") + "/")
    if friction:
        head, sep, rest = text.partition("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n")
        slope, _, rest = rest.partition("\n")
        text = head + sep + slope + "\n*FRICTION\n0.6\n" + rest
    with open(path, "w") as f:
        f.write(text)


def run(exe, deck, out):
    """Run under nice and /usr/bin/time -v: wall [s], peak RSS [MB], per step
    (iterations, factorizations) and stick and slip node counts, and the
    factorization time from the phases file."""
    cmd = ["nice", "/usr/bin/time", "-v", exe, "-q", "--no-vtu", "-o", out, deck]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        sys.exit(f"{deck}: exit {r.returncode}\n{r.stderr[-2000:]}")
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", r.stderr)
    secs = float(wall.group(1) or 0) * 3600 + float(wall.group(2)) * 60 + float(wall.group(3))
    rss = float(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1)) / 1024
    # CPU seconds (user + system): on the shared machine the wall time carries the other
    # jobs' load, the CPU time much less of it
    cpu = sum(float(re.search(rf"{k} time \(seconds\): ([\d.]+)", r.stderr).group(1)) for k in ("User", "System"))
    job = os.path.splitext(os.path.basename(deck))[0]
    steps, stick, slip = [], [], []
    with h5py.File(os.path.join(out, job + ".h5"), "r") as f:
        dofs = int(np.array(f["steps"][min(f["steps"])]["U"]).size)
        for key in sorted(f["steps"]):
            g = f["steps"][key].get("contact/iterations")
            if g is not None:
                steps.append((int(g["iteration"].size), int(np.array(g["factorized"]).sum())))
            pair = f["steps"][key].get("contact/pair_1")
            if pair is not None and "STATUS" in pair:
                status = np.array(pair["STATUS"])
                stick.append(int((status == 3).sum()))
                slip.append(int((status == 4).sum()))
    fact = 0.0
    phases = os.path.join(out, job + "_phases.csv")
    if os.path.exists(phases):
        with open(phases) as f:
            for row in csv.DictReader(f):
                if row.get("phase") == "factorize":
                    fact += float(row.get("seconds", 0.0))
    return {"dofs": dofs, "wall": secs, "cpu": cpu, "rss": rss, "steps": steps, "stick": stick, "slip": slip, "t_factorize": fact}


def pair(exe, name, make, work, repeat=1):
    """Frictionless then frictional, `repeat` times in turn; the fastest run of each."""
    rows = {}
    for _ in range(repeat):
        for friction in (False, True):
            tag = "mu" if friction else "mu0"
            deck = os.path.join(work, f"{name}_{tag}.inp")
            make(deck, friction)
            r = run(exe, deck, os.path.join(work, f"out_{name}_{tag}"))
            if tag not in rows or r["wall"] < rows[tag]["wall"]:
                rows[tag] = r
    fr, f0 = rows["mu"], rows["mu0"]
    dofs = fr["dofs"]
    nf0 = sum(f for _, f in f0["steps"])
    worst = max(f for _, f in fr["steps"])
    print(f"{name}: {dofs} unknowns")
    for tag, r in rows.items():
        print(f"  {tag:4s} wall {r['wall']:8.2f} s  cpu {r['cpu']:8.2f} s  RSS {r['rss']:7.1f} MB  factorize {r['t_factorize']:7.2f} s  "
              f"iterations/factorizations per step {r['steps']}  stick {r['stick']} slip {r['slip']}")
    print(f"  frictional / frictionless wall {fr['wall'] / f0['wall']:.2f}, cpu {fr['cpu'] / f0['cpu']:.2f}, "
          f"factorizations "
          f"{sum(f for _, f in fr['steps'])} / {nf0}, at most {worst} per increment, "
          f"at most {max(i for i, _ in fr['steps'])} iterations")
    return {"model": name, "dofs": dofs, "steps": len(fr["steps"]),
            "iterations_mu": " ".join(str(i) for i, _ in fr["steps"]),
            "factorizations_mu": " ".join(str(f) for _, f in fr["steps"]),
            "factorizations_mu0": " ".join(str(f) for _, f in f0["steps"]),
            "max_factorizations_per_increment": worst,
            "wall_mu": round(fr["wall"], 2), "wall_mu0": round(f0["wall"], 2),
            "ratio": round(fr["wall"] / f0["wall"], 2),
            "cpu_mu": round(fr["cpu"], 2), "cpu_mu0": round(f0["cpu"], 2),
            "ratio_cpu": round(fr["cpu"] / f0["cpu"], 2),
            "factorize_mu": round(fr["t_factorize"], 2), "factorize_mu0": round(f0["t_factorize"], 2),
            "rss_mu": round(fr["rss"]), "rss_mu0": round(f0["rss"]), "stick": " ".join(map(str, fr["stick"])), "slip": " ".join(map(str, fr["slip"]))}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "vemcontact"))
    ap.add_argument("--dofs", type=float, nargs="*", default=[1e5, 1e6])
    ap.add_argument("--increments", type=int, default=4)
    ap.add_argument("--dam", action="store_true", help="the paper's dam too")
    ap.add_argument("--repeat", type=int, default=1, help="runs of each pair (the fastest kept)")
    ap.add_argument("--csv", default=None)
    ap.add_argument("--work", default=None)
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="friction_cost_")
    os.makedirs(work, exist_ok=True)
    rows = []
    if a.dam:
        rows.append(pair(a.exe, "dam", dam_deck, work, a.repeat))
    for n in a.dofs:
        rows.append(pair(a.exe, f"block_{n:.0e}", lambda d, fr, n=n: block_deck(d, int(n), a.increments, fr), work, a.repeat))
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
