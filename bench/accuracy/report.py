"""Tables, Pareto figures and the document docs/accuracy-vs-speed.md from the rows of
main.py (one row per case, family and mesh level)."""
from __future__ import annotations

import math
import os
import sys

import numpy as np

import meshes

ROOT = meshes.ROOT
ROUNDOFF = 1e-9       # errors below this are round-off: the exact answer is in the discrete space (the
                      # smallest discretization error of the study is 6e-6; S2S interface pressures reach 3e-10)


def _ok(v):
    return math.isfinite(v) and v > ROUNDOFF
BASE_LABEL = {"vem-voronoi": "VEM, Voronoi", "vem-quad": "VEM, quads", "fem-quad": "FEM quads (Q4)",
              "fem-tri": "FEM triangles (T3)", "vem2-voronoi": "VEM k = 2, Voronoi", "vem2-quad": "VEM k = 2, quads",
              "fem-q8": "FEM quads (Q8)", "fem-t6": "FEM triangles (T6)"}
BASE_STYLE = {"vem-voronoi": ("tab:green", "o"), "vem-quad": ("tab:blue", "s"), "fem-quad": ("tab:orange", "D"),
              "fem-tri": ("tab:red", "^"), "vem2-voronoi": ("darkgreen", "o"), "vem2-quad": ("navy", "s"),
              "fem-q8": ("saddlebrown", "D"), "fem-t6": ("darkred", "^")}
SECOND_ORDER = ("vem2-voronoi", "vem2-quad", "fem-q8", "fem-t6")      # drawn dashed, open markers
CONTACT_CASES = ("hertz", "interface")
# contact formulations (cases.CONTACT_VARIANTS): label and line style
VARIANT_LABEL = {"": "NTS penalty", "nts-hard": "NTS HARD", "s2s-hard": "S2S HARD"}
VARIANT_LINE = {"": "-", "nts-hard": "--", "s2s-hard": ":"}
MAX_ITERATIONS = 10     # the robustness target: iterations per increment


def _split(fam):
    base, _, var = fam.partition("+")
    return base, var


class _Labels(dict):
    """FAMILY_LABEL[fam]: 'VEM, quads' for the linear cases' families, 'VEM, quads, S2S HARD'
    for a contact formulation; the plain family of a contact case is labelled by flabel."""
    def __missing__(self, fam):
        base, var = _split(fam)
        return BASE_LABEL[base] + (f", {VARIANT_LABEL[var]}" if var else "")


FAMILY_LABEL = _Labels()


def flabel(fam, case=None):
    base, var = _split(fam)
    if case in CONTACT_CASES:
        return f"{BASE_LABEL[base]}, {VARIANT_LABEL[var]}"
    return FAMILY_LABEL[fam]


def style(fam):
    base, var = _split(fam)
    return BASE_STYLE[base] + ("--" if base in SECOND_ORDER and not var else VARIANT_LINE[var],)

# per case: primary metric, other metrics, their labels
METRICS = {
    "manufactured": ("energy", ["u_l2"]),
    "timoshenko": ("tip", ["energy", "u_l2"]),
    "lame": ("u_l2", ["energy", "hoop"]),
    "hertz": ("peak", ["halfwidth"]),
    "interface": ("pressure", ["pressure_rms", "resultant", "stress"]),
}
LABEL = {
    "energy": "energy-norm error of the stress (k = 1: element, k = 2: nodal)",
    "u_l2": "nodal displacement error (discrete L2)",
    "tip": "tip deflection error",
    "hoop": "hoop stress error at the bore (nodal stress)",
    "peak": "peak contact pressure error vs 83.60",
    "halfwidth": "contact half-width error vs 1.523 (fit)",
    "pressure": "contact pressure error (max over slave nodes)",
    "pressure_rms": "contact pressure error (RMS over slave nodes)",
    "stress": "sigma_yy error (max over elements)",
    "resultant": "resultant contact force error",
}
SHORT = {"energy": "energy", "u_l2": "u (L2)", "tip": "tip defl.", "hoop": "hoop at bore", "peak": "peak p",
         "halfwidth": "half-width", "pressure": "p max", "pressure_rms": "p RMS", "stress": "s_yy max",
         "resultant": "resultant"}
RATE_EXPECTED = {"energy": "1, k = 2: 2", "u_l2": "2, k = 2: 3", "tip": "2, k = 2: 3-4", "hoop": "1", "peak": "-",
                 "halfwidth": "-", "pressure": "-", "pressure_rms": "-", "stress": "-",
                 "resultant": "-"}


def _families(rows):
    seen = []
    for r in rows:
        if r["family"] not in seen:
            seen.append(r["family"])
    return seen


def rate(rs, metric, last=3):
    """Observed rate in h: -2 d log(err) / d log(unknowns), least squares over the
    finest `last` levels (unknowns ~ h^-2)."""
    pts = [(r["unknowns"], r[metric]) for r in rs if _ok(r[metric])][-last:]
    if len(pts) < 2:
        return float("nan")
    n, e = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return -2 * np.polyfit(n, e, 1)[0]


def pareto(points):
    """Non-dominated (time, error) points, sorted by time."""
    pts = sorted(points)
    front, best = [], float("inf")
    for t, e in pts:
        if e < best:
            front.append((t, e))
            best = e
    return front


