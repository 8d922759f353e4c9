"""The VEM stabilisation factor tau (*SOLID SECTION, STABILIZATION=tau): what it does.

One command (Release build, about a minute):

    PYTHONPATH=postprocess .venv/bin/python bench/vem_tau.py [--exe build/vemcontact] [--work out/vem_tau]

For tau in TAUS it measures, through the executable:
  1. paper example 1 (two-element cantilever under an end moment, L = 40, b = 8,
     E = 1000, nu = 0, plane strain): mean tip u_y over the exact M L^2/(2 E I) = 0.3
     against the distortion 2d/b = 0 .. 4.9, beside the bilinear quad (FEM) on the
     same two quads;
  2. convergence on Voronoi meshes (3 sizes) of the manufactured quadratic solution and
     of the Timoshenko cantilever with parabolic end shear (bench/accuracy/cases.py
     builds the meshes and decks): relative energy and L2 errors, their rate and constant;
  3. the Hertz 1155-element VEM deck (inputs/hertz_1155_vem.inp): peak contact pressure
     against the analytic 83.60;
and without it (numpy re-implementation of src/element/vem.f90, checked against the
executable on example 1 to 1e-12):
  4. the smallest non-zero over the largest eigenvalue of single-element matrices of a
     few shapes, VEM for each tau and the Q4 where it applies.

Writes bench/results/vem_tau.csv (long format: study, case, tau, x, quantity, value),
docs/figures/vem_tau.png, docs/figures/vem_tau_ex1.png and the tables of
docs/vem-stabilisation.md between its 'tables' markers (the prose stays).
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

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "accuracy"))
import cases   # noqa: E402
import fields  # noqa: E402

TAUS = [1 / 16, 1 / 8, 1 / 4, 1 / 2, 3 / 4, 1.0, 2.0, 4.0]
TAU_LABEL = {1 / 16: "1/16", 1 / 8: "1/8", 1 / 4: "1/4", 1 / 2: "1/2", 3 / 4: "3/4", 1.0: "1", 2.0: "2", 4.0: "4",
             4 / 3: "4/3"}
DISTORTIONS = [round(0.1 * k, 1) for k in range(50)]          # 2d/b = 0 .. 4.9
EX1 = dict(L=40.0, b=8.0, E=1000.0, nu=0.0, M=16.0)
EX1_EXACT = EX1["M"] * EX1["L"] ** 2 / (2 * EX1["E"] * EX1["b"] ** 3 / 12)     # 0.3
HERTZ_P0 = 83.60
MARK_BEGIN, MARK_END = "<!-- tables:begin (bench/vem_tau.py) -->", "<!-- tables:end -->"


# ---------------------------------------------------------------- running decks
def run(exe, deck_path, outdir):
    r = subprocess.run([exe, "-q", "-o", outdir, deck_path], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"vemcontact failed ({r.returncode}) on {deck_path}:\n{r.stdout}{r.stderr}")
    return os.path.join(outdir, os.path.splitext(os.path.basename(deck_path))[0] + ".h5")


def with_tau(deck, tau):
    """The deck with STABILIZATION=tau on every *SOLID SECTION line (VEM sections only)."""
    if tau is None:
        return deck
    return re.sub(r"(?im)^(\*SOLID SECTION,[^\n]*)$", lambda m: m.group(1) + f", STABILIZATION={float(tau)!r}", deck)


# ---------------------------------------------------------------- 1. example 1
def ex1_deck(two_d_over_b, formulation, tau):
    """inputs/example1_cantilever.inp with the shared edge from (L/2 - d, 0) to (L/2 + d, b)."""
    L, b = EX1["L"], EX1["b"]
    d = two_d_over_b * b / 2
    f = EX1["M"] / b
    s = f"""** bench/vem_tau.py: paper example 1, 2d/b = {two_d_over_b}
