"""Cost of *TIE at scale (docs/performance.md, "*TIE"): two blocks of quads, [0, 1]^2
(n x n cells) and [1, 2] x [0, 1] ((n - 1) x (n - 1)), tied along x = 1 with
non-matching nodes, uniaxial tension.  Element types: VPE on both (node insertion, node
to node), CPE4 on the left (the FEM corners inserted into the VEM face), CPE4 on both
(CalculiX's closest point), and a conforming block of 2n x n VPE without a tie (the
baseline).  Prints the phases of each run from JOB_phases.csv and the largest stress
error (the exact S_xx is the load, 10).

    usage: nice python bench/tie.py [--solver=NAME] EXE OUTDIR [n ...]   (default n = 100 500)
"""
import csv
import os
import subprocess
import sys
import time

import h5py
import numpy as np


def block(x0, n, first_node, first_elem, etype):
    m = n + 1
    ids = np.arange(m * m).reshape(m, m) + first_node     # ids[j, i]
    xs = x0 + np.arange(m) / n
    ys = np.arange(m) / n
    nodes = [f"{ids[j, i]}, {float(xs[i])!r}, {float(ys[j])!r}" for j in range(m) for i in range(m)]
    elems, master, slave = [], [], []
    for j in range(n):
        for i in range(n):
            e = first_elem + j * n + i
            elems.append(f"{e}, {ids[j, i]}, {ids[j, i + 1]}, {ids[j + 1, i + 1]}, {ids[j + 1, i]}")
            if i == n - 1:
                master.append(f"{e}, S2")
            if i == 0:
                slave.append(f"{e}, S4")
    return nodes, elems, master, slave, etype


def deck(n, left, right):
    nl, el, ml, _, _ = block(0.0, n, 1, 1, left)
    off = (n + 1) ** 2 + 1
    nr, er, _, sr, _ = block(1.0, n - 1, off, n * n + 1, right)
    held = [f"{1 + j * (n + 1)}, 1" for j in range(n + 1)] + ["1, 2"]
    right_end = [f"{n * n + 1 + j * (n - 1) + n - 2}, P2, -10.0" for j in range(n - 1)]
    return "\n".join(["*NODE"] + nl + nr + [f"*ELEMENT, TYPE={left}, ELSET=L"] + el +
                     [f"*ELEMENT, TYPE={right}, ELSET=R"] + er + ["*SURFACE, NAME=MASTER"] + ml +
                     ["*SURFACE, NAME=SLAVE"] + sr +
                     ["*TIE, NAME=GLUE", "SLAVE, MASTER", "*MATERIAL, NAME=M", "*ELASTIC", "2000.0, 0.3",
                      "*SOLID SECTION, ELSET=L, MATERIAL=M", "*SOLID SECTION, ELSET=R, MATERIAL=M",
                      "*BOUNDARY"] + held + ["*STEP", "*STATIC", "*DLOAD"] + right_end +
                     ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]) + "\n"


def merged(n):
    """The baseline without a tie: one conforming block [0, 2] x [0, 1] of 2n x n VPE."""
    m = 2 * n + 1
    nodes = [f"{j * m + i + 1}, {float(2.0 * i / (2 * n))!r}, {float(j / n)!r}" for j in range(n + 1) for i in range(m)]
    elems = [f"{j * 2 * n + i + 1}, {j * m + i + 1}, {j * m + i + 2}, {(j + 1) * m + i + 2}, {(j + 1) * m + i + 1}"
             for j in range(n) for i in range(2 * n)]
    held = [f"{j * m + 1}, 1" for j in range(n + 1)] + ["1, 2"]
    load = [f"{j * 2 * n + 2 * n}, P2, -10.0" for j in range(n)]
    return "\n".join(["*NODE"] + nodes + ["*ELEMENT, TYPE=VPE, ELSET=ALL"] + elems +
                     ["*MATERIAL, NAME=M", "*ELASTIC", "2000.0, 0.3", "*SOLID SECTION, ELSET=ALL, MATERIAL=M",
                      "*BOUNDARY"] + held + ["*STEP", "*STATIC", "*DLOAD"] + load +
                     ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]) + "\n"


def main(argv):
    solver = []
    if argv and argv[0].startswith("--solver="):
        solver = ["--solver", argv.pop(0).split("=", 1)[1]]
    exe, out = argv[0], argv[1]
    sizes = [int(a) for a in argv[2:]] or [100, 500]
    print("| n | elements | unknowns | left/right | set-up s | assemble s | factorize s | solve s | total s | "
          "max abs(S_xx - 10) / 10 |")
    print("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    for n in sizes:
        for left, right in (("VPE", "VPE"), ("CPE4", "VPE"), ("CPE4", "CPE4"), ("merged", "")):
            job = f"tie_{n}_{left}_{right}" if right else f"tie_{n}_merged"
            d = os.path.join(out, job)
            os.makedirs(d, exist_ok=True)
            with open(os.path.join(d, job + ".inp"), "w") as fh:
                fh.write(deck(n, left, right) if right else merged(n))
            t0 = time.perf_counter()
            subprocess.run([exe, "-q", "--no-vtu", *solver, "-o", d, os.path.join(d, job + ".inp")], check=True)
            wall = time.perf_counter() - t0
            with open(os.path.join(d, job + "_phases.csv")) as fh:
                ph = {r["phase"]: float(r["seconds"]) for r in csv.DictReader(fh)}
            with h5py.File(os.path.join(d, job + ".h5")) as f:
                s = f["steps/0001/S_element"][...]
                nnode = f["mesh/node_ids"].shape[0]
            err = np.abs(s[:, 0] - 10.0).max() / 10.0
            print(f"| {n} | {len(s)} | {2 * nnode} | {left}/{right} | {ph.get('set-up', 0):.3f} | "
                  f"{ph.get('assemble', 0):.3f} | {ph.get('factorize', 0):.3f} | {ph.get('solve', 0):.3f} | "
                  f"{wall:.2f} | {err:.1e} |")


if __name__ == "__main__":
    main(sys.argv[1:])
