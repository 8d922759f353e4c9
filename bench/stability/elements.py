"""Element-level extremes swept to breakdown (issue 6, item 2, part B).

    usage: .venv/bin/python bench/stability/elements.py [--exe PATH] [--work DIR] [--no-doc]

Three sweeps, every number from runs of the vemcontact executable:

1. nu -> 0.5 in plane strain (volumetric locking): the Lame thick cylinder under
   internal pressure and the Timoshenko cantilever with parabolic end shear (plane-strain
   form of bench/accuracy's exact field) on one fixed mesh per family (VEM on Voronoi
   cells, VEM on quads, FEM quads, FEM triangles).  Errors against the exact solution and
   the locking factor error(nu) / error(0.3).
2. Distortion: the paper's example 1 (two quads, shared edge skewed by 2d/b) for 2d/b from
   0 to 10, and a 2 x 2 cantilever whose centre node is dragged towards a corner (convex,
   then non-convex, then degenerate, then tangled); tip deflection ratio, what the code
   says, and the stability of each element: the smallest non-zero eigenvalue of its
   stiffness over the largest.  Strongly non-convex single cells (stars, combs, L, U,
   slits with reflex angles near 360 degrees) get a single-element patch test.
3. Short edges: a hexagonal (Voronoi-like) cell with one edge shrunk to eps of the
   diameter, a near-duplicate vertex inserted on a side, and two cells sharing the short
   edge: patch-test error, element eigenvalue ratio, CHOLMOD's rcond, down to eps = 0.

Element stiffness eigenvalues come from the code, not from a re-implementation: a single
element deck with 3 dofs held is run with --write-matrix, which gives the free-free block
K_ff of the element stiffness; the rigid modes R (K R = 0) then give the rest,
K_fc = -K_ff R_f R_c^-1 and K_cc = -K_cf R_f R_c^-1, so the full K is recovered exactly.

Writes bench/results/stability_{nu,distortion,short_edges}.csv and docs/stability-elements.md.
"""
from __future__ import annotations

import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import scipy.io

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "accuracy"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from machine_info import describe  # noqa: E402
import cases   # noqa: E402
import fields  # noqa: E402
import meshes  # noqa: E402

EXE = os.path.join(ROOT, "build", "vemcontact")
NUS = [0.3, 0.45, 0.49, 0.499, 0.4999]
_RCOND = re.compile(r"rcond\s+([0-9.Ee+-]+)")


# ------------------------------------------------------------------ running decks
def run_deck(text, job, work, matrix=False):
    """Run a deck; returns dict(rc, msg (first error/warning lines), log, h5, mtx, rcond)."""
    ddir, odir = os.path.join(work, "decks"), os.path.join(work, "out", job)
    os.makedirs(ddir, exist_ok=True)
    os.makedirs(odir, exist_ok=True)
    deck = os.path.join(ddir, job + ".inp")
    with open(deck, "w") as f:
        f.write(text)
    cmd = [EXE, "-q", "-o", odir] + (["--write-matrix"] if matrix else []) + [deck]
    r = subprocess.run(cmd, capture_output=True, text=True)
    logp = os.path.join(odir, job + ".log")
    log = open(logp).read() if os.path.exists(logp) else ""
    m = _RCOND.findall(log)
    msg = " | ".join(ln.strip() for ln in (r.stderr + "\n" + log).splitlines()
                     if "error:" in ln or "warning:" in ln)
    msg = " | ".join(dict.fromkeys(msg.split(" | ")))       # drop repeats (stderr and log)
    return dict(rc=r.returncode, msg=msg, log=log, h5=os.path.join(odir, job + ".h5"),
                mtx=os.path.join(odir, job + ".mtx"), rcond=float(m[-1]) if m else float("nan"))


def poly_deck(title, xy, elems, fixed, cloads, E=1000.0, nu=0.3, form="VEM", plane="VPE"):
    """Deck of a polygon mesh: xy (n,2) nodes 1..n, elems lists of 1-based node ids,
    fixed = [(node, dof, value)], cloads = [(node, dof, value)]."""
    s = [f"** stability study (bench/stability/elements.py): {title}", "*NODE"]
    s += [f"{i + 1}, {float(x)!r}, {float(y)!r}" for i, (x, y) in enumerate(xy)]
    s.append(f"*ELEMENT, TYPE={plane}, ELSET=B")
    s += [f"{k + 1}, " + ", ".join(str(v) for v in c) for k, c in enumerate(elems)]
    s += ["*MATERIAL, NAME=M", "*ELASTIC", f"{float(E)!r}, {float(nu)!r}",
          f"*SOLID SECTION, ELSET=B, MATERIAL=M, FORMULATION={form}", "1.0", "*BOUNDARY"]
    s += [f"{n}, {d}, {d}, {float(v)!r}" for n, d, v in fixed]
    s += ["*STEP", "*STATIC", "*CLOAD"]
    s += [f"{n}, {d}, {float(v)!r}" for n, d, v in cloads if v != 0.0]
    s += ["*END STEP", ""]
    return "\n".join(s)


def read_u(h5):
    return fields.read_result(h5)["U"]


# ------------------------------------------------------------------ patch test
GRAD = np.array([[2.0e-3, 3.0e-3], [1.0e-3, -4.0e-3]])     # u = u0 + G x: strain and rotation
U0 = np.array([1.0e-3, -2.0e-3])