*NODE
1, 0.0, 0.0
2, {float(L / 2 - d)!r}, 0.0
3, {float(L)!r}, 0.0
4, {float(L)!r}, {float(b)!r}
5, {float(L / 2 + d)!r}, {float(b)!r}
6, 0.0, {float(b)!r}
*ELEMENT, TYPE=VPE, ELSET=BEAM
1, 1, 2, 5, 6
2, 2, 3, 4, 5
*MATERIAL, NAME=UNIT
*ELASTIC
{float(EX1['E'])!r}, {float(EX1['nu'])!r}
*SOLID SECTION, ELSET=BEAM, MATERIAL=UNIT, FORMULATION={formulation}
1.0
*BOUNDARY
1, 1, 2
6, 1
*STEP
*STATIC
*CLOAD
3, 1, {float(f)!r}
4, 1, {float(-f)!r}
*END STEP
"""
    return with_tau(s, tau)


def tip_ratio(h5):
    with h5py.File(h5, "r") as f:
        x = f["mesh/coordinates"][...]
        step = f["steps"][sorted(f["steps"])[0]]
        u = step["U"][...]
    tip = np.abs(x[:, 0] - EX1["L"]) < 1e-9
    return float(u[tip, 1].mean() / EX1_EXACT)


def study_ex1(exe, work, rows):
    os.makedirs(os.path.join(work, "ex1"), exist_ok=True)
    res = {}
    for tau in [None] + TAUS:
        for r in DISTORTIONS:
            form = "FEM" if tau is None else "VEM"
            job = f"ex1_{form}_{'q4' if tau is None else f'{tau:.4f}'}_{r:.1f}".replace(".", "p")
            path = os.path.join(work, "ex1", job + ".inp")
            with open(path, "w") as fh:
                fh.write(ex1_deck(r, form, tau))
            v = tip_ratio(run(exe, path, os.path.join(work, "ex1", "out")))
            res[(tau, r)] = v
            rows.append(dict(study="ex1", case="FEM Q4" if tau is None else "VEM", tau="" if tau is None else tau,
                             x=r, quantity="tip_ratio", value=v))
    return res


def paper_statements(vem, fem):
    """The paper's four statements on its Fig. 4 for one VEM curve (dict 2d/b -> ratio) against
    the Q4's: (i) FEM better at 2d/b = 0, (ii) FEM loses more (relative, 0 -> 4), (iii) the
    curves meet near 2d/b = 1 (first crossing in 0.5..1.5), (iv) VEM better beyond it."""
    cross = next((r for r in DISTORTIONS if vem[r] > fem[r]), None)
    i_ = vem[0.0] < fem[0.0]
    ii = 1 - fem[4.0] / fem[0.0] > 1 - vem[4.0] / vem[0.0]
    iii = cross is not None and 0.5 <= cross <= 1.5
    iv = cross is not None and all(vem[r] > fem[r] for r in DISTORTIONS if r >= cross)
    return cross, (i_, ii, iii, iv)


SCAN_TAUS = [round(1.0 + 0.1 * k, 1) for k in range(11)] + [4 / 3]


def study_paper_scan(exe, work, ex1, rows):
    """tau from 1 to 2 (and 4/3): where does the VEM curve meet the Q4's?"""
    fem = {r: ex1[(None, r)] for r in DISTORTIONS}
    res = {}
    for tau in sorted(set(SCAN_TAUS)):
        vem = {}
        for r in DISTORTIONS:
            if (tau, r) in ex1:
                vem[r] = ex1[(tau, r)]
                continue
            path = os.path.join(work, "ex1", f"scan_{tau:.4f}_{r:.1f}".replace(".", "p") + ".inp")
            with open(path, "w") as fh:
                fh.write(ex1_deck(r, "VEM", tau))
            vem[r] = tip_ratio(run(exe, path, os.path.join(work, "ex1", "out")))
        cross, st = paper_statements(vem, fem)
        res[tau] = (vem, cross, st)
        rows.append(dict(study="ex1_scan", case="VEM", tau=tau, x="", quantity="first_2db_vem_above_fem",
                         value=float("nan") if cross is None else cross))
        for r in DISTORTIONS:
            rows.append(dict(study="ex1_scan", case="VEM", tau=tau, x=r, quantity="tip_ratio", value=vem[r]))
    return res