def figure(case, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    prim, others = METRICS[case]
    mets = [prim] + others[:1]
    big = case in CONTACT_CASES
    fig, axs = plt.subplots(len(mets), 2, figsize=(12 if big else 10, (4.6 if big else 3.6) * len(mets)),
                            squeeze=False)
    for i, m in enumerate(mets):
        for fam in _families(rows):
            rs = [r for r in rows if r["family"] == fam and _ok(r[m])]
            ro = [r for r in rows if r["family"] == fam and math.isfinite(r[m]) and not _ok(r[m])]
            if ro and case in CONTACT_CASES:
                # exact to round-off (S2S on the interface): drawn at the round-off line
                c, mk, ls = style(fam)
                for j, key in enumerate(("unknowns", "time_s")):
                    axs[i, j].loglog([r[key] for r in ro], [ROUNDOFF] * len(ro), marker=mk, color=c, ls=ls, ms=5,
                                     mfc="none", label=f"{flabel(fam, case)}: round-off, drawn at {ROUNDOFF:.0e}")
            if not rs:
                continue
            c, mk, ls = style(fam)
            lab = f"{flabel(fam, case)} (rate {rate(rs, m):.2f})"
            axs[i, 0].loglog([r["unknowns"] for r in rs], [r[m] for r in rs], marker=mk, color=c, ls=ls, label=lab,
                             ms=4)
            axs[i, 1].loglog([r["time_s"] for r in rs], [r[m] for r in rs], marker=mk, color=c, ls=ls,
                             label=flabel(fam, case), ms=4)
        front = pareto([(r["time_s"], r[m]) for r in rows if _ok(r[m])])
        if front:
            t, e = zip(*front)
            axs[i, 1].step(t, e, where="post", color="0.4", lw=3, alpha=0.35, label="Pareto front")
        for ax in axs[i]:
            for lvl in (1e-2, 1e-3):
                ax.axhline(lvl, color="0.6", ls=":", lw=0.8)
            ax.grid(True, which="major", alpha=0.3)
            ax.set_ylabel(LABEL[m], fontsize=8)
        axs[i, 0].set_xlabel("unknowns (2 x nodes)")
        axs[i, 1].set_xlabel("wall time [s] (median of the runs, vemcontact 'total')")
        axs[i, 0].legend(fontsize=7)
        axs[i, 1].legend(fontsize=7)
    fig.suptitle(f"{case}: error against unknowns and against time (dotted: 1 % and 0.1 %)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def _pct(v):
    if not math.isfinite(v):
        return "n/a"
    return f"{100 * v:.3g} %" if v > ROUNDOFF else "round-off"


def _fmt_int(n):
    return f"{int(n):,}".replace(",", " ")


def table(case, rows):
    prim, others = METRICS[case]
    mets = [prim] + others
    head = ["family", "level", "mesh", "unknowns", "time [s]"] + [SHORT[m] for m in mets]
    if case in CONTACT_CASES:
        head[5:5] = ["iter.", "fact."]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * 3 + "---:|" * (len(head) - 3)]
    for r in rows:
        failed = str(r.get("status", "ok")) != "ok"
        cells = [flabel(r["family"], case), str(r["level"]), r["mesh"], _fmt_int(r["unknowns"]),
                 "-" if failed else f"{r['time_s']:.3g}"]
        if case in CONTACT_CASES:
            cells += [_int(r.get("contact_iterations")), _int(r.get("factorizations"))]
        if failed:
            cells += [f"**{r['status']}**"] + [""] * (len(mets) - 1)
        else:
            cells += [_pct(r[m]) for m in mets]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _int(v):
    try:
        return str(int(v)) if math.isfinite(float(v)) else "-"
    except (TypeError, ValueError):
        return "-"


def _rate_txt(v):
    return f"{v:.2f}" if math.isfinite(v) else "n/a"


def rates_table(case, rows):
    prim, others = METRICS[case]
    mets = [prim] + others
    lines = ["| family | " + " | ".join(f"rate of {SHORT[m]} (expected {RATE_EXPECTED[m]})" for m in mets) + " |",
             "|---|" + "---:|" * len(mets)]
    for fam in _families(rows):
        rs = [r for r in rows if r["family"] == fam]
        lines.append(f"| {flabel(fam, case)} | " + " | ".join(_rate_txt(rate(rs, m)) for m in mets) + " |")
    return "\n".join(lines)


def cheapest(rows, metric, target):
    ok = [r for r in rows if math.isfinite(r[metric]) and r[metric] <= target]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def extrapolate(rs, metric, target):
    """Unknowns and time at which the fitted finest-levels trend reaches target (None if
    the trend does not decrease)."""
    pts = [r for r in rs if _ok(r[metric])][-3:]
    if len(pts) < 2:
        return None
    ln, le, lt = (np.log([r[k] for r in pts]) for k in ("unknowns", metric, "time_s"))
    s = np.polyfit(ln, le, 1)[0]
    st = np.polyfit(lt, le, 1)[0]
    if s >= -0.05 or st >= -0.05:
        return None
    last = pts[-1]
    n = last["unknowns"] * (target / last[metric]) ** (1 / s)
    t = last["time_s"] * (target / last[metric]) ** (1 / st)
    return n, t


def recommendation(case, rows):
    prim = METRICS[case][0]
    out = []
    for target, name in ((1e-2, "1 %"), (1e-3, "0.1 %")):
        best = cheapest(rows, prim, target)
        per = []
        for fam in _families(rows):
            rs = [r for r in rows if r["family"] == fam]
            b = cheapest(rs, prim, target)
            if b:
                per.append(f"{flabel(fam, case)}: {b['mesh']} ({_fmt_int(b['unknowns'])} unknowns, "
                           f"{b['time_s']:.3g} s)")
            else:
                ex = extrapolate(rs, prim, target)
                done = [r for r in rs if math.isfinite(r[prim])]
                if not done:
                    per.append(f"{flabel(fam, case)}: every run failed")
                    continue
                finest = min(done, key=lambda r: r[prim])
                if ex and ex[0] < 1e8:
                    per.append(f"{flabel(fam, case)}: not reached (best {_pct(finest[prim])} at "
                               f"{_fmt_int(finest['unknowns'])} unknowns); the trend of the finest levels "
                               f"extrapolates to about {ex[0]:.2g} unknowns, {ex[1]:.2g} s")
                else:
                    per.append(f"{flabel(fam, case)}: not reached (best {_pct(finest[prim])} at "
                               f"{_fmt_int(finest['unknowns'])} unknowns) and the error no longer decreases")
        if best:
            head = (f"**{name}** ({LABEL[prim]}): cheapest is **{flabel(best['family'], case)}, {best['mesh']}** "
                    f"({_fmt_int(best['unknowns'])} unknowns, {best['time_s']:.3g} s).")
        else:
            head = f"**{name}** ({LABEL[prim]}): **no family reaches it** within the meshes run."
        out.append(head + " Per family: " + "; ".join(per) + ".")
    return out


CASE_TEXT = {
    "manufactured": """\
**Set-up.** Unit square, plane strain, E = 100, nu = 0.3, with the quadratic field
u_x = c (x^2 + 2y^2 - xy), u_y = c (-2x^2 + y^2 + 3xy), c = 0.01. Its stress is linear,
so -div sigma = b is constant, b = -((lambda+mu) grad div u + mu lap u) = (-7.115, -0.192)
(computed in `fields.py`), and a `*DLOAD GRAV` (density 1, g = |b|, direction b/|b|)
reproduces it exactly; the exact u is prescribed at every boundary node (`*BOUNDARY`
with values). Why this choice: the deck language has only constant body forces, and a
quadratic u is the richest field whose body force is constant; it is not in the
discrete spaces (linear on VEM edges, bilinear/linear for FEM), so the errors are pure
discretization errors, with no load or boundary approximation. Expected rates: O(h) in
the energy norm, O(h^2) for nodal displacements (unknowns N ~ h^-2, so h-rates are
-2 × the slope against N). Meshes: n × n quads (and the same split into triangles),
Voronoi with n^2 cells. On the uniform structured meshes all three structured families
reproduce this quadratic field *exactly at the nodes* (the discrete equations of a
uniform grid are exact for quadratics, a known superconvergence; "round-off" in the
table), so their nodal error says nothing there; on Voronoi meshes it converges at
O(h^2). The energy error is then only the error of the element-constant stress.
The second-order spaces (k = 2 VEM, Q8, T6) contain this field, so they reproduce it to
round-off on every mesh (a patch test, not a convergence study; three coarse levels).""",
    "timoshenko": """\
**Set-up.** Cantilever [0, 48] × [-6, 6], plane stress, E = 3e7, nu = 0.3, end shear
P = 1000 (Timoshenko & Goodier; the form of Augarde & Deeks 2008):
sigma_xx = -P (L - x) y / I, tau_xy = P/(2I)(D^2/4 - y^2),
u_x = -P y/(6EI) [(6L - 3x) x + (2 + nu)(y^2 - D^2/4)],
u_y = P/(6EI) [3 nu y^2 (L - x) + (4 + 5nu) D^2 x/4 + (3L - x) x^2].
The parabolic traction at x = L is applied as consistent nodal forces (`*CLOAD` per
node: the traction integrated against the linear edge shape functions, exactly; for
the second-order families against the quadratic ones of each side); the
exact displacements are prescribed at every node of x = 0 (so the fixity is that of the
formula). Tip deflection u_y(L, 0) = 0.0089 (interpolated linearly along x = L for
Voronoi meshes, which have no node at y = 0). Meshes: 4k × k quads (aspect 1), Voronoi
with 4k^2 cells. The formulas are checked numerically at start (sigma = C eps(u),
div sigma = 0).""",
    "lame": """\
**Set-up.** Quarter of a thick cylinder a = 1 ≤ r ≤ b = 2, plane strain, E = 1000,
nu = 0.3, internal pressure p = 1 as `*DLOAD P<k>` on the element sides on r = a,
rollers on x = 0 (u_x = 0) and y = 0 (u_y = 0). Exact:
u_r = (1+nu) a^2 p / (E (b^2 - a^2)) [(1-2nu) r + b^2/r],
sigma_tt = a^2 p/(b^2 - a^2) (1 + b^2/r^2) (= 1.667 at the bore).
Quads and triangles: polar grid nr × nt with nt ≈ (pi/2)·1.5·nr (square cells at mid
radius), nodes exactly on the arcs (our generator: the mesher has no annulus);
Voronoi: the mesher on the quarter annulus as a polygon with about one arc vertex per
cell size. The boundary is a polygon with nodes on the circles, so the geometric error
(O(h^2)) is part of the error, as in practice. Metrics: u_r at the nodes (discrete L2,
primary), energy norm of the element stress, and the hoop stress at the bore from the
nodal (averaged) stress S_node, mean relative error over the bore nodes. Second order:
the polar grid gets a node on every side, on the circle for the sides along an arc: Q8
and T6 sides are isoparametric, k = 2 VEM quads (VPE2) have curved sides (the quadratic
curve through the side's three nodes, docs/vem-formulation.md), so both bodies follow
the circles to O(h^3) and converge at rate 3-4. The k = 2 VEM on Voronoi cells meshes
the polygon with arc vertices (its side nodes at the middles of the chords), whose O(h^2)
geometric error bounds its displacement error (rate 2, not 3). The hoop error is over
the nodes on r = a (corners and arc middles for the polar grids, corners for Voronoi).""",
    "hertz": """\
**Set-up.** The paper's example 2 exactly as in `inputs/hertz_*` (disc R = 10, E = 1e3,
on a block E = 1e6, nu = 0.3, plane strain, half model, load 100 at the top of the disc,
penalty K = 1e5), on the mesh family of `postprocess/scenes/ex2_hertz.toml` (same
gradings toward the contact point): the paper's 389-, 600- and 1155-element meshes
(identical to `inputs/meshes/ex2_hertz_*`), then the 600-element mesh's divisions
× 2, 4 and 8 (`bench/hertz_refined.toml`'s h20k and h100k sit between them). Reference:
p0 = 83.60 and a = 1.523 of plane-strain Hertz theory. That is the answer for two
half-spaces with a parabolic gap and a rigid contact; the model has a finite block,
a point load at the top of the disc, a circular (not parabolic) profile and a penalty
overclosure of ~8e-4 (0.05 % of a), so the discrete peak converges to a value slightly
off 83.60 and the error against 83.60 levels off: that floor is a modelling error, not
a discretization error. The half-width is the a of a least-squares fit of
p^2 = p0^2 (1 - x^2/a^2) to the slave nodes with p > 0.3 p_max. VEM on Voronoi is not
run: the mesher meshes the half-disc only with structured quads/triangles. Second order
(k = 2 VEM on quads, Q8): the same meshes with `[mesh] order = 2`, the disc's arc side
nodes on the circle (curved VPE2 sides, isoparametric Q8 sides), up to × 4; slave
points are all nodes of the face with weights l/6, 4l/6, l/6 (docs/contact-formulation.md).

**Contact formulations.** *NTS penalty* is the paper's deck: `TYPE=NODE TO SURFACE`
(node to segment, finite sliding), `PRESSURE-OVERCLOSURE=LINEAR` with K = 1e5.
*NTS HARD* is the same pair with `PRESSURE-OVERCLOSURE=HARD` (augmented Lagrangian, no
overclosure; the active set is searched with soft springs, K h/E = 10, which stiffen to
K h/E = 1e3 at the first multiplier update). *S2S HARD* is `TYPE=SURFACE TO SURFACE`
(each side's interface nodes inserted into the other side's VEM polygons, node-to-node
contact with the pairing fixed at the start) with HARD; VEM first order only (FEM bodies
and second-order sides are refused),
so the inserted nodes add a few unknowns (the unknowns column counts them). CPRESS is the
force the solution balances over the tributary length of each slave node (inserted ones
included).""",
    "interface": """\
**Set-up.** The paper's example 3 as in `inputs/interface_*` (blocks [0,4]×[0,1] and
[0,4]×[1,2] meshed independently, non-matching at y = 1; E = 1e9, nu = 0.3, plane
strain; K = 1e12; top moved by -0.1, bottom fixed, top held in x), **with rollers on the
sides** (u_x = 0 on x = 0 and x = 4): then both blocks are in uniaxial strain and the
answer is a uniform contact pressure p = 0.1/(2/E' + 1/K) = 6.7254e7 with
E' = E(1-nu)/((1+nu)(1-2nu)). The paper's decks leave the sides free and have end
effects without a closed form. Quads 24k × 6k below and 20k × 5k above (non-matching
for every k), triangles split from them, Voronoi with 100 k^2 cells per block. The
exact solution is linear in each block, so every element represents it: what remains
is the error of the node-to-segment transfer across non-matching meshes. Metrics: the
largest and the RMS relative deviation of CPRESS from p over the slave nodes, and the
largest relative deviation of the element sigma_yy from -p. Second order (k = 2 VEM on
Voronoi cells and quads, Q8): the mesher's `order = 2` meshes; the resultant is then
sum CPRESS * CNAREA (the weights l/6, 4l/6, l/6 of each slave side).

**Contact formulations.** *NTS penalty* as above (K = 1e12); *NTS HARD*: the same pair
with `PRESSURE-OVERCLOSURE=HARD` (augmented Lagrangian, no overclosure), measured against
the exact p = 0.1 E'/2 = 6.7308e7 of an interface without compliance; *S2S HARD*:
`TYPE=SURFACE TO SURFACE` with HARD (interface nodes of each block inserted into the other
block's polygons, node-to-node pairs fixed at the start; VEM only, so VEM on Voronoi and
VEM on quads), against the same p. S2S passes the contact patch test on non-matching
meshes: errors at round-off ("round-off" in the tables, below 1e-9) at every level.""",
}


def _sources_text(sources):
    """Which run each case comes from, when they differ (a --cases rerun keeps the others)."""
    if not sources:
        return ""
    groups = {}
    for case, src in sources.items():
        groups.setdefault(src, []).append(case)
    if len(groups) < 2:
        return ""
    return " Cases by run: " + "; ".join(f"{', '.join(cs)}: {src}" for src, cs in groups.items()) + "."


def robustness(rows):
    """The robustness target of the contact formulations: every contact run converges in at
    most MAX_ITERATIONS iterations per increment without the fallback to the frozen
    pairing; the factorizations against the iterations (an iteration whose matrix did not
    change only re-solves)."""
    lines = ["| case | formulation | family | finest levels: unknowns | iterations per increment | "
             "numeric factorizations | re-solves only | fallbacks | verdict |",
             "|---|---|---|---|---|---|---|---|---|"]
    verdicts = []
    for case in CONTACT_CASES:
        rs = [r for r in rows if r["case"] == case]
        for fam in _families(rs):
            fr = [r for r in rs if r["family"] == fam]
            base, var = _split(fam)
            unk, its, fac, res, fb, bad = [], [], [], [], [], []
            for r in fr[-3:]:                     # the three finest levels run
                failed = str(r.get("status", "ok")) != "ok"
                unk.append(_fmt_int(r["unknowns"]))
                it = r.get("contact_iterations", float("nan"))
                f = r.get("factorizations", float("nan"))
                its.append(("**" + _int(it) + " (failed)**") if failed else
                           (f"**{_int(it)}**" if math.isfinite(it) and it > MAX_ITERATIONS else _int(it)))
                fac.append(_int(f))
                tot = r.get("iterations_total", it)
                res.append(_int(tot - f) if math.isfinite(tot) and math.isfinite(f) else "-")
                nfb = r.get("fallbacks", 0)
                fb.append(_int(nfb))
                if failed:
                    bad.append(f"{r['level']}: {r['status'].replace('failed: ', '')[:90]}")
                elif it > MAX_ITERATIONS or (math.isfinite(nfb) and nfb > 0):
                    bad.append(f"{r['level']}: {_int(it)} iterations" + (f", {_int(nfb)} fallbacks" if nfb else ""))
            allbad = [r for r in fr if str(r.get("status", "ok")) != "ok" or r.get("contact_iterations", 0) >
                      MAX_ITERATIONS or r.get("fallbacks", 0) > 0]
            verdict = "meets" if not allbad else "**misses** (" + "; ".join(
                f"{r['level']}" for r in allbad) + ")"
            verdicts.append((case, fam, not allbad))
            lines.append(f"| {case} | {VARIANT_LABEL[var]} | {BASE_LABEL[base]} | {' / '.join(unk)} | "
                         f"{' / '.join(its)} | {' / '.join(fac)} | {' / '.join(res)} | {' / '.join(fb)} | {verdict} |")
    return "\n".join(lines), verdicts


def write(rows, machine, elapsed, repeat, figdir=None, doc=None, sources=None):
    figdir = figdir or os.path.join(ROOT, "docs", "figures")
    doc = doc or os.path.join(ROOT, "docs", "accuracy-vs-speed.md")
    os.makedirs(figdir, exist_ok=True)
    case_names = []
    for r in rows:
        if r["case"] not in case_names:
            case_names.append(r["case"])
    rel_fig = os.path.relpath(figdir, os.path.dirname(doc))
    parts = [f"""# Accuracy against cost

How accurate is each discretization for the work it costs? Five cases with known
answers, four first-order families (and four second-order ones in the three smooth
cases), mesh sequences from coarse to about 10^5 to 5·10^5 unknowns;
the two contact cases (Hertz, interface) compare three contact formulations as well
(node to surface with penalty or HARD, surface to surface with HARD; see their sections
and the robustness table at the end):

| family | formulation | mesh |
|---|---|---|
| VEM, Voronoi | VEM (VPE/VPS) | the mesher's centroidal Voronoi cells (`vctools.mesh`, Lloyd) |
| VEM, quads | VEM | structured quads |
| FEM quads (Q4) | FEM bilinear, 2×2 Gauss | the same quads (`FORMULATION=FEM`) |
| FEM triangles (T3) | FEM constant strain | the same quads split in two triangles |
| VEM k = 2, Voronoi | second-order VEM (VPE2/VPS2) | the same Voronoi cells, a node in the middle of every side (`[mesh] order = 2`) |
| VEM k = 2, quads | second-order VEM | the same quads with side nodes |
| FEM quads (Q8) | FEM serendipity (CPE8/CPS8), 3×3 Gauss | the same quads with side nodes |
| FEM triangles (T6) | FEM quadratic triangles (CPE6/CPS6) | the same split quads with side nodes |

The second-order families (issue 13) run in the three cases with smooth solutions
(manufactured, Timoshenko, Lamé); contact on second-order sides is compared on the Hertz
problem in docs/paper-reproduction.md, not here. Their rows were added with
`bash bench/accuracy/run.sh --cases manufactured,timoshenko,lame --families
vem2-voronoi,vem2-quad,fem-q8,fem-t6 --repeat 3`: `--families` runs only those families
and keeps the other families' rows of each case (from `out/accuracy/rows/`, else from
`bench/results/accuracy.csv`), so the first-order rows are those of the earlier run
named under **Machine** below.

Everything here is regenerated by one command (about {elapsed / 60:.0f} minutes of runs on the machine
below, plus 2-3 minutes of Voronoi meshing the first time):

    bash bench/accuracy/run.sh

It builds the Release executable if needed, writes the meshes and decks to
`out/accuracy/` (meshes are cached there: delete the folder to rebuild them), runs every
deck {repeat} times (3 times when a run takes more than 5 s), measures the errors from the HDF5 output, and writes
`bench/results/accuracy.csv` (one row per case, family and mesh: unknowns, median time,
errors), `bench/results/accuracy_runs.csv` (every timing), the figures
`docs/figures/accuracy_<case>.png` and this document. `--cases hertz,lame` reruns some cases (the others are taken from
`out/accuracy/rows/`), `--report-only` redraws the figures and this document from the
CSV, `--quick` is a smoke test (three
coarse levels, two repeats, output under `out/accuracy/`). Sources: `bench/accuracy/`
(`cases.py`: set-ups and decks, `fields.py`: exact fields and norms, `meshes.py`,
`report.py`).

**Machine:** {machine}.{_sources_text(sources)} Release build (`scripts/build.sh Release`), one vemcontact
process at a time. The machine is shared and noisy: times below 0.05 s are dominated by
fixed costs (HDF5 set-up, file output) and their ratios mean little.

**Time** is the median over {repeat} runs of vemcontact's own `total` (the last line of
JOB.log: reading the deck, assembly, ordering, factorization, contact iterations,
stresses, VTU and HDF5 output; process start-up, about 10 ms, excluded; the process wall
time is in the CSV as `wall_s`). Meshing time is not included (meshes are inputs).

**Unknowns** are 2 × nodes (vemcontact's count, constrained dofs included).

**Norms** (relative; `fields.py`):
- *energy*: energy norm of the error of the element stress (`S_element`, the constant
  element stress the code reports; for VEM the projected stress). For the second-order
  families the element stress is linear and the HDF5 file keeps its mean, not the
  field, so there the *nodal* stress (`S_node`, each element's own linear stress at
  its nodes, averaged over the elements at a node) is measured, interpolated linearly on
  the fan triangles of the element's corners. This is the stress a user of these
  elements reads; averaging makes it somewhat smoother than the raw element field, so
  the k = 2 numbers are, if anything, slightly favoured; they are compared with k = 1 by
  rate (1 against 2) and by the cost of reaching 1 % and 0.1 %, where the gap is a
  factor 10-100 in unknowns, far beyond that effect:
  sqrt(Σ_e ∫_e (σ_h - σ)ᵀ C⁻¹ (σ_h - σ) / ∫ σᵀ C⁻¹ σ), integrated on a fan of triangles
  per element with the edge-midpoint rule (exact for these quadratic integrands, except
  for the Lamé cylinder, where it is accurate far beyond the error itself);
- *u (L2)*: nodal displacement error, sqrt(Σ_i w_i |u_h,i - u(x_i)|² / Σ_i w_i |u(x_i)|²)
  with the lumped nodal areas w_i = Σ_(e ∋ i) area(e)/n_nodes(e) (second order: the
  area shared by all 2n nodes of an element, corners and side nodes);
- point quantities (tip deflection, peak pressure, ...): |computed - exact| / |exact|.

**Rates** are fitted on the three finest meshes of a family, as rates in h:
-2 × d log(error)/d log(unknowns) (unknowns ~ h^-2 in 2D).

**Recommendations** pick, among the runs made, the cheapest (median time) that reaches
the error level in the case's first metric; where no run reaches it, the trend of the
three finest levels is extrapolated and marked as such.
"""]
    summary = []
    for case in case_names:
        rs = [r for r in rows if r["case"] == case]
        fig = os.path.join(figdir, f"accuracy_{case}.png")
        figure(case, rs, fig)
        rec = recommendation(case, rs)
        summary.append((case, rec))
        parts.append(f"## {case.capitalize()}\n\n{CASE_TEXT[case]}\n\n"
                     f"![{case}]({rel_fig}/accuracy_{case}.png)\n\n"
                     f"Left: error against unknowns; right: against time, with the Pareto front (grey)."
                     f" Top: {LABEL[METRICS[case][0]]}; bottom: {LABEL[([METRICS[case][0]] + METRICS[case][1])[1]]}.\n\n"
                     f"{table(case, rs)}\n\nObserved rates (in h, finest three meshes):\n\n{rates_table(case, rs)}\n\n"
                     "**Recommendation.**\n\n" + "\n\n".join(f"- {x}" for x in rec) + "\n")
    lines = ["## Summary: the cheapest run to reach 1 % and 0.1 %", "",
             "Among the runs made (median time on this machine); first metric of each case.", "",
             "| case | metric | 1 % | 0.1 % |", "|---|---|---|---|"]
    for case in case_names:
        rs = [r for r in rows if r["case"] == case]
        prim = METRICS[case][0]
        cells = []
        for target in (1e-2, 1e-3):
            b = cheapest(rs, prim, target)
            cells.append(f"{flabel(b['family'], case)}, {b['mesh']}: {_fmt_int(b['unknowns'])} unknowns, "
                         f"{b['time_s']:.3g} s" if b else "not reached")
        lines.append(f"| {case} | {LABEL[prim]} | {cells[0]} | {cells[1]} |")
    parts.append("\n".join(lines) + "\n")
    if any(r["case"] in CONTACT_CASES for r in rows):
        tab, verdicts = robustness(rows)
        parts.append(ROBUSTNESS_TEXT.format(maxit=MAX_ITERATIONS, table=tab,
                                            met=sum(v for *_, v in verdicts), n=len(verdicts)))
    parts.append(SUMMARY_TEMPLATE)
    sys.path.insert(0, os.path.join(ROOT, "bench", "adapt"))
    import section as adaptive                       # the adaptive section (bench/adapt/dam.py's results)
    with open(doc, "w") as f:
        f.write(adaptive.insert("\n".join(parts), adaptive.section()))
    print(f"wrote {doc} and {len(case_names)} figures in {figdir}")


ROBUSTNESS_TEXT = """\
## Contact iterations and factorizations: the robustness target

Target (the contact formulations issue): every contact case, including the finest
non-matching interfaces, converges in at most {maxit} iterations per increment without a
fallback, and no numeric factorization happens when the matrix has not changed. Measured
from each run's iteration records in the HDF5 file (`/steps/NNNN/contact/iterations`;
`bench/accuracy/main.py`, `contact_stats_h5`; every deck here has one step, one
increment): *iterations per increment* is the number of records of the step,
*numeric factorizations* the records with `factorized` = 1, *re-solves only* the
iterations that reused the factor (N - F: solves with the factor of the same matrix or,
by GMRES, of a nearby pairing); from the log, *fallbacks*: the lines '(Newton step on
the pairing replaced by the frozen-pairing step: ...)' (finite sliding's Newton step
given up for the frozen-pairing step when GMRES with the factor does not converge). The
result file of a failed run
has no step and no records: its iterations are the largest iteration number of the log's
iteration table. The three finest levels of each family and
formulation, separated by ' / '; a run that failed stops its family. The verdict is over
all levels of the family.

{table}

{met} of {n} family/formulation combinations meet the target on every level. The code
factorizes when the active set, the segments or HARD's springs change
(`same_key`/`near_key` in `src/contact/rules.f90`); a pairing whose projections moved by
at most a tenth of a segment is solved with the factor of the old one by GMRES, and so
are the Newton steps of finite sliding, whose tangent (not symmetric) the factor lacks
(docs/contact-robustness.md, session 4). So node to surface with the penalty factorizes
once per run here (3 iterations: the undeformed pairing, then two Newton steps), NTS HARD
twice (the soft search of the active set, K h/E = 10, and the stiffened springs,
K h/E = 1e3; 6-10 iterations: the multiplier updates and the Newton steps on the pairing
run together), and SURFACE TO SURFACE, whose pairing is fixed, twice as well (4
iterations: the soft search, the stiffening, then re-solves). Hertz needs more
factorizations because its active set grows from a point over 3-5 iterations.
"""


SUMMARY_TEMPLATE = """\
## What to use (plain recommendation)

- **Second order (k = 2 VEM, Q8, T6) wherever stresses matter or 0.1 % is wanted.**
  In the energy norm the k = 2 families converge at O(h^2) against O(h) for k = 1
  (rates 2.0 in Timoshenko and Lamé): 0.1 % in the energy norm of the cantilever takes
  about 10^4 unknowns with VEM k = 2 on Voronoi cells (1.0e-4 at 41 000 unknowns, 1 s)
  and 6 500 with VEM k = 2 quads (4.6e-4, 0.09 s), where no first-order family reaches
  even 1 % within the meshes run (1.4 % at 1.3·10^5 unknowns, FEM triangles). For the
  tip deflection the k = 2 families are 50-1000 times more accurate than k = 1 at about
  the same number of unknowns;
  Q8 is the most accurate of them on these structured meshes (bending is its best case
  on rectangles; 6.5e-7 at 1 700 unknowns, against 2.9e-6 for VEM k = 2 on the same
  quads and 1.1e-5 on Voronoi cells), and VEM k = 2 is the one that keeps this accuracy
  on arbitrary polygons and distorted meshes (docs/paper-reproduction.md, example 1).
  The quadratic manufactured field is reproduced to round-off by all four second-order
  families on every mesh (so "cheapest" there only says that a 4 × 4 mesh is exact).
  Curved boundaries: with its side nodes on the arcs (curved sides) VEM k = 2 on quads
  follows the circles of the Lamé cylinder as Q8 does: nodal displacement error 4.7e-7
  at 15 000 unknowns (rate 3.5; with straight chords it was 6.0e-5, rate 2, the
  polygon's O(h^2) geometric error), energy 2.7e-4 (Q8 3.7e-4); Q8 stays ahead in the
  displacements (1.3e-8, rate 4). VEM k = 2 on Voronoi cells meshes the polygon with arc
  vertices and keeps the O(h^2) geometric error (1.9e-4 at 25 000 unknowns). Stresses
  gain either way: energy 2.7e-4 at 15 000 unknowns for VEM k = 2 quads against 8.9e-3
  at 20 000 for VEM quads.
  Per unknown, second-order runs cost about 1.7-2.5 times as much time as first-order
  ones at 2-6·10^4 unknowns (denser matrix rows, more fill), which the accuracy gains
  dwarf; at 10^6 unknowns see docs/performance.md.

- **Displacements and deflections of smooth problems: VEM on quads.** It is the
  cheapest or tied in every smooth case. In bending (Timoshenko) its tip deflection is
  about 4 times more accurate than FEM quads (Q4, full 2×2 integration, stiff in
  bending) at the same mesh, i.e. FEM quads need about twice the element size
  refinement (4× the unknowns) for the same deflection, and 25-30 times more accurate
  than FEM triangles. 1 % needs only a handful of elements through the depth; 0.1 % is
  reached with about 16 elements through the depth of the beam (a few thousand
  unknowns, well under 0.1 s). Cost per unknown is the same for all families (same
  sparse Cholesky), so fewer unknowns is less time, up to the noise of small runs.
- **Stresses in the energy norm** (the element stress the code reports, constant per
  element) converge at O(h) for every first-order family, with nearly the same constant at the same
  element size: 1 % needs 64 × 64 elements on the unit square of the manufactured case
  (about 10^4 unknowns, 0.1 s) and 64 elements radially in the Lamé cylinder, and more
  than 64 elements through the depth of the cantilever (1.6 % there);
  **0.1 % needs about 5·10^5 unknowns or more** and is reached in none of the smooth
  cases within the meshes run (FEM triangles at 512 × 512 on the unit square,
  5·10^5 unknowns and several seconds, come to 0.11 %). For
  stress accuracy use a second-order element (above), the nodal (averaged) stress or
  local refinement; no first-order family is cheaper than the others for stresses.
- **VEM on Voronoi meshes** costs about 2 times the unknowns of quads for the same
  number of cells (a Voronoi mesh has about 2 nodes per cell, a quad mesh 1), with
  about the same error per cell. Per unknown it beats FEM quads and triangles for
  bending deflections but not VEM quads; for energy-norm stresses it needs twice the
  unknowns of the structured families. Use it where the geometry needs it (joints,
  arbitrary bodies, mesh grading), not for accuracy per cost on simple shapes.
- **FEM triangles** are the worst choice for bending and displacements (O(h^2) but with
  a constant 25-30 times larger than VEM quads); their nodal-averaged hoop stress at the
  bore of the Lamé cylinder is the best of the four, because the averaging of
  constant-strain triangles happens to be more accurate at a boundary.
- **Hertz contact:** VEM quads and FEM quads are indistinguishable; the paper's
  389-element mesh already gives the peak pressure within 1 %. With the penalty the
  computed peak converges to about 83.75, 0.18 % above Hertz's 83.60: **0.1 % against the
  Hertz formula is not reachable with this model** (finite block, point load, circular
  profile), whatever the mesh or formulation. FEM triangles need far more unknowns (their
  peak pressure oscillates with the diagonal pattern). **HARD contact is not more
  accurate here:** without the penalty's overclosure (about 8e-4, which lowers the peak)
  the peak converges to about 83.95 (NTS HARD) and 84.07 (S2S HARD), 0.4-0.6 % above
  83.60, so the error against the formula is 2-3 times that of the penalty at the finest
  mesh; the half-width is the same within 0.1 %. S2S HARD is the least accurate of the
  three on the paper's coarse meshes (peak 3.3 % off at 389 elements, 2.2 % at 600, against
  0.8 % for the penalty), and it costs more iterations: 7-10 (4-8 factorizations; the
  active set is searched on soft springs, then the stiffened springs' multiplier updates
  only re-solve) against 4-5 for the penalty; NTS HARD 6-8 iterations with 3-5
  factorizations (one per active set of the search, one for the stiffening). All three
  meet the robustness target on every Hertz mesh. The
  resultants agree (99.7 of the
  applied 100 on the half model by the trapezoid rule, for all three), so these are
  accuracy and cost differences, not wrong answers. Use the penalty (or HARD where no
  overclosure is wanted) for curved contact; S2S gains nothing here and costs more.
  **Second order** (VEM k = 2 quads with curved arc sides, Q8, both NODE TO SURFACE):
  within 1 % from the coarsest mesh (389 elements, 2 538 unknowns: +0.46 % and +0.28 %
  with the penalty), and they converge to the same modelling floor as first order (83.75
  and 83.76 on 600 × 4, 58 580 unknowns; HARD 83.95 and 83.96). VEM k = 2 comes from
  below: it passes 83.54 (-0.07 %) at 600 elements (3 848 unknowns), which the table
  above counts as reaching 0.1 %, but that is a crossing on the way to the floor, not
  convergence to 83.60; 0.1 % is out of reach for second order too. The half-width fit
  is within 1.5 % on every mesh (0.7 % on the finer two).
- **Non-matching interface:** the node-to-segment transfer on non-matching structured
  meshes leaves a pattern in the contact pressure that does not shrink with the mesh:
  slave nodes that sit over master nodes carry 9-10 % less pressure, the others about
  2 % more (the resultant converges: 4e-5 on the finest quads). Voronoi meshes show an irregular
  pattern of the same size; NTS HARD has the same pattern (the transfer, not the
  penalty, makes it). So **with node to surface neither 1 % nor 0.1 % in the nodal contact
  pressure is reachable by refining**. **SURFACE TO SURFACE passes the patch test:** on
  Voronoi and on quads, at every level, the contact pressure, the resultant and the
  stresses are exact to round-off (1e-12 relative or below), in 4 iterations with 2
  numeric factorizations per run (the soft search, then the stiffened springs), for a
  few percent more unknowns (the inserted interface nodes) and a run time of 0.4-1.3
  times the penalty's (noisy at a load of 2-5; node to surface with the penalty
  factorizes only once). Use it for non-matching interfaces of VEM bodies where the local
  contact pressure matters. **Second order with node to surface is worse here:** on the
  mesher's `order = 2` meshes (VEM k = 2 on Voronoi cells and quads, Q8; slave weights
  l/6, 4l/6, l/6 per side, master sides split into their two chords) the nodal contact
  pressure deviates from p by 30-34 % (max) and 16-19 % (RMS) on quads and 47-57 % / 16-24 %
  on Voronoi cells at every level, and the element sigma_yy by 5-17 %: a uniform pressure
  is transmitted exactly only on matching meshes (test_second_order_contact.py), and
  the node-to-segment transfer across non-matching quadratic sides distributes it
  unevenly between corner and side nodes. The resultant (sum CPRESS * CNAREA) converges
  at O(h) (6e-4 on the finest meshes). SURFACE TO SURFACE is refused on second-order
  sides; for non-matching contact interfaces use first-order VEM with S2S.

## Notes

- Node to surface with finite sliding converges on every interface mesh here, the finest
  included (2 × 25 600 Voronoi cells, about 2·10^5 unknowns, K h/E about 10: 3 iterations
  with the penalty, 10 with HARD), since session 4 (the master's reference normal, and
  Newton steps on the pairing by GMRES). Before, with the current normal, these runs did
  not settle (exit status 4 after 50 iterations), the finest VEM quads took 43 iterations
  with the penalty and failed with HARD, and NTS HARD took 13-22 iterations with a
  factorization each (docs/contact-robustness.md has the before/after table).
- With `SMALL SLIDING` the pairing is fixed and an iteration whose active set holds only
  re-solves (docs/performance.md, "Contact formulations").
- Small runs (< 0.05 s) are dominated by fixed costs and by the noise of the shared
  machine: their time ratios mean little. The runs of a study take turns on one core;
  other jobs on the machine add noise that the median of the repeats only partly removes.
- Meshes are deterministic (seeded); the mesher's Voronoi internals may change between
  versions, which moves the Voronoi numbers slightly.
"""