def patch_test(xy, elems, job, work, E=1000.0, nu=0.3, form="VEM", matrix=False):
    """Linear displacement u = U0 + G (x - x1) on any polygon mesh: the consistent nodal
    forces of its constant stress on every node (sum over elements of t sigma q_i, q_i half
    the rotated chord of the neighbours: the integral of N_i n over the two sides, for any
    element whose shape functions are linear on the sides), the exact values on 3 dofs.
    Returns (run result, relative max nodal error, fixed dofs)."""
    xy = np.asarray(xy, float)
    n = len(xy)
    # scale-free: the field is relative to node 1 and to the mesh size
    h = np.ptp(xy, axis=0).max()
    x1 = xy[0]
    uex = U0 * h + (xy - x1) @ GRAD.T
    eps = np.array([GRAD[0, 0], GRAD[1, 1], GRAD[0, 1] + GRAD[1, 0]])
    D = fields.stiffness(E, nu, "strain")
    sx, sy, txy = D @ eps
    sig = np.array([[sx, txy], [txy, sy]])
    f = np.zeros((n, 2))
    for c in elems:
        c0 = [v - 1 for v in c]
        m = len(c0)
        for k in range(m):
            p, q = xy[c0[(k - 1) % m]], xy[c0[(k + 1) % m]]
            qi = 0.5 * np.array([q[1] - p[1], -(q[0] - p[0])])
            f[c0[k]] += sig @ qi
    # hold node 1 and the component of the farthest node across the line to it
    far = int(np.argmax(np.linalg.norm(xy - x1, axis=1)))
    dfar = 2 if abs(xy[far, 0] - x1[0]) >= abs(xy[far, 1] - x1[1]) else 1
    fixed = [(1, 1, uex[0, 0]), (1, 2, uex[0, 1]), (far + 1, dfar, uex[far, dfar - 1])]
    held = {(1, 1), (1, 2), (far + 1, dfar)}
    cl = [(i + 1, d + 1, f[i, d]) for i in range(n) for d in range(2) if (i + 1, d + 1) not in held]
    r = run_deck(poly_deck(job, xy, elems, fixed, cl, E, nu, form), job, work, matrix)
    err = float("nan")
    if r["rc"] == 0:
        u = read_u(r["h5"])
        err = float(np.abs(u - uex).max() / np.abs(uex).max())
    fdofs = [2 * (nd - 1) + (d - 1) for nd, d, _ in fixed]
    return r, err, fdofs


def element_eigen_ratio(xy, r, fdofs):
    """Smallest non-zero over largest eigenvalue of the element stiffness recovered from the
    run's matrix (a single element with 3 dofs held); also the rigid-mode residual
    max|lam_1..3| / lam_max, which checks the recovery."""
    if r["rc"] != 0 or not os.path.exists(r["mtx"]):
        return float("nan"), float("nan")
    kb = scipy.io.mmread(r["mtx"]).toarray()
    kb = np.triu(kb) + np.triu(kb, 1).T if np.allclose(np.tril(kb, -1), 0) else kb
    xy = np.asarray(xy, float)
    n = len(xy)
    c = np.asarray(fdofs)
    f = np.setdiff1d(np.arange(2 * n), c)
    rel = xy - xy.mean(0)
    R = np.zeros((2 * n, 3))
    R[0::2, 0] = 1
    R[1::2, 1] = 1
    R[0::2, 2] = -rel[:, 1]
    R[1::2, 2] = rel[:, 0]
    Kff = kb[np.ix_(f, f)]
    T = R[f] @ np.linalg.inv(R[c])
    Kfc = -Kff @ T
    Kcc = -Kfc.T @ T
    K = np.zeros((2 * n, 2 * n))
    K[np.ix_(f, f)] = Kff
    K[np.ix_(f, c)] = Kfc
    K[np.ix_(c, f)] = Kfc.T
    K[np.ix_(c, c)] = Kcc
    lam = np.linalg.eigvalsh(0.5 * (K + K.T))
    return float(lam[3] / lam[-1]), float(np.abs(lam[:3]).max() / lam[-1])


# ------------------------------------------------------------------ 1. nu sweep
class TimoshenkoStrain(fields.Timoshenko):
    """Plane-strain form of the Timoshenko cantilever: the plane-stress field with
    E* = E/(1-nu^2), nu* = nu/(1-nu) (same stresses, same boundary tractions)."""
    plane = "strain"
    nu = 0.3

    def u(self, x, y):
        E, nu = self.E, self.nu
        Es, nus = E / (1 - nu * nu), nu / (1 - nu)
        L, D, P, I = self.L, self.D, self.P, self.I
        ux = -P * y / (6 * Es * I) * ((6 * L - 3 * x) * x + (2 + nus) * (y * y - D * D / 4))
        uy = P / (6 * Es * I) * (3 * nus * y * y * (L - x) + (4 + 5 * nus) * D * D * x / 4 + (3 * L - x) * x * x)
        return np.stack([ux, uy], -1)