# ---------------------------------------------------------------- 2. convergence
def study_convergence(exe, work, rows):
    sel = {"manufactured": (cases.manufactured, [8, 16, 32]), "timoshenko": (cases.timoshenko, [4, 8, 16])}
    for sub in ("decks", "out", "meshes"):
        os.makedirs(os.path.join(work, sub), exist_ok=True)
    res = {}
    for cname, (gen, levels) in sel.items():
        for runobj in gen(work):
            if runobj.family != "vem-voronoi" or runobj.level > max(levels):
                break                                     # Voronoi family first, levels ascending
            if runobj.level not in levels:
                continue
            for tau in TAUS:
                job = f"{cname}_{runobj.level}_{tau:.4f}".replace(".", "p")
                path = os.path.join(work, "decks", job + ".inp")
                with open(path, "w") as fh:
                    fh.write(with_tau(runobj.deck, tau))
                res_h5 = fields.read_result(run(exe, path, os.path.join(work, "out", job)))
                met = runobj.metrics(res_h5)
                qs = ["energy", "u_l2"]
                if cname == "timoshenko":
                    # signed: the tip deflection on the axis over the exact one, minus 1
                    case, x = fields.Timoshenko(), res_h5["x"]
                    on = np.abs(x[:, 0] - case.L) < 1e-9 * case.L
                    o = np.argsort(x[on, 1])
                    met["tip_error"] = float(np.interp(0.0, x[on, 1][o], res_h5["U"][on, 1][o]) / case.tip() - 1)
                    qs.append("tip_error")
                h = 1.0 / math.sqrt(runobj.elements)      # relative cell size
                for q in qs:
                    res[(cname, q, tau, runobj.elements)] = met[q]
                    rows.append(dict(study="convergence", case=cname, tau=tau, x=runobj.elements,
                                     quantity=q, value=met[q]))
                print(f"  {cname:12s} {runobj.elements:5d} cells tau {tau:6.4f}: energy {met['energy']:.4e} "
                      f"u_l2 {met['u_l2']:.4e} (h {h:.3f})", flush=True)
    return res


# ---------------------------------------------------------------- 3. Hertz
def study_hertz(exe, work, rows):
    src = os.path.join(ROOT, "inputs", "hertz_1155_vem.inp")
    deck = open(src).read()
    deck = deck.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    os.makedirs(os.path.join(work, "hertz"), exist_ok=True)
    res = {}
    for tau in TAUS:
        path = os.path.join(work, "hertz", f"hertz_1155_{tau:.4f}".replace(".", "p") + ".inp")
        with open(path, "w") as fh:
            fh.write(with_tau(deck, tau))
        r = fields.read_result(run(exe, path, os.path.join(work, "hertz", "out")))
        p = float(r["contact"]["CPRESS"].max())
        res[tau] = p
        rows.append(dict(study="hertz", case="hertz_1155_vem", tau=tau, x="", quantity="peak_pressure", value=p))
        print(f"  hertz 1155 tau {tau:6.4f}: peak {p:.3f} ({(p - HERTZ_P0) / HERTZ_P0:+.2%})", flush=True)
    return res


# ---------------------------------------------------------------- 4. element matrices (numpy)
def elastic(E, nu, plane):
    if plane == "strain":
        c = E / ((1 + nu) * (1 - 2 * nu))
        return c * np.array([[1 - nu, nu, 0], [nu, 1 - nu, 0], [0, 0, (1 - 2 * nu) / 2]])
    c = E / (1 - nu * nu)
    return c * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])


