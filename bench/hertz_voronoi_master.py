"""NODE TO SURFACE with a Voronoi-meshed disc as the MASTER of the Hertz contact (issue 22):
the deck of postprocess/tests/test_contact_sts_hertz.py (`peak(exe, d, "DMASTER", ...)`) at
several polygon resolutions (narc sides on the half circle), finite sliding and SMALL
SLIDING, HARD.  Writes per run the contact iterations of every increment (HDF5 records,
FREQUENCY=1 frames), whether an increment was cut back, the peak CPRESS against p0 and
the slave node that carries it (its x, its distance to the nearest master vertex), and
the pressure profile as CSV.

usage: bench/hertz_voronoi_master.py EXE OUTDIR [narc[xM] ...]    (default: 240 480 960)
Measured (docs/contact-formulation.md, "NODE TO SURFACE on a curved master"):
240 480 480x2 480x4.

narcxM: the block (the slave) with M times the test's 24 x 20 divisions, so that its
nodes on the contact face outnumber the disc's (M = 2, 4).

Each resolution runs finite sliding and SMALL SLIDING with ROLES=AUTO (the default: the
soft, finely meshed disc becomes the slave, src/contact/roles.f90) and finite sliding
with ROLES=KEEP (the block's nodes as the slave, as written): "roles" in each row.
Measured (Release): AUTO +2.0 / +1.02 / +0.97 % at 240 / 480 / 960 (10 / 12 / 10
iterations, one increment); KEEP +28.7 / +23.2 % at 240 / 480.
"""
import csv
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.join(ROOT, "postprocess", "tests"))
sys.path.insert(0, os.path.join(ROOT, "postprocess"))
from test_contact_sts_hertz import P0, SCENE
from vctools.mesh.scene import mesh_scene_file

A = 2 * 200.0 / (np.pi * P0)    # contact half width of the analytical solution, 2 P / (pi p0)

DECK = """*INCLUDE, INPUT=hertz.inp
*MATERIAL, NAME=D
*ELASTIC
1000.0, 0.3
*MATERIAL, NAME=B
*ELASTIC
1.0e6, 0.3
*SOLID SECTION, ELSET=DISC, MATERIAL=D
1.0
*SOLID SECTION, ELSET=BLOCK, MATERIAL=B
1.0
*SURFACE INTERACTION, NAME=I
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD
*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE{small}{roles}
DMASTER_SLAVE, DMASTER_MASTER
*BOUNDARY
SYMMETRY, 1
BLOCK_BOTTOM, 1, 2
*STEP
*STATIC
*CONTACT FILE, FREQUENCY=1
CDIS, CSTR
*CLOAD
DISC_TOP, 2, -100.0
*END STEP
"""


def mesh(d, narc, refine=1):
    th = np.linspace(-np.pi / 2, np.pi / 2, narc + 1)
    disc = [[float(10 * np.cos(t)), float(20 + 10 * np.sin(t))] for t in th]
    disc[0], disc[-1] = [0.0, 10.0], [0.0, 30.0]
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(d, "hertz.toml")
    with open(scene, "w") as f:
        text = SCENE.format(disc=disc, arc=disc[: narc // 2 + 1])
        text = text.replace("divisions = [24, 20]", f"divisions = [{24 * refine}, {20 * refine}]")
        f.write(text)
    mesh_scene_file(scene, out=os.path.join(d, "hertz.inp"), echo=None)
    return np.array(disc[: narc // 2 + 1])


def increments(f):
    """The contact iterations of every converged increment: the frames' (FREQUENCY=1),
    then the step's records (its last increment).  A cut-back shows as more than one
    increment (the step is one increment unless cut back); the log names it."""
    its = []
    frames = f.get("increments/0001")
    for m in sorted(frames) if frames is not None else []:
        g = frames[m].get("contact/iterations")
        if g is not None:
            its.append(int(np.array(g["iteration"]).size))
    return its + [int(np.array(f["steps/0001/contact/iterations/iteration"]).size)]


def run(exe, d, narc, vertices, small, refine=1, keep=False):
    name = f"nts_{'small' if small else 'finite'}{'_keep' if keep else ''}"
    deck = os.path.join(d, name + ".inp")
    with open(deck, "w") as f:
        f.write(DECK.format(small=", SMALL SLIDING" if small else "", roles=", ROLES=KEEP" if keep else ""))
    r = subprocess.run([exe, "-q", "-o", os.path.join(d, name), deck], capture_output=True, text=True, check=False)
    row = {"narc": narc, "block": f"{24 * refine}x{20 * refine}", "sliding": "small" if small else "finite",
           "roles": "keep" if keep else "auto", "exit": r.returncode}
    h5 = os.path.join(d, name, name + ".h5")
    if r.returncode != 0 or not os.path.exists(h5):
        return row
    with h5py.File(h5, "r") as f:
        cp = np.array(f["steps/0001/contact/pair_1/CPRESS"])
        x = np.array(f["steps/0001/contact/pair_1/coordinates"])[:, 0]
        row["increments"] = increments(f)
        row["peak"] = float(cp.max())
        row["peak_rel"] = float(cp.max() / P0 - 1)
        i = int(np.argmax(cp))
        row["peak_x"] = float(x[i])
        row["peak_x_over_a"] = float(x[i] / A)
        row["peak_vertex_dist"] = float(np.min(np.abs(vertices[:, 0] - x[i])))
        with open(os.path.join(d, name + "_profile.csv"), "w", newline="") as fo:
            w = csv.writer(fo)
            w.writerow(["x", "cpress", "hertz"])
            for xi, pi in sorted(zip(x, cp)):
                w.writerow([xi, pi, P0 * np.sqrt(max(0.0, 1 - (xi / A) ** 2))])
    return row


def main():
    exe, out = sys.argv[1], sys.argv[2]
    for arg in sys.argv[3:] or ["240", "480", "960"]:
        narc, refine = (int(v) for v in (arg.split("x") + ["1"])[:2])
        d = os.path.join(out, f"narc{arg}")
        vertices = mesh(d, narc, refine)
        for small, keep in ((False, False), (True, False), (False, True)):
            print(run(exe, d, narc, vertices, small, refine, keep), flush=True)


if __name__ == "__main__":
    main()