def timoshenko_strain(work, fam, k, nu):
    """The Timoshenko deck of bench/accuracy/cases.py on a plane-strain (VPE) mesh."""
    case = TimoshenkoStrain()
    case.nu = nu
    if nu <= 0.45:      # finite differences times lambda ~ 1/(1-2nu) lose the check's digits beyond
        fields.check_exact(case, pts=[(5.0, 1.0), (20.0, -3.0), (40.0, 4.5)])
    L, D = case.L, case.D
    shape = cases.SHAPE[fam]
    box = (0.0, -D / 2, L, D / 2)
    if shape == "voronoi":
        mp = meshes.rectangle(work + "/meshes", f"stc_vor_{4 * k * k}", box, "voronoi", 4 * k * k, plane="strain")
        desc = f"{4 * k * k} Voronoi cells"
    else:
        mp = meshes.rectangle(work + "/meshes", f"stc_{shape}_{k}", box, shape, (4 * k, k), plane="strain")
        desc = f"{4 * k}x{k} {'quads' if shape == 'quad' else 'quads split in 2'}"
    m = meshes.read_inp(mp)
    deck = cases._header("Timoshenko cantilever, plane strain", cases._rel_include(work + "/decks", mp),
                         case.E, case.nu, cases.FORMULATION[fam])
    tol = 1e-9 * L
    clamp = cases._boundary_nodes(m, lambda x, y: x < tol)
    tip = sorted(cases._boundary_nodes(m, lambda x, y: x > L - tol), key=lambda i: m.xy[m.index[i], 1])
    ys = np.array([m.xy[m.index[i], 1] for i in tip])
    f = cases._edge_forces(ys, lambda y: case.P / (2 * case.I) * (D * D / 4 - y * y))
    u = case.u(m.xy[:, 0], m.xy[:, 1])
    lines = ["*BOUNDARY"]
    for i in clamp:
        kk = m.index[i]
        lines += [f"{i}, 1, 1, {float(u[kk, 0])!r}", f"{i}, 2, 2, {float(u[kk, 1])!r}"]
    lines += ["*STEP", "*STATIC", "*CLOAD"] + [f"{i}, 2, {float(fi)!r}" for i, fi in zip(tip, f) if fi != 0.0]
    deck += "\n".join(lines) + "\n*END STEP\n"

    def metrics(res):
        x = res["x"]
        on = np.abs(x[:, 0] - L) < 1e-9 * L
        o = np.argsort(x[on, 1])
        uy = np.interp(0.0, x[on, 1][o], res["U"][on, 1][o])
        return dict(tip_ratio=uy / case.tip(), tip=abs(uy - case.tip()) / abs(case.tip()),
                    energy=fields.energy_error(res, case), u_l2=fields.u_l2_error(res, case))
    return deck, metrics, desc, len(m.elems)


TIMO_K = 8      # 32 x 8 quads (256 elements), 256 Voronoi cells
LAME_NR = 8     # 8 x 19 polar quads, 152 Voronoi cells


def sweep_nu(work):
    rows = []
    for fam in cases.FAMILIES:
        for nu in NUS:
            deck, metrics, desc, ne = timoshenko_strain(work, fam, TIMO_K, nu)
            job = f"nu_timo_{fam}_{nu}".replace(".", "_")
            r = run_deck(deck, job, work)
            row = dict(case="timoshenko", family=fam, mesh=desc, elements=ne, nu=nu, rc=r["rc"],
                       rcond=r["rcond"], message=r["msg"])
            if r["rc"] == 0:
                row.update(metrics(fields.read_result(r["h5"])))
            rows.append(row)
            print(f"  timoshenko {fam:12s} nu {nu:<7} rc {r['rc']} " +
                  " ".join(f"{k} {row[k]:.3e}" for k in ("tip_ratio", "energy", "u_l2") if k in row), flush=True)
        old = fields.Lame.nu
        try:
            for nu in NUS:
                fields.Lame.nu = nu
                run = next(rr for rr in cases.lame(work, quick=True) if rr.family == fam and rr.level == LAME_NR)
                job = f"nu_lame_{fam}_{nu}".replace(".", "_")
                r = run_deck(run.deck, job, work)
                row = dict(case="lame", family=fam, mesh=run.mesh_desc, elements=run.elements, nu=nu, rc=r["rc"],
                           rcond=r["rcond"], message=r["msg"])
                if r["rc"] == 0:
                    met = run.metrics(fields.read_result(r["h5"]))
                    row.update(energy=met["energy"], u_l2=met["u_l2"], hoop=met["hoop"])
                rows.append(row)
                print(f"  lame       {fam:12s} nu {nu:<7} rc {r['rc']} " +
                      " ".join(f"{k} {row[k]:.3e}" for k in ("energy", "u_l2") if k in row), flush=True)
        finally:
            fields.Lame.nu = old
    base = {(r["case"], r["family"]): r for r in rows if r["nu"] == 0.3}
    for r in rows:
        b = base[(r["case"], r["family"])]
        for k in ("tip", "energy", "u_l2"):
            if k in r and k in b:
                r[f"lock_{k}"] = r[k] / b[k]
    return rows


# ------------------------------------------------------------------ 2. distortion
EX1_L, EX1_B, EX1_E, EX1_M = 40.0, 8.0, 1000.0, 16.0
EX1_EXACT = EX1_M * EX1_L ** 2 / (2 * EX1_E * EX1_B ** 3 / 12)      # 0.3


def example1_mesh(db):
    d = 0.5 * db * EX1_B
    xy = [(0, 0), (EX1_L / 2 - d, 0), (EX1_L, 0), (EX1_L, EX1_B), (EX1_L / 2 + d, EX1_B), (0, EX1_B)]
    return np.array(xy, float), [[1, 2, 5, 6], [2, 3, 4, 5]], 3, 4, [(1, 1), (1, 2), (6, 1)]