def vem_k(xy, D, t=1.0, tau=1.0, floor=1e-2, lam_cap=2.0):
    """src/element/vem.f90 in numpy: consistency + tau x D-recipe (lambda capped, floor)."""
    xy = np.asarray(xy, float)
    n = len(xy)
    x, y = xy[:, 0], xy[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    q = 0.5 * np.stack([np.roll(y, -1) - np.roll(y, 1), -(np.roll(x, -1) - np.roll(x, 1))], 1)
    B = np.zeros((3, 2 * n))
    B[0, 0::2], B[1, 1::2], B[2, 0::2], B[2, 1::2] = q[:, 0], q[:, 1], q[:, 1], q[:, 0]
    B /= area
    Kc = area * t * B.T @ D @ B
    w = Kc.diagonal()[0::2] + Kc.diagonal()[1::2]
    tr = Kc.trace()
    excess = D[0, 1] - lam_cap * D[2, 2]
    if excess > 0:
        w = w - t / area * excess * (q ** 2).sum(1)
        tr = w.sum()
    s = tau * np.maximum(0.5 * w, floor * tr / (2 * n))
    xbar = xy.mean(0)
    p = 1.0 / n + (xy - xbar) @ q.T / area        # p[j, i]
    M = np.kron(np.eye(n) - p, np.eye(2))
    return Kc + M.T @ np.diag(np.repeat(s, 2)) @ M


def q4_k(xy, D, t=1.0):
    xy = np.asarray(xy, float)
    K = np.zeros((8, 8))
    g = 1 / math.sqrt(3)
    for xi in (-g, g):
        for eta in (-g, g):
            dN = 0.25 * np.array([[-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)],
                                  [-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]])
            J = dN @ xy
            dNx = np.linalg.solve(J, dN)
            B = np.zeros((3, 8))
            B[0, 0::2], B[1, 1::2], B[2, 0::2], B[2, 1::2] = dNx[0], dNx[1], dNx[1], dNx[0]
            K += t * np.linalg.det(J) * B.T @ D @ B
    return K


def shapes():
    rng = np.random.default_rng(5)
    ang = np.sort(rng.uniform(0, 2 * np.pi, 7))
    hept = np.stack([np.cos(ang), 0.6 * np.sin(ang)], 1)
    star = np.array([(r * math.cos(2 * math.pi * k / 8), r * math.sin(2 * math.pi * k / 8))
                     for k, r in zip(range(8), [1.0, 0.35] * 4)])
    return {
        "unit square": [(0, 0), (1, 0), (1, 1), (0, 1)],
        "ex1 rectangle 20x8": [(0, 0), (20, 0), (20, 8), (0, 8)],
        "ex1 quad 2d/b=4": [(0, 0), (4, 0), (36, 8), (0, 8)],
        "rectangle 10:1": [(0, 0), (10, 0), (10, 1), (0, 1)],
        "regular hexagon": [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3)) for k in range(6)],
        "random convex heptagon": hept.tolist(),
        "star octagon (non-convex)": star.tolist(),
    }


def study_eigen(rows):
    res = {}
    for plane, nu in (("strain", 0.3),):
        D = elastic(1.0, nu, plane)
        for name, xy in shapes().items():
            for tau in TAUS + [None]:
                if tau is None:
                    if len(xy) != 4:
                        continue
                    K = q4_k(xy, D)
                else:
                    K = vem_k(xy, D, tau=tau)
                lam = np.linalg.eigvalsh(K)
                ratio = lam[3] / lam[-1]
                res[(name, tau)] = ratio
                rows.append(dict(study="eigen", case=name, tau="" if tau is None else tau, x="",
                                 quantity="lambda4_over_lambdamax", value=ratio))
    return res


def check_numpy_kernel(exe, work):
    """The numpy kernel reproduces the executable: example 1 solved with it against the run."""
    worst = 0.0
    for tau in (1 / 16, 1.0, 4.0):
        for r in (0.0, 1.0, 4.0):
            L, b = EX1["L"], EX1["b"]
            d = r * b / 2
            X = np.array([(0, 0), (L / 2 - d, 0), (L, 0), (L, b), (L / 2 + d, b), (0, b)])
            K = np.zeros((12, 12))
            D = elastic(EX1["E"], EX1["nu"], "strain")
            for conn in ([0, 1, 4, 5], [1, 2, 3, 4]):
                ke = vem_k(X[conn], D, tau=tau)
                dofs = np.ravel([[2 * c, 2 * c + 1] for c in conn])
                K[np.ix_(dofs, dofs)] += ke
            f = np.zeros(12)
            f[4], f[6] = EX1["M"] / b, -EX1["M"] / b
            free = [k for k in range(12) if k not in (0, 1, 10)]
            u = np.zeros(12)
            u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
            mine = (u[5] + u[7]) / 2 / EX1_EXACT
            path = os.path.join(work, "ex1", f"check_{tau:.4f}_{r}".replace(".", "p") + ".inp")
            with open(path, "w") as fh:
                fh.write(ex1_deck(r, "VEM", tau))
            theirs = tip_ratio(run(exe, path, os.path.join(work, "ex1", "out")))
            worst = max(worst, abs(mine - theirs) / abs(theirs))
    if worst > 1e-10:
        raise RuntimeError(f"the numpy VEM kernel differs from the executable by {worst:.2e}")
    return worst


