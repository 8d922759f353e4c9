"""Meshes for the accuracy study: the mesher's CLI (vctools.mesh scene) for rectangles,
Voronoi bodies and the Hertz half model, and a polar grid of our own for the quarter
annulus (the mesher has no structured annulus).  Mesh files are cached by name under
the work folder: a second run reuses them (delete the folder to rebuild)."""
from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PY = sys.executable


class Mesh:
    """Nodes and polygons of a mesh .inp (what *NODE and *ELEMENT hold)."""

    def __init__(self, ids, xy, elems, etype):
        self.ids = np.asarray(ids)          # user node ids
        self.xy = np.asarray(xy, float)     # (n, 2)
        self.elems = elems                  # list of (elem id, [node ids])
        self.etype = etype
        self.index = {int(i): k for k, i in enumerate(self.ids)}


def read_inp(path):
    """*NODE and *ELEMENT blocks of a mesher file (continued element lines included)."""
    ids, xy, elems, etype = [], [], [], None
    mode, pending = None, []
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                mode = None
                kw = s.upper().replace(" ", "")
                if kw.startswith("*NODE"):
                    mode = "node"
                elif kw.startswith("*ELEMENT"):
                    mode = "elem"
                    etype = [p.split("=")[1] for p in kw.split(",") if p.startswith("TYPE=")][0]
                continue
            if mode == "node":
                p = s.split(",")
                ids.append(int(p[0]))
                xy.append((float(p[1]), float(p[2])))
            elif mode == "elem":
                pending += [t for t in s.split(",") if t.strip()]
                if not s.endswith(","):
                    v = [int(t) for t in pending]
                    elems.append((v[0], v[1:]))
                    pending = []
    return Mesh(ids, xy, elems, etype)


def mesher(toml_text, name, workdir, seed=None):
    """Run `python -m vctools.mesh scene` on a scene text; returns the output path(s).
    Cached: when the expected output exists it is not regenerated."""
    os.makedirs(workdir, exist_ok=True)
    scene = os.path.join(workdir, name + ".toml")
    out = os.path.join(workdir, name + ".inp")
    if os.path.exists(out):
        return out
    with open(scene, "w") as f:
        f.write(toml_text)
    cmd = [PY, "-m", "vctools.mesh", "scene", scene, "-o", out, "--processes", "2"]
    if seed is not None:
        cmd += ["--seed", str(seed)]
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"mesher failed on {scene}:\n{r.stdout}\n{r.stderr}")
    return out


def rectangle(workdir, tag, box, shape, n, plane="strain", lloyd=20, formulation="vem", order=1):
    """A rectangle body B: shape 'quad'/'tri' with divisions n = (nx, ny), or
    'voronoi' with n = number of cells.  Written as VPE/VPS (the section decides VEM/FEM);
    order 2: the mesher's second-order mesh (VPE2/VPS2, or CPE8/CPE6 with formulation 'fem')."""
    x0, y0, x1, y1 = box
    if shape == "voronoi":
        body = f'mesher = "voronoi"\ncells = {int(n)}\n'
    else:
        body = f'mesher = "{shape}"\ndivisions = [{n[0]}, {n[1]}]\n'
    text = (f'[mesh]\nseed = 7\nlloyd = {lloyd}\nformulation = "{formulation}"\nplane = "{plane}"\n'
            + (f'order = {order}\n' if order != 1 else '') +
            f'title = "accuracy study {tag}"\n\n[[body]]\nname = "B"\n'
            f'rectangle = [{float(x0)!r}, {float(y0)!r}, {float(x1)!r}, {float(y1)!r}]\n' + body)
    return mesher(text, tag, workdir)