def drag_mesh(t):
    """2 x 2 quads on the same beam; the centre node moves from (L/2, b/2) towards the
    top-left corner (0, b): P = (L/2 (1-t), b/2 (1+t)).  The upper-left quad turns
    non-convex at t = 0.5 (P crosses its diagonal), the centre node reaches the corner
    node at t = 1 (zero-length side, folded lower-left quad), beyond it the mesh tangles."""
    L, b = EX1_L, EX1_B
    P = (L / 2 * (1 - t), b / 2 * (1 + t))
    xy = [(0, 0), (L / 2, 0), (L, 0), (0, b / 2), P, (L, b / 2), (0, b), (L / 2, b), (L, b)]
    return (np.array(xy, float), [[1, 2, 5, 4], [2, 3, 6, 5], [4, 5, 8, 7], [5, 6, 9, 8]], 3, 9,
            [(1, 1), (1, 2), (4, 1), (7, 1)])


def cantilever_deck(xy, elems, bot, top, held, form):
    fixed = [(n, d, 0.0) for n, d in held]
    cl = [(bot, 1, EX1_M / EX1_B), (top, 1, -EX1_M / EX1_B)]
    return poly_deck("cantilever with end moment", xy, elems, fixed, cl, EX1_E, 0.0, form)


def convexity(xy):
    """'convex', 'non-convex', or 'not simple' (shapely), with the largest interior angle."""
    from shapely.geometry import Polygon
    p = Polygon(xy)
    n = len(xy)
    ang = []
    a = 0.5 * sum(xy[k - 1][0] * xy[k][1] - xy[k][0] * xy[k - 1][1] for k in range(n))
    for k in range(n):
        e1 = np.subtract(xy[k], xy[k - 1])
        e2 = np.subtract(xy[(k + 1) % n], xy[k])
        if np.linalg.norm(e1) == 0 or np.linalg.norm(e2) == 0:
            ang.append(float("nan"))
            continue
        turn = math.atan2(e1[0] * e2[1] - e1[1] * e2[0], e1 @ e2) * (1 if a >= 0 else -1)
        ang.append(180.0 - math.degrees(turn))
    kind = "not simple" if (not p.is_valid or p.area <= 0 or any(map(math.isnan, ang))) else \
        ("convex" if max(ang) < 180.0 + 1e-9 else "non-convex")
    return kind, max((x for x in ang if not math.isnan(x)), default=float("nan"))


def sweep_distortion(work):
    rows = []
    fams = [("example1", example1_mesh, [0, 0.5, 1, 2, 3, 4, 4.5, 4.9, 4.99, 5, 5.01, 5.5, 6, 8, 10]),
            ("drag", drag_mesh, [0, 0.25, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99, 1.0, 1.01, 1.1, 1.25])]
    for fam, gen, params in fams:
        for p in params:
            xy, elems, bot, top, held = gen(p)
            shapes = [convexity([tuple(xy[v - 1]) for v in c]) for c in elems]
            row = dict(mesh=fam, param=p, shapes="; ".join(f"{k} {a:.1f}" for k, a in shapes))
            for form in ("VEM", "FEM"):
                job = f"dist_{fam}_{p}_{form}".replace(".", "_")
                r = run_deck(cantilever_deck(xy, elems, bot, top, held, form), job, work)
                row[f"{form.lower()}_rc"] = r["rc"]
                row[f"{form.lower()}_rcond"] = r["rcond"]
                row[f"{form.lower()}_message"] = r["msg"]
                row[f"{form.lower()}_tip_ratio"] = float("nan")
                if r["rc"] == 0:
                    u = read_u(r["h5"])
                    row[f"{form.lower()}_tip_ratio"] = 0.5 * (u[bot - 1, 1] + u[top - 1, 1]) / EX1_EXACT
                # stability of each element on its own (3 dofs held, the patch test's loads)
                worst = float("inf")
                for k, c in enumerate(elems):
                    rr, err, fd = patch_test([tuple(xy[v - 1]) for v in c], [[1, 2, 3, 4]],
                                             f"{job}_e{k + 1}", work, form=form, matrix=True)
                    lam, _ = element_eigen_ratio([tuple(xy[v - 1]) for v in c], rr, fd)
                    if not math.isnan(lam):
                        worst = min(worst, lam)
                    if k == 0 or not math.isnan(err):
                        row[f"{form.lower()}_patch"] = max(row.get(f"{form.lower()}_patch", 0.0) or 0.0,
                                                           err if not math.isnan(err) else 0.0)
                row[f"{form.lower()}_eig_ratio_min"] = worst if worst < float("inf") else float("nan")
            rows.append(row)
            print(f"  {fam:9s} {p:<6} {row['shapes']:40s} VEM {row['vem_tip_ratio']:.4f} "
                  f"FEM {row['fem_tip_ratio']:.4f} eig VEM {row['vem_eig_ratio_min']:.2e} "
                  f"FEM {row['fem_eig_ratio_min']:.2e} | {row['vem_message'][:60]} | {row['fem_message'][:60]}",
                  flush=True)
    return rows


def star(n, inner):
    t = 2 * np.pi * np.arange(n) / n
    r = np.where(np.arange(n) % 2 == 0, 1.0, inner)
    return np.c_[r * np.cos(t), r * np.sin(t)]