# ---------------------------------------------------------------- report
def rate_fit(cells, errs):
    """Least-squares err = C h^p with h = 1/sqrt(cells): (p, C)."""
    h = 1 / np.sqrt(np.asarray(cells, float))
    p, lc = np.polyfit(np.log(h), np.log(errs), 1)
    return p, math.exp(lc)


def tables(ex1, scan, conv, hertz, eig, kernel_check):
    tl = lambda t: TAU_LABEL.get(t, f"{t:g}")   # noqa: E731
    out = []
    # example 1
    show = [0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 4.5, 4.9]
    out.append("### Example 1: tip deflection / exact (0.3) against 2d/b\n")
    out.append("| tau | " + " | ".join(f"{r:g}" for r in show) + " | loss 0 -> 4 |")
    out.append("|---|" + "---:|" * (len(show) + 1))
    for tau in TAUS + [None]:
        name = "FEM Q4" if tau is None else f"VEM tau = {tl(tau)}"
        vals = [ex1[(tau, r)] for r in show]
        loss = 1 - ex1[(tau, 4.0)] / ex1[(tau, 0.0)]
        out.append(f"| {name} | " + " | ".join(f"{v:.4f}" for v in vals) + f" | {loss:.1%} |")
    out.append("")
    out.append("Crossing with the Q4 (the smallest 2d/b where VEM > FEM, 0.1 steps) and the paper's four "
               "statements: (i) FEM better than VEM at 2d/b = 0, (ii) FEM falls faster, "
               "(iii) equal near 2d/b = 1, (iv) VEM better beyond.\n")
    out.append("| tau | VEM - FEM at 0 | VEM/FEM at 1 | first 2d/b with VEM > FEM | VEM/FEM at 4 | (i) | (ii) | (iii) | (iv) |")
    out.append("|---|---:|---:|---:|---:|:-:|:-:|:-:|:-:|")
    yn = lambda b: "yes" if b else "no"   # noqa: E731
    fem = {r: ex1[(None, r)] for r in DISTORTIONS}
    for tau in sorted(set(TAUS) | set(scan)):
        vem = scan[tau][0] if tau in scan else {r: ex1[(tau, r)] for r in DISTORTIONS}
        cross, (i_, ii, iii, iv) = paper_statements(vem, fem)
        out.append(f"| {tl(tau)} | {vem[0.0] - fem[0.0]:+.4f} | {vem[1.0] / fem[1.0]:.3f} | "
                   f"{'-' if cross is None else f'{cross:g}'} | {vem[4.0] / fem[4.0]:.3f} | "
                   f"{yn(i_)} | {yn(ii)} | {yn(iii)} | {yn(iv)} |")
    out.append("")
    # convergence
    for cname, title in (("manufactured", "Manufactured quadratic solution (unit square, plane strain)"),
                         ("timoshenko", "Timoshenko cantilever, parabolic end shear (48 x 12, plane stress)")):
        cells = sorted({k[3] for k in conv if k[0] == cname})
        out.append(f"### {title}, Voronoi cells {', '.join(map(str, cells))}\n")
        out.append("| tau | " + " | ".join(f"energy {c}" for c in cells) + " | energy rate | "
                   + " | ".join(f"L2 {c}" for c in cells) + " | L2 rate | energy / tau=1 | L2 / tau=1 |")
        out.append("|---|" + "---:|" * (2 * len(cells) + 4))
        for tau in TAUS:
            e = [conv[(cname, "energy", tau, c)] for c in cells]
            l2 = [conv[(cname, "u_l2", tau, c)] for c in cells]
            pe, _ = rate_fit(cells, e)
            pl, _ = rate_fit(cells, l2)
            e1 = conv[(cname, "energy", 1.0, cells[-1])]
            l1 = conv[(cname, "u_l2", 1.0, cells[-1])]
            out.append(f"| {tl(tau)} | " + " | ".join(f"{v:.3e}" for v in e) + f" | {pe:.2f} | "
                       + " | ".join(f"{v:.3e}" for v in l2) + f" | {pl:.2f} | {e[-1] / e1:.3f} | {l2[-1] / l1:.3f} |")
        out.append("")
        out.append("(rates: least-squares slope of log error against log h, h = cells^-1/2; the ratios are on "
                   "the finest mesh)\n")
        if cname == "timoshenko":
            out.append("Signed tip deflection error (on the axis, against the exact tip deflection):\n")
            out.append("| tau | " + " | ".join(f"{c} cells" for c in cells) + " |")
            out.append("|---|" + "---:|" * len(cells))
            for tau in TAUS:
                out.append(f"| {tl(tau)} | " + " | ".join(f"{conv[(cname, 'tip_error', tau, c)]:+.3e}" for c in cells)
                           + " |")
            out.append("")
    # eigen
    names = list(dict.fromkeys(k[0] for k in eig))
    out.append("### Smallest non-zero / largest eigenvalue of one element (E = 1, nu = 0.3, plane strain)\n")
    out.append("| shape | " + " | ".join(f"tau {tl(t)}" for t in TAUS) + " | Q4 |")
    out.append("|---|" + "---:|" * (len(TAUS) + 1))
    for nm in names:
        q = eig.get((nm, None))
        out.append(f"| {nm} | " + " | ".join(f"{eig[(nm, t)]:.2e}" for t in TAUS) + f" | {'-' if q is None else f'{q:.2e}'} |")
    out.append("")
    out.append(f"(numpy kernel of bench/vem_tau.py; it reproduces the executable's example-1 deflections to "
               f"{kernel_check:.1e} relative)\n")
    # hertz
    out.append("### Hertz, 1155 elements, VEM, K = 1e5: peak contact pressure (analytic 83.60)\n")
    out.append("| tau | " + " | ".join(tl(t) for t in TAUS) + " |")
    out.append("|---|" + "---:|" * len(TAUS))
    out.append("| peak | " + " | ".join(f"{hertz[t]:.2f}" for t in TAUS) + " |")
    out.append("| error | " + " | ".join(f"{(hertz[t] - HERTZ_P0) / HERTZ_P0:+.2%}" for t in TAUS) + " |")
    out.append("")
    return "\n".join(out)