def annulus_voronoi(workdir, tag, a, b, cells, lloyd=20, formulation="vem", order=1):
    """Quarter annulus a <= r <= b, x, y >= 0, as a polygon whose arcs have about one
    vertex per cell size (the mesher keeps polygon vertices as nodes)."""
    h = math.sqrt(math.pi / 4 * (b * b - a * a) / cells)
    ni = max(2, math.ceil(math.pi / 2 * a / h))
    no = max(2, math.ceil(math.pi / 2 * b / h))
    outer = [(b * math.cos(t), b * math.sin(t)) for t in np.linspace(0, math.pi / 2, no + 1)]
    inner = [(a * math.cos(t), a * math.sin(t)) for t in np.linspace(math.pi / 2, 0, ni + 1)]
    pts = outer + inner
    pts[no] = (0.0, b)
    pts[no + 1] = (0.0, a)
    pts[0] = (b, 0.0)
    pts[-1] = (a, 0.0)
    poly = ", ".join(f"[{float(x)!r}, {float(y)!r}]" for x, y in pts)
    text = (f'[mesh]\nseed = 7\nlloyd = {lloyd}\nformulation = "{formulation}"\nplane = "strain"\n'
            + (f'order = {order}\n' if order != 1 else '') +
            f'title = "accuracy study {tag}"\n\n[[body]]\nname = "B"\npolygon = [{poly}]\n'
            f'mesher = "voronoi"\ncells = {int(cells)}\n')
    return mesher(text, tag, workdir)


def annulus_polar(workdir, tag, a, b, nr, nt, shape, formulation="vem", order=1):
    """Polar grid of the quarter annulus: nr radial by nt angular cells, nodes exactly on
    the arcs; 'tri' splits each quad with alternating diagonals (as the mesher does).
    order 2: a node on every side, shared by its two cells, after the corners (Abaqus
    order), in the middle of a radial side and on the arc for a side along a circle (the
    side is then the quadratic curve through its three nodes: isoparametric CPE8/CPE6,
    curved VPE2 sides), as the mesher does."""
    out = os.path.join(workdir, tag + ".inp")
    if os.path.exists(out):
        return out
    os.makedirs(workdir, exist_ok=True)
    r = np.linspace(a, b, nr + 1)
    t = np.linspace(0.0, math.pi / 2, nt + 1)
    R, T = np.meshgrid(r, t, indexing="ij")          # node (i, j) -> i*(nt+1)+j
    x, y = R * np.cos(T), R * np.sin(T)
    x[:, -1] = 0.0
    y[:, 0] = 0.0
    nid = lambda i, j: i * (nt + 1) + j + 1
    cells = []
    for i in range(nr):
        for j in range(nt):
            q = [nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)]   # CCW in (r, t)
            if shape == "quad":
                cells.append(q)
            elif (i + j) % 2 == 0:
                cells += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
            else:
                cells += [[q[0], q[1], q[3]], [q[1], q[2], q[3]]]
    xs, ys = list(x.ravel()), list(y.ravel())
    etype = "VPE"
    if order == 2:
        side = {}
        for c in cells:
            mids = []
            for s in range(len(c)):
                i, j = c[s], c[(s + 1) % len(c)]
                key = (min(i, j), max(i, j))
                if key not in side:
                    px, py = (xs[i - 1] + xs[j - 1]) / 2, (ys[i - 1] + ys[j - 1]) / 2
                    ri, rj = math.hypot(xs[i - 1], ys[i - 1]), math.hypot(xs[j - 1], ys[j - 1])
                    if abs(ri - rj) < 1e-12 * b:       # a side along an arc
                        t = math.atan2(py, px)
                        px, py = ri * math.cos(t), ri * math.sin(t)
                    xs.append(px)
                    ys.append(py)
                    side[key] = len(xs)
                mids.append(side[key])
            c += mids
        etype = "VPE2" if formulation == "vem" else ("CPE8" if shape == "quad" else "CPE6")
    with open(out, "w") as f:
        f.write(f"** polar grid of the quarter annulus {a} <= r <= {b}: {nr} x {nt} {shape}, order {order}\n")
        f.write("*NODE, NSET=NALL\n")
        for k, (xx, yy) in enumerate(zip(xs, ys)):
            f.write(f"{k + 1}, {float(xx)!r}, {float(yy)!r}\n")
        f.write(f"*ELEMENT, TYPE={etype}, ELSET=B\n")
        for e, c in enumerate(cells):
            f.write(f"{e + 1}, " + ", ".join(map(str, c)) + "\n")
    return out