def comb(teeth, gap):
    """A comb of `teeth` teeth on the base [0, 1] x [0, 0.2], teeth up to y = 1; the slots
    between them take the fraction `gap` of the width: a 4*teeth-gon."""
    sw = gap / (teeth - 1)
    tw = (1.0 - gap) / teeth
    x0 = [k * (tw + sw) for k in range(teeth)]
    pts = [(0.0, 0.0), (1.0, 0.0)]
    for k in range(teeth - 1, -1, -1):
        pts += [(x0[k] + tw, 1.0), (x0[k], 1.0)]
        if k > 0:
            pts += [(x0[k], 0.2), (x0[k - 1] + tw, 0.2)]
    pts[2] = (1.0, 1.0)
    pts[-1] = (0.0, 1.0)
    return np.array(pts, float)


def slit(width):
    """Unit square with a slit from the middle of the right side to the centre, of angular
    opening `width` (radians) at its tip: the tip's interior angle is 360 deg - width."""
    hw = 0.5 * math.tan(width / 2)       # width < 90 deg: the slit ends inside the side
    return np.array([(0, 0), (1, 0), (1, 0.5 - hw), (0.5, 0.5), (1, 0.5 + hw), (1, 1), (0, 1)], float)


def nonconvex_shapes():
    out = [("square", np.array([(0, 0), (1, 0), (1, 1), (0, 1)], float)),
           ("L", np.array([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)], float)),
           ("L thin (arms 1/20)", np.array([(0, 0), (1, 0), (1, .05), (.05, .05), (.05, 1), (0, 1)], float)),
           ("U", np.array([(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)], float)),
           ("U deep slot 1/50", np.array([(0, 0), (1.02, 0), (1.02, 1), (.52, 1), (.52, .02), (.5, .02),
                                          (.5, 1), (0, 1)], float))]
    for n in (12, 16, 20):
        for inner in (0.5, 0.2, 0.05):
            out.append((f"star {n}-gon inner {inner}", star(n, inner)))
    for teeth, gap in ((3, 0.5), (6, 0.5), (8, 0.9)):
        out.append((f"comb {teeth} teeth gap {gap} ({4 * teeth}-gon)", comb(teeth, gap)))
    for deg in (60, 10, 1, 0.1, 0.01):
        out.append((f"slit, reflex {360 - deg:g} deg", slit(math.radians(deg))))
    return out


def sweep_shapes(work):
    rows = []
    for name, xy in nonconvex_shapes():
        kind, amax = convexity([tuple(p) for p in xy])
        for form in ("VEM",):
            job = "shape_" + re.sub(r"[^A-Za-z0-9]+", "_", name) + "_" + form
            r, err, fd = patch_test(xy, [list(range(1, len(xy) + 1))], job, work, form=form, matrix=True)
            lam, rig = element_eigen_ratio(xy, r, fd)
            rows.append(dict(mesh="shape", param=name, shapes=f"{kind} {amax:.2f}", vem_rc=r["rc"],
                             vem_message=r["msg"], vem_patch=err, vem_eig_ratio_min=lam, rigid_residual=rig,
                             rcond=r["rcond"], vertices=len(xy)))
            print(f"  {name:34s} {kind:10s} max angle {amax:8.3f} patch {err:.2e} eig {lam:.2e} "
                  f"rcond {r['rcond']:.2e} rc {r['rc']} {r['msg'][:80]}", flush=True)
    return rows


# ------------------------------------------------------------------ 3. short edges
EPS = [1e-2, 1e-4, 1e-6, 1e-8, 1e-9, 3e-10, 1e-10, 1e-11, 1e-12, 1e-14, 0.0]


def hexagon_short(eps):
    """Regular hexagon of circumradius 1 (diameter 2) with its right (vertical) side
    shrunk to eps * 2 about its midpoint."""
    ang = np.radians([-30, 30, 90, 150, 210, 270])
    xy = np.c_[np.cos(ang), np.sin(ang)]
    xy[0] = (math.sqrt(3) / 2, -eps)
    xy[1] = (math.sqrt(3) / 2, eps)
    return xy


def hexagon_near_duplicate(eps):
    """Regular hexagon with a 7th vertex on side 1-2 at eps * 2 from vertex 1 (collinear)."""
    ang = np.radians([-30, 30, 90, 150, 210, 270])
    xy = np.c_[np.cos(ang), np.sin(ang)]
    v = xy[1] - xy[0]
    extra = xy[0] + v / np.linalg.norm(v) * 2 * eps
    return np.vstack([xy[:1], extra, xy[1:]])


def honeycomb(eps, rings=2):
    """Hexagonal Voronoi cells (circumradius 1) around the origin, `rings` rings of
    neighbours; the centre cell's right side is shrunk to eps * 2 about its midpoint by
    moving its two ends, which the right, upper-right and lower-right neighbours share:
    four cells then nearly meet in one point, as when four Voronoi generators are nearly
    cocircular.  Returns nodes and counter-clockwise cells (1-based)."""
    s3 = math.sqrt(3)
    centres = []
    for q in range(-rings, rings + 1):
        for r in range(-rings, rings + 1):
            if abs(q + r) <= rings:
                centres.append((s3 * (q + r / 2), 1.5 * r))
    ang = np.radians([-30, 30, 90, 150, 210, 270])
    keys, xy, cells = {}, [], []
    for cx, cy in centres:
        c = []
        for a in ang:
            p = (cx + math.cos(a), cy + math.sin(a))
            k = (round(p[0], 6), round(p[1], 6))
            if k not in keys:
                keys[k] = len(xy)
                xy.append(list(p))
            c.append(keys[k] + 1)
        cells.append(c)
    xy = np.array(xy)
    xy[keys[(round(s3 / 2, 6), -0.5)]] = (s3 / 2, -eps)
    xy[keys[(round(s3 / 2, 6), 0.5)]] = (s3 / 2, eps)
    return xy, cells