def figures(ex1, scan, conv, hertz, eig, figdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cmap = plt.get_cmap("viridis")
    col = {t: cmap(k / (len(TAUS) - 1)) for k, t in enumerate(TAUS)}
    tl = lambda t: TAU_LABEL.get(t, f"{t:g}")   # noqa: E731
    # example 1 alone
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for tau in TAUS:
        ax.plot(DISTORTIONS, [ex1[(tau, r)] for r in DISTORTIONS], color=col[tau], lw=2 if tau == 1.0 else 1.2,
                label=f"VEM tau={tl(tau)}")
    ax.plot(DISTORTIONS, [ex1[(None, r)] for r in DISTORTIONS], "k--", lw=2, label="FEM Q4")
    if scan is not None and 1.1 in scan:
        ax.plot(DISTORTIONS, [scan[1.1][0][r] for r in DISTORTIONS], color="tab:red", ls=":", lw=2,
                label="VEM tau=1.1 (the paper's text)")
    ax.set_xlabel("distortion 2d/b")
    ax.set_ylabel("tip deflection / exact")
    ax.set_yscale("log")
    ax.set_title("Example 1: two-element cantilever, end moment")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "vem_tau_ex1.png"), dpi=110)
    plt.close(fig)
    # overview
    fig, axs = plt.subplots(2, 2, figsize=(11, 8))
    ax = axs[0, 0]
    for tau in TAUS:
        ax.plot(DISTORTIONS, [ex1[(tau, r)] / ex1[(tau, 0.0)] for r in DISTORTIONS], color=col[tau],
                label=f"tau={tl(tau)}")
    ax.plot(DISTORTIONS, [ex1[(None, r)] / ex1[(None, 0.0)] for r in DISTORTIONS], "k--", lw=2, label="Q4")
    ax.set_xlabel("2d/b")
    ax.set_ylabel("tip deflection / its value at 2d/b = 0")
    ax.set_title("Example 1: sensitivity to distortion")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax = axs[0, 1]
    for cname, mk in (("manufactured", "o-"), ("timoshenko", "s--")):
        cells = sorted({k[3] for k in conv if k[0] == cname})
        ax.plot(TAUS, [conv[(cname, "energy", t, cells[-1])] for t in TAUS], mk, label=f"{cname} energy, {cells[-1]} cells")
        ax.plot(TAUS, [conv[(cname, "u_l2", t, cells[-1])] for t in TAUS], mk, mfc="none",
                label=f"{cname} L2, {cells[-1]} cells")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("tau")
    ax.set_ylabel("relative error")
    ax.set_title("Voronoi meshes: error against tau (finest mesh)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax = axs[1, 0]
    names = list(dict.fromkeys(k[0] for k in eig))
    for nm in names:
        ax.plot(TAUS, [eig[(nm, t)] for t in TAUS], "o-", ms=3, label=nm)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("tau")
    ax.set_ylabel("lambda_4 / lambda_max")
    ax.set_title("One element: smallest non-zero / largest eigenvalue")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax = axs[1, 1]
    ax.plot(TAUS, [hertz[t] for t in TAUS], "o-", label="VEM, 1155 elements")
    ax.axhline(HERTZ_P0, color="k", ls="--", label="Hertz 83.60")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("tau")
    ax.set_ylabel("peak contact pressure")
    ax.set_title("Hertz (inputs/hertz_1155_vem.inp)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "vem_tau.png"), dpi=110)
    plt.close(fig)


def write_doc(text, doc):
    if not os.path.exists(doc):
        body = f"# VEM stabilisation factor tau\n\n{MARK_BEGIN}\n{MARK_END}\n"
    else:
        body = open(doc).read()
    i, j = body.find(MARK_BEGIN), body.find(MARK_END)
    if i < 0 or j < 0:
        body += f"\n{MARK_BEGIN}\n{MARK_END}\n"
        i, j = body.find(MARK_BEGIN), body.find(MARK_END)
    body = body[:i] + MARK_BEGIN + "\n\n" + text + "\n" + body[j:]
    with open(doc, "w") as fh:
        fh.write(body)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.environ.get("VEMCONTACT_EXE", os.path.join(ROOT, "build", "vemcontact")))
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "vem_tau"))
    args = ap.parse_args(argv)
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)
    # a private copy: others may rebuild the executable during the sweep
    exe = os.path.join(work, "vemcontact")
    shutil.copy2(args.exe, exe)
    rows = []
    print("== example 1", flush=True)
    ex1 = study_ex1(exe, work, rows)
    scan = study_paper_scan(exe, work, ex1, rows)
    kcheck = check_numpy_kernel(exe, work)
    print(f"   numpy kernel = executable to {kcheck:.1e}", flush=True)
    print("== convergence on Voronoi meshes", flush=True)
    conv = study_convergence(exe, work, rows)
    print("== Hertz", flush=True)
    hertz = study_hertz(exe, work, rows)
    print("== element eigenvalues", flush=True)
    eig = study_eigen(rows)
    os.makedirs(os.path.join(ROOT, "bench", "results"), exist_ok=True)
    with open(os.path.join(ROOT, "bench", "results", "vem_tau.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, ["study", "case", "tau", "x", "quantity", "value"])
        w.writeheader()
        for r in rows:
            r = dict(r)
            if isinstance(r["value"], float):
                r["value"] = f"{r['value']:.10g}"
            w.writerow(r)
    figures(ex1, scan, conv, hertz, eig, os.path.join(ROOT, "docs", "figures"))
    text = tables(ex1, scan, conv, hertz, eig, kcheck)
    write_doc(text, os.path.join(ROOT, "docs", "vem-stabilisation.md"))
    print(text)


if __name__ == "__main__":
    main()
