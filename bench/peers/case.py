"""The peers' cantilever (issue 15): Timoshenko's beam L = 8, D = 4 (x in [0, 8],
y in [-2, 2]), E = 1e7, nu = 0.3, plane strain, end shear P = -1000 as the
parabolic traction on x = 8 (consistent nodal loads), the exact displacement
prescribed on x = 0, on a Lloyd-Voronoi mesh from vctools.mesh (uniform random
seeds, `lloyd` iterations, `seed`).

    python case.py deck DIR [--cells 100000] [--seed 1] [--lloyd 20]
    python case.py tip DIR/beam.h5   # one CSV line: u_y(8, 0), exact, absolute and relative error

The exact field (Timoshenko and Goodier, section 21; plane strain: E' = E/(1 - nu^2),
nu' = nu/(1 - nu); I = D^3/12) is the one whose axis does not rotate at the fixed
end (dv/dx(0, 0) = 0):

    u_x = -P y/(6 E' I) [(6L - 3x) x + (2 + nu')(y^2 - D^2/4)] + theta y
    u_y =  P/(6 E' I) [3 nu' y^2 (L - x) + (4 + 5 nu') D^2 x/4 + (3L - x) x^2] - theta x
    theta = P (4 + 5 nu') D^2/(24 E' I)

so that u_y(L, 0) = P L^3/(3 E' I) = -2.9120e-3 exactly; its stresses are
s_xx = -P (L - x) y/I, s_yy = 0, s_xy = P/(2I)(D^2/4 - y^2) (checked: equilibrium,
the free edges y = +-D/2, and the resultant P of s_xy on x = L).
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys

import numpy as np

L, D, E, NU, P = 8.0, 4.0, 1.0e7, 0.3, -1000.0
EP, NUP = E / (1 - NU**2), NU / (1 - NU)          # plane strain
I = D**3 / 12
THETA = P * (4 + 5 * NUP) * D**2 / (24 * EP * I)
TIP_EXACT = P * L**3 / (3 * EP * I)               # -2.9120e-3


def exact_u(x, y):
    ux = -P * y / (6 * EP * I) * ((6 * L - 3 * x) * x + (2 + NUP) * (y**2 - D**2 / 4)) + THETA * y
    uy = P / (6 * EP * I) * (3 * NUP * y**2 * (L - x) + (4 + 5 * NUP) * D**2 * x / 4 + (3 * L - x) * x**2) - THETA * x
    return ux, uy


def traction_loads(y):
    """Consistent nodal forces of t_y = P/(2I)(D^2/4 - y^2) on the sides between the
    sorted heights y (linear shape functions; 2-point Gauss is exact for the cubic)."""
    f = np.zeros_like(y)
    g = np.array([-1.0, 1.0]) / np.sqrt(3.0)
    for k in range(len(y) - 1):
        a, b = y[k], y[k + 1]
        for s in g:
            t = 0.5 * (1 + s)
            yy = a + t * (b - a)
            w = 0.5 * (b - a) * P / (2 * I) * (D**2 / 4 - yy**2)
            f[k] += w * (1 - t)
            f[k + 1] += w * t
    return f


def read_mesh(path):
    """Node coordinates {id: (x, y)} and node sets {name: [ids]} of a vctools.mesh file."""
    nodes, sets, block, name = {}, {}, None, None
    with open(path) as fh:
        for line in fh:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                key = s.split(",")[0].strip().upper()
                block = key
                if key == "*NSET":
                    name = [p.split("=")[1].strip() for p in s.split(",") if p.strip().upper().startswith("NSET=")][0]
                    sets[name] = []
                continue
            if block == "*NODE":
                p = s.split(",")
                nodes[int(p[0])] = (float(p[1]), float(p[2]))
            elif block == "*NSET":
                sets[name] += [int(v) for v in s.replace(",", " ").split()]
    return nodes, sets


def make_deck(out, cells, seed, lloyd):
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "beam.toml")
    with open(scene, "w") as fh:
        fh.write(f'[mesh]\ntitle = "Timoshenko cantilever, {cells} Lloyd-Voronoi cells"\n'
                 f"seed = {seed}\nlloyd = {lloyd}\n\n"
                 f'[[body]]\nname = "BEAM"\nrectangle = [0.0, {-D / 2}, {L}, {D / 2}]\n'
                 f'mesher = "voronoi"\ncells = {cells}\n\n'
                 f'[[selection]]\nname = "LEFT"\nx = 0.0\n\n[[selection]]\nname = "RIGHT"\nx = {L}\n')
    mesh = os.path.join(out, "beam_mesh.inp")
    subprocess.run([sys.executable, "-m", "vctools.mesh", "scene", scene, "-o", mesh], check=True,
                   stdout=subprocess.DEVNULL)
    nodes, sets = read_mesh(mesh)
    left = sorted(set(sets["LEFT"]))
    right = sorted(set(sets["RIGHT"]), key=lambda n: nodes[n][1])
    fy = traction_loads(np.array([nodes[n][1] for n in right]))
    with open(os.path.join(out, "beam.inp"), "w") as fh:
        fh.write("** Timoshenko cantilever (bench/peers/case.py)\n*INCLUDE, INPUT=beam_mesh.inp\n"
                 f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{float(E)!r}, {float(NU)!r}\n"
                 "*SOLID SECTION, ELSET=BEAM, MATERIAL=STEEL\n*STEP\n*STATIC\n*BOUNDARY\n")
        for n in left:
            ux, uy = exact_u(*nodes[n])
            fh.write(f"{n}, 1, 1, {float(ux)!r}\n{n}, 2, 2, {float(uy)!r}\n")
        fh.write("*CLOAD\n")
        for n, f in zip(right, fy):
            fh.write(f"{n}, 2, {float(f)!r}\n")
        fh.write("*END STEP\n")


def tip(h5path):
    """u_y at (L, 0): the VEM displacement is linear on a side, so it is interpolated
    between the two nodes of x = L around y = 0."""
    import h5py
    with h5py.File(h5path, "r") as f:
        xy = f["mesh/coordinates"][...]
        steps = sorted(f["steps"])
        u = f["steps"][steps[-1]]["U"][...]
    on = np.flatnonzero(np.abs(xy[:, 0] - L) <= 1e-9 * L)
    on = on[np.argsort(xy[on, 1])]
    k = np.searchsorted(xy[on, 1], 0.0)
    a, b = on[max(k - 1, 0)], on[min(k, len(on) - 1)]
    t = 0.0 if a == b else (0.0 - xy[a, 1]) / (xy[b, 1] - xy[a, 1])
    uy = (1 - t) * u[a, 1] + t * u[b, 1]
    return uy, abs(uy - TIP_EXACT), abs(uy - TIP_EXACT) / abs(TIP_EXACT)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("deck")
    d.add_argument("out")
    d.add_argument("--cells", type=int, default=100000)
    d.add_argument("--seed", type=int, default=1)
    d.add_argument("--lloyd", type=int, default=20)
    t = sub.add_parser("tip")
    t.add_argument("h5")
    a = ap.parse_args(argv)
    if a.cmd == "deck":
        make_deck(a.out, a.cells, a.seed, a.lloyd)
    else:
        uy, err, rel = tip(a.h5)
        print(f"{uy:.6e},{TIP_EXACT:.6e},{err:.3e},{rel:.3e}")


if __name__ == "__main__":
    main()