def sweep_short_edges(work):
    rows = []
    for eps in EPS:
        for kind in ("short side", "near-duplicate vertex", "19 Voronoi cells, 4 meeting at the short side"):
            if kind == "short side":
                xy, elems = hexagon_short(eps), [[1, 2, 3, 4, 5, 6]]
            elif kind == "near-duplicate vertex":
                xy, elems = hexagon_near_duplicate(eps), [[1, 2, 3, 4, 5, 6, 7]]
            else:
                xy, elems = honeycomb(eps)
            job = f"short_{kind.split()[0]}_{kind.split()[1]}_{eps:g}".replace(".", "_").replace("-", "m")
            single = len(elems) == 1
            r, err, fd = patch_test(xy, elems, job, work, matrix=single)
            lam, rig = element_eigen_ratio(xy, r, fd) if single else (float("nan"), float("nan"))
            rows.append(dict(kind=kind, eps=eps, rc=r["rc"], patch=err, eig_ratio=lam, rigid_residual=rig,
                             rcond=r["rcond"], message=r["msg"]))
            print(f"  {kind:34s} eps {eps:<8g} rc {r['rc']} patch {err:.2e} eig {lam:.2e} rcond "
                  f"{r['rcond']:.2e} {r['msg'][:90]}", flush=True)
    return rows


# ------------------------------------------------------------------ output
def machine():
    return describe()


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def _f(v, fmt="{:.3g}"):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else fmt.format(v)


def _msg(m, n=150):
    m = re.sub(r"^\S+\.inp:\d+: ", "", m.split(" | ")[0]) if m else ""
    return (m[:n] + "...") if len(m) > n else m


def write_doc(out, mach, path):
    nu, dist, short = out["nu"], out["distortion"], out["short"]
    L = ["# Element-level stability: nu -> 0.5, distortion, non-convex cells, short sides", "",
         "Issue 6, item 2 (part B). Every number below comes from runs of the `vemcontact` executable,",
         "written by `bench/stability/elements.py` (one command, about 5 minutes:",
         "`.venv/bin/python bench/stability/elements.py`), raw numbers in",
         "`bench/results/stability_{nu,distortion,short_edges}.csv`. Machine: " + mach + ".",
         "Fast tests that lock the behaviour: `tests/unit/element/test_element_extremes.f90`.", "",
         "## Summary", "",
         "| sweep | breakdown | what the code does there |", "|---|---|---|",
         "| nu -> 0.5, plane strain | FEM quads and triangles lock: tip deflection 0.27 (Q4) and 0.16 (CST) of "
         "exact at nu = 0.4999 | warning per element set for nu > 0.45 on FEM elements (`element_warnings`, "
         "printed at the start of the run, test postprocess/tests/test_element_warnings.py); the VEM no longer locks (stabilisation with lambda capped at 2 mu) |",
         "| example 1, 2d/b | quads convex (largest angle 168.7 deg) up to 2d/b = 5, where nodes coincide; "
         "tangled beyond | stop, exit 1: 'has a zero-length side: its nodes 1 and 2 coincide', then 'is "
         "self-intersecting: its sides 2-5 and 6-1 cross' |",
         "| a node dragged into a neighbour | VEM fine while non-convex (to 267 deg); eigenvalue ratio falls "
         "like (1-t)^4 as the cell's area vanishes, rcond like (1-t)^3, answer stays sensible | FEM: "
         "warning for non-convex quads, stop when the map folds at a Gauss point (naming angle and node); "
         "both: stop when the nodes meet ('pinched') |",
         "| non-convex single cells | none: stars, combs (32-gon), thin L, deep U, slit at 359.99 deg all pass "
         "the patch test to 1e-13 | - |",
         "| short sides | none down to 3e-10 of the diameter (patch 1e-15, eigenvalue ratio and rcond "
         "unchanged) | sides <= 1e-10 of the diameter: stop, 'has a zero-length side ... merge the two nodes' |",
         ""]
    # ---- nu
    L += ["## 1. Poisson's ratio to 0.4999, plane strain", "",
          "Timoshenko cantilever (L = 48, D = 12, parabolic end shear, exact displacements held at x = 0; "
          "the plane-strain form of bench/accuracy's field: E/(1-nu^2), nu/(1-nu)) on 32 x 8 quads / "
          "the same split in triangles / 256 Voronoi cells; Lame cylinder (a = 1, b = 2, internal pressure) on "
          "8 x 19 polar quads / 152 Voronoi cells. Errors relative to the exact solution; locking factor = "
          "error at nu / error at nu = 0.3.", "",
          "| case | family | nu | tip / exact | tip error | energy error | u L2 error | locking (u L2) | rcond |",
          "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in nu:
        L.append(f"| {r['case']} | {r['family']} | {r['nu']} | {_f(r.get('tip_ratio'), '{:.4f}')} | "
                 f"{_f(r.get('tip'))} | {_f(r.get('energy'))} | {_f(r.get('u_l2'))} | {_f(r.get('lock_u_l2'))} | "
                 f"{_f(r.get('rcond'))} |")
    L += ["",
          "Before this change the VEM locked as badly as the Q4 (same meshes, tip / exact at nu = 0.49, 0.499, "
          "0.4999: VEM on quads 0.894, 0.528, 0.284, on Voronoi cells 0.949, 0.703, 0.374; Lame u L2 error "
          "0.0019 -> 0.72). The cause is the D-recipe stabilisation: its weights are the diagonal of the "
          "consistency stiffness, which carries lambda ~ 1/(1 - 2 nu), so the non-polynomial (hourglass) modes "
          "got a volumetric penalty and every element had to be nearly a linear field. The consistency part "
          "alone has one volumetric constraint per element (about 4 dofs per Voronoi cell, 2 per quad), which "
          "does not lock. Now the stabilisation takes lambda capped at 2 mu (`vem_lambda_cap` in "
          "src/element/vem.f90): lambda <= 2 mu holds for every plane-stress material and for plane strain up "
          "to nu = 1/3, so those results are unchanged bit for bit (every reference deck has nu <= 0.33 and "
          "passes unchanged); beyond, the stabilisation stops growing with lambda.",
          "",
          "The FEM families keep their textbook locking (full 2 x 2 Gauss Q4 and CST; CalculiX's CPE4 does "
          "the same). Decision: warn, do not stop (the answer is valid, just far too stiff): "
          "`element_warnings` in src/driver/validate.f90 returns, for every section whose material has "
          "nu > 0.45 on plane-strain FEM elements, one line naming the element set, the material, nu, the "
          "number of FEM quads and triangles and the measured factor for nu's bracket, and recommending "
          "FORMULATION=VEM. The Lame cylinder on the polar triangle mesh is an exception worth knowing: its "
          "exact field is nearly divergence-free and the criss-cross-free split does not lock there "
          "(u error 0.0065 -> 0.0125), which is why the factor quoted is the cantilever's.", ""]
    # ---- distortion
    L += ["## 2. Distortion and non-convex cells", "",
          "### Example 1 (two quads, shared side from (L/2 - d, 0) to (L/2 + d, b)), nu = 0", "",
          "With L/b = 5 both quads are trapezoids and stay convex for every 2d/b < 5 (the largest angle "
          "only tends to 168.7 deg); at 2d/b = 5 node 2 reaches node 1 and node 5 node 4, beyond that the "
          "shared side crosses the end sides. Eigenvalue ratio: smallest non-zero over largest eigenvalue of "
          "the element stiffness (worst element).", "",
          "| 2d/b | shapes (largest angle) | VEM tip / exact | FEM tip / exact | VEM eig ratio | FEM eig ratio | "
          "message |", "|---:|---|---:|---:|---:|---:|---|"]
    for r in dist:
        if r["mesh"] != "example1":
            continue
        L.append(f"| {r['param']} | {r['shapes']} | {_f(r['vem_tip_ratio'], '{:.4f}')} | "
                 f"{_f(r['fem_tip_ratio'], '{:.4f}')} | {_f(r['vem_eig_ratio_min'])} | "
                 f"{_f(r['fem_eig_ratio_min'])} | {_msg(r['vem_message'])} |")
    L += ["", "### A node dragged into its neighbour (2 x 2 quads, centre node to the top-left corner)", "",
          "P = (L/2 (1-t), b/2 (1+t)): the upper-left quad turns non-convex at t = 0.5, its area vanishes and P "
          "meets corner node 7 at t = 1 (the lower-left quad then has a hanging node, which is fine); beyond, "
          "the mesh tangles.", "",
          "| t | shapes (largest angle) | VEM tip / exact | FEM tip / exact | VEM eig ratio | VEM rcond | "
          "FEM rcond | VEM message | FEM message |", "|---:|---|---:|---:|---:|---:|---:|---|---|"]
    for r in dist:
        if r["mesh"] != "drag":
            continue
        L.append(f"| {r['param']} | {r['shapes']} | {_f(r['vem_tip_ratio'], '{:.4f}')} | "
                 f"{_f(r['fem_tip_ratio'], '{:.4f}')} | {_f(r['vem_eig_ratio_min'])} | {_f(r.get('vem_rcond'))} | "
                 f"{_f(r.get('fem_rcond'))} | {_msg(r['vem_message'], 90)} | {_msg(r['fem_message'], 90)} |")
    L += ["",
          "The VEM answers throughout the non-convex range; the element's eigenvalue ratio falls like (1-t)^4 "
          "and the system's rcond like (1-t)^3 because the cell's area goes to zero, not because it is "
          "non-convex (the same cell shapes at finite area, below, are fine). The solver's rcond guard "
          "(warning below 1e-9, stop below 1e-12, src/driver/linear.f90) covers the last stretch; an area "
          "below 1e-12 h^2 is 'zero area', coincident nodes are 'pinched'. The FEM quad passes the patch test "
          "while its Gauss points see a positive Jacobian (t = 0.6), but its map folds near the reflex corner: "
          "the code now warns there and stops, naming the angle and node, once a Gauss point folds "
          "(t >= 0.7), instead of the old 'Jacobian is not positive' from the assembly.", "",
          "### Strongly non-convex single cells (VEM, single-element patch test through the executable)", "",
          "Consistent nodal forces of a constant stress on every node, the exact linear displacement on 3 "
          "dofs; patch error = max nodal error / max displacement.", "",
          "| cell | vertices | largest angle | patch error | eig ratio | rcond |", "|---|---:|---|---:|---:|---:|"]
    for r in dist:
        if r["mesh"] != "shape":
            continue
        L.append(f"| {r['param']} | {r['vertices']} | {r['shapes']} | {_f(r['vem_patch'], '{:.1e}')} | "
                 f"{_f(r['vem_eig_ratio_min'])} | {_f(r['rcond'])} |")
    L += ["",
          "The projector needs no star-shapedness: grad(Pi u) = (1/|E|) sum u_i (x) q_i is the exact boundary "
          "integral of u n for any simple polygon, and the D-recipe stabilisation only uses the vertex "
          "positions. What degrades stability is thinness (thin L, comb with narrow teeth, star with a small "
          "inner radius: eigenvalue ratio ~1e-4, still well conditioned), not reflex angles (the slit at "
          "359.99 deg has the ratio of a plain square with a notch, 0.02).", ""]
    # ---- short
    L += ["## 3. Short sides and near-duplicate vertices (VEM)", "",
          "A regular hexagon (diameter 2) whose right side is shrunk to 2 eps; the same hexagon with a 7th "
          "vertex on a side at 2 eps from a corner; 19 hexagonal Voronoi cells where the centre cell's side is "
          "shrunk by moving its two ends, so that four cells nearly meet in a point (patch test on the whole "
          "patch, rcond of the assembled problem).", "",
          "| case | eps (side / diameter) | exit | patch error | eig ratio | rcond | message |",
          "|---|---:|---:|---:|---:|---:|---|"]
    for r in short:
        L.append(f"| {r['kind']} | {r['eps']:g} | {r['rc']} | {_f(r['patch'], '{:.1e}')} | {_f(r['eig_ratio'])} | "
                 f"{_f(r['rcond'])} | {_msg(r['message'], 110)} |")
    L += ["",
          "Nothing degrades down to the acceptance limit: the boundary weights q_i are chords of the "
          "neighbours, so a short side enters K only through sums that stay finite, and the stabilisation's "
          "floor (vem_floor) keeps the two ends of a tiny side held. The only breakdown is the definition: at "
          "eps = 0 the side has no normal.", "",
          "Decision: reject sides of at most 1e-10 of the element's diameter (geom_rtol, unchanged) with "
          "'element N has a zero-length side: its nodes A and B coincide (distance 2.00E-11 for a "
          "diameter of 2.00, below 1.00E-10 of it); a side of no length has no normal, merge the two nodes', and non-adjacent "
          "coincident vertices as 'pinched'. Accepting them would be exact for the element itself (a "
          "zero-length side contributes nothing to the boundary integrals), but the two nodes stay distinct "
          "dofs at one point, a surface or contact segment on such a side has no normal, a pressure on it "
          "vanishes silently, and the right fix is the mesher's (merge the nodes: issue 4 notes that short "
          "edges are not collapsed yet). Sides from 1e-10 up are accepted and answer to round-off.", "",
          "## Recommendations", "",
          "- Nearly incompressible plane strain: use the VEM (FORMULATION=VEM; works on quad and triangle "
          "meshes too). The FEM sections get a warning at the start of the run.",
          "- FEM quads must be convex; non-convex quads run with the VEM.",
          "- Mesh generation: collapse sides shorter than ~1e-8 of the cell diameter (well above the 1e-10 "
          "rejection) to avoid the stop.",
          "- Slivers (area -> 0) are the real stability hazard, not non-convexity: the rcond guard catches "
          "them; a mesh quality report of area / diameter^2 would name them earlier.", ""]
    with open(path, "w") as f:
        f.write("\n".join(L))
    print("wrote", path)


def main(argv=None):
    global EXE
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", default=EXE)
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "stability_elements"))
    ap.add_argument("--only", default="nu,distortion,short", help="comma list of nu, distortion, short")
    ap.add_argument("--no-doc", action="store_true")
    args = ap.parse_args(argv)
    work = os.path.abspath(args.work)
    os.makedirs(os.path.join(work, "bin"), exist_ok=True)
    EXE = os.path.join(work, "bin", "vemcontact")
    shutil.copy2(args.exe, EXE)                 # others may rebuild build/ meanwhile
    res = os.path.join(ROOT, "bench", "results")
    only = args.only.split(",")
    out = {}
    if "nu" in only:
        print("== nu sweep (plane strain)", flush=True)
        out["nu"] = sweep_nu(work)
        write_csv(os.path.join(res, "stability_nu.csv"), out["nu"])
    if "distortion" in only:
        print("== distortion", flush=True)
        out["distortion"] = sweep_distortion(work) + sweep_shapes(work)
        write_csv(os.path.join(res, "stability_distortion.csv"), out["distortion"])
    if "short" in only:
        print("== short edges", flush=True)
        out["short"] = sweep_short_edges(work)
        write_csv(os.path.join(res, "stability_short_edges.csv"), out["short"])
    if not args.no_doc and len(out) == 3:
        write_doc(out, machine(), os.path.join(ROOT, "docs", "stability-elements.md"))


if __name__ == "__main__":
    main()
