"""vc-paper: reproduce the tables and figures of Sun et al. (2022).

  python -m vctools.paper [--out DIR] [--work DIR] [--exe PATH] [--quick] [-j N]

Runs the paper's four examples with vemcontact in a work folder (default
out/paper), draws the figures into DIR/figures and writes DIR/paper-reproduction.md
(DIR default: docs/) with each table and figure regenerated, the paper's numbers
beside ours and, where they differ, by how much and why:

  example 1  two-element cantilever, 2d/b = 0, 0.5, ..., 4, VEM and FEM, first
             and second order (k = 2 VEM, 8-node quad) (Fig. 4)
  example 2  Hertz contact, 389/600/1155 elements, VEM and FEM (Figs. 6-8), and
             the 600-element VEM mesh with K = 1e5, 1e4, 1e3 (Table 1); each mesh
             also with HARD contact, NODE TO SURFACE and (VEM) SURFACE TO SURFACE
  example 3  horizontal interface, quad/tri/Voronoi 50-500 meshes (Figs. 10, 11),
             and node by node NODE TO SURFACE against SURFACE TO SURFACE (HARD),
             in the decks as they are and with the top and bottom on rollers
             (the contact patch test: exact uniform pressure)
  example 4  dam on a jointed foundation (Figs. 13, 14), NODE TO SURFACE with
             the penalty and SURFACE TO SURFACE with HARD along the joint

Variants of the decks in inputs/ are written to the work folder's decks/ by text
substitution (TYPE=SURFACE TO SURFACE, PRESSURE-OVERCLOSURE=HARD, rollers).

--quick runs a subset (2d/b = 0 and 2, the 389-element Hertz meshes, Table 1 on
the 389-element mesh, two interface meshes, no dam) for tests, with the same
variants.  Exit status:
0 done, 1 a run failed or bad input (the document is still written, naming the
failed runs).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import math
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from vctools.cli import entry
from vctools.plot.results import ResultError
from . import runs as rr

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
INPUTS = os.path.join(ROOT, "inputs")
MESHES = os.path.join(INPUTS, "meshes")

# the paper's numbers (section 4.2 and Table 1)
HERTZ_ARGS = (200.0, 10.0, 1.0e3, 0.3, 1.0e6, 0.3)     # P on the full disc, R, E1, nu1, E2, nu2
PAPER_P0, PAPER_VEM, PAPER_FEM = 83.60, 82.21, 80.57
CANTILEVER_EXACT = 0.3                                  # M L^2 / (2 E I), M = 16, L = 40, b = 8, E = 1000
Q4_CLOSED_FORM = 1.0 / 4.125                            # 1 / (1 + (L_e/b)^2 / 2), L_e = 20, b = 8, nu = 0
DISTORTIONS = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0]
HERTZ_MESHES = [389, 600, 1155]
PENALTIES = [1.0e5, 1.0e4, 1.0e3]
INTERFACES = ["quad", "tri", "voronoi_50", "voronoi_100", "voronoi_200", "voronoi_300", "voronoi_500"]
JOINT_LINE = [[4.0, 10.0], [10.0, 4.0]]
E_PLANE_STRAIN = 1.0e9 / (1 - 0.3 ** 2)                # example 3: E / (1 - nu^2)
P_INTERFACE = E_PLANE_STRAIN * 0.05                     # example 3 on rollers: the exact uniform pressure


@dataclass
class Job:
    key: str
    deck: str
    out: str
    rc: int | None = None
    seconds: float = 0.0
    message: str = ""

    @property
    def ok(self) -> bool:
        return self.rc == 0


@dataclass
class Plan:
    distortions: list
    hertz: list
    table1_mesh: int
    interfaces: list
    dam: bool
    jobs: dict = field(default_factory=dict)


# ------------------------------------------------------------------ decks
def _mesh_nodes(path: str) -> dict:
    """Node id -> (x, y) of the *NODE block of a mesh file."""
    nodes, inside = {}, False
    with open(path) as fh:
        for line in fh:
            s = line.strip()
            if s.startswith("**") or not s:
                continue
            if s.startswith("*"):
                inside = s.upper().startswith("*NODE")
                continue
            if inside:
                v = [t.strip() for t in s.split(",")]
                nodes[int(v[0])] = (float(v[1]), float(v[2]))
    return nodes


def cantilever_deck(db: float, form: str) -> str:
    """Example 1 deck for distortion `db` on the mesher's two quads (VEM or FEM):
    E = 1000, nu = 0, clamped at x = 0, end moment M = 16 as the couple +-M/b = +-2
    on the tip nodes (bottom in tension, as inputs/example1_cantilever.inp)."""
    mesh = os.path.join(MESHES, f"ex1_cantilever_2db_{db:.1f}_{form}.inp")
    formulation = form.rstrip("2").upper()      # vem2 / fem2: the second-order meshes
    if not os.path.exists(mesh):
        raise ResultError(f"{mesh}: no such file (python -m vctools.mesh paper writes it)")
    nodes = _mesh_nodes(mesh)
    xmax = max(x for x, _ in nodes.values())
    tip = sorted((y, i) for i, (x, y) in nodes.items() if abs(x - xmax) < 1e-9)
    bottom, top = tip[0][1], tip[-1][1]
    return f"""** written by vctools.paper: example 1 of Sun et al. (2022), 2d/b = {db:.1f}, {form.upper()}
** (loading as inputs/example1_cantilever.inp: the couple +-M/b = +-2 at the tip nodes)
*HEADING
Example 1: cantilever with end moment, two quads, 2d/b = {db:.1f}, {form.upper()}
*INCLUDE, INPUT={mesh}
*MATERIAL, NAME=UNIT
*ELASTIC
1000.0, 0.0
*SOLID SECTION, ELSET=BEAM, MATERIAL=UNIT, FORMULATION={formulation}
1.0
*BOUNDARY
CLAMP, 1
CLAMP_ORIGIN, 2
*STEP
*STATIC
*CLOAD
{bottom}, 1, 2.0
{top}, 1, -2.0
*END STEP
"""


def penalty_deck(nelem: int, K: float, form: str = "vem") -> str:
    """inputs/hertz_N_FORM.inp with the pressure-overclosure slope K and the mesh
    included by absolute path."""
    src = os.path.join(INPUTS, f"hertz_{nelem}_{form}.inp")
    with open(src) as fh:
        lines = fh.read().splitlines()
    out, want = [f"** written by vctools.paper from {os.path.relpath(src, ROOT)}: penalty slope K = {K:.0e}"], False
    for line in lines:
        s = line.strip()
        if want and s and not s.startswith("**"):
            out.append(f"{K:.6e}")
            want = False
            continue
        if s.upper().startswith("*SURFACE BEHAVIOR"):
            want = True
        if s.upper().startswith("*INCLUDE"):
            line = re.sub(r"INPUT=(\S+)", lambda m: "INPUT=" + os.path.join(INPUTS, m.group(1)), line, flags=re.I)
        out.append(line)
    return "\n".join(out) + "\n"


def variant_deck(src: str, note: str, surface_to_surface: bool = False, hard: bool = False,
                 rollers: bool = False) -> str:
    """A variant of the deck `src` (inputs/...) by text substitution: TYPE=SURFACE TO SURFACE on
    *CONTACT PAIR, PRESSURE-OVERCLOSURE=HARD (its LINEAR data line dropped), and for example 3
    `rollers`: the model's supports BOTTOM, 1, 2 and TOP, 1 become BOTTOM, 2 and TOP free in x
    but for the left corner node of each (x held there: no rigid sliding), so that the exact
    solution is the uniform compression.  *INCLUDE paths become absolute."""
    with open(src) as fh:
        lines = fh.read().splitlines()
    out = [f"** written by vctools.paper from {os.path.relpath(src, ROOT)}: {note}"]
    drop_data, in_bc, before_steps, done = False, False, True, set()
    mesh = None
    for line in lines:
        s = line.strip()
        u = s.upper().replace(" ", "")
        if drop_data and s and not s.startswith("**"):
            drop_data = False
            if not s.startswith("*"):
                continue                   # the LINEAR data line K
        if u.startswith("*STEP"):
            before_steps = False
        if s.startswith("*") and not s.startswith("**"):
            in_bc = u.startswith("*BOUNDARY") and before_steps
        if u.startswith("*INCLUDE"):
            m = re.search(r"INPUT=(\S+)", line, flags=re.I)
            mesh = os.path.join(os.path.dirname(src), m.group(1))
            line = line[:m.start(1)] + mesh + line[m.end(1):]
        if hard and u.startswith("*SURFACEBEHAVIOR"):
            line, drop_data = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD", True
            done.add("hard")
        if surface_to_surface and u.startswith("*CONTACTPAIR"):
            line = re.sub(r"TYPE\s*=\s*NODE TO SURFACE", "TYPE=SURFACE TO SURFACE", line, flags=re.I)
            done.add("sts")
        if rollers and in_bc and u in ("BOTTOM,1,2", "TOP,1"):
            nodes = _mesh_nodes(mesh)
            if u == "TOP,1":
                top = min(nodes, key=lambda i: (-nodes[i][1], nodes[i][0]))
                out.append(f"{top}, 1, 1")
            else:
                bottom = min(nodes, key=lambda i: (nodes[i][1], nodes[i][0]))
                out += ["BOTTOM, 2, 2", f"{bottom}, 1, 1"]
            done.add(u)
            continue
        out.append(line)
    want = ({"hard"} if hard else set()) | ({"sts"} if surface_to_surface else set()) | \
        ({"BOTTOM,1,2", "TOP,1"} if rollers else set())
    if want - done:
        raise ResultError(f"{src}: cannot write the variant ({note}): no {', '.join(sorted(want - done))} to replace")
    return "\n".join(out) + "\n"


def make_plan(quick: bool) -> Plan:
    if quick:
        return Plan(distortions=[0.0, 2.0], hertz=[389], table1_mesh=389, interfaces=["quad", "voronoi_50"], dam=False)
    return Plan(distortions=DISTORTIONS, hertz=HERTZ_MESHES, table1_mesh=600, interfaces=INTERFACES, dam=True)


def write_jobs(plan: Plan, work: str) -> None:
    decks = os.path.join(work, "decks")
    os.makedirs(decks, exist_ok=True)

    def add(key, deck, text=None):
        if text is not None:
            with open(deck, "w") as fh:
                fh.write(text)
        plan.jobs[key] = Job(key, deck, os.path.join(work, key))

    for db in plan.distortions:
        for form in ("vem", "fem", "vem2", "fem2"):
            add(f"ex1_{db:.1f}_{form}", os.path.join(decks, f"ex1_cantilever_2db_{db:.1f}_{form}.inp"),
                cantilever_deck(db, form))
    for n in plan.hertz:
        for form in ("vem", "fem"):
            add(f"hertz_{n}_{form}", os.path.join(INPUTS, f"hertz_{n}_{form}.inp"))
    for K in PENALTIES:
        add(f"table1_K{K:.0e}", os.path.join(decks, f"hertz_{plan.table1_mesh}_vem_K{K:.0e}.inp"),
            penalty_deck(plan.table1_mesh, K))
    for form in ("vem", "fem"):    # the paper's final choice omega = 1e4 on its finest mesh
        n = max(plan.hertz)
        add(f"hertz_{n}_{form}_K1e4", os.path.join(decks, f"hertz_{n}_{form}_K1e+04.inp"), penalty_deck(n, 1.0e4, form))
    # HARD contact: node to surface on every mesh, surface to surface on the VEM meshes
    # (surface to surface inserts nodes into polygons: FEM bodies are refused)
    for n in plan.hertz:
        for form, kinds in (("vem", ("nts", "sts")), ("fem", ("nts",))):
            src = os.path.join(INPUTS, f"hertz_{n}_{form}.inp")
            for kind in kinds:
                add(f"hard_hertz_{n}_{form}_{kind}", os.path.join(decks, f"hertz_{n}_{form}_{kind}_hard.inp"),
                    variant_deck(src, f"{'SURFACE' if kind == 'sts' else 'NODE'} TO SURFACE, HARD",
                                 surface_to_surface=kind == "sts", hard=True))
    for m in plan.interfaces:
        src = os.path.join(INPUTS, f"interface_{m}.inp")
        add(f"interface_{m}", src)
        add(f"interface_{m}_sts", os.path.join(decks, f"interface_{m}_sts_hard.inp"),
            variant_deck(src, "SURFACE TO SURFACE, HARD", surface_to_surface=True, hard=True))
        add(f"roller_{m}_nts", os.path.join(decks, f"interface_{m}_rollers.inp"),
            variant_deck(src, "top and bottom on rollers", rollers=True))
        add(f"roller_{m}_sts", os.path.join(decks, f"interface_{m}_rollers_sts_hard.inp"),
            variant_deck(src, "top and bottom on rollers, SURFACE TO SURFACE, HARD", surface_to_surface=True,
                         hard=True, rollers=True))
    if plan.dam:
        src = os.path.join(INPUTS, "dam_joint.inp")
        add("dam_joint", src)
        add("dam_joint_sts", os.path.join(decks, "dam_joint_sts_hard.inp"),
            variant_deck(src, "SURFACE TO SURFACE, HARD", surface_to_surface=True, hard=True))


def run_job(exe: str, job: Job) -> Job:
    os.makedirs(job.out, exist_ok=True)
    t = time.perf_counter()
    try:
        r = subprocess.run([exe, "-q", "-o", job.out, job.deck], capture_output=True, text=True, timeout=600)
        job.rc, err = r.returncode, (r.stderr or r.stdout).strip().splitlines()
        job.message = err[-1] if err and r.returncode else ""
    except (OSError, subprocess.TimeoutExpired) as exc:
        job.rc, job.message = -1, " ".join(str(exc).split())
    job.seconds = time.perf_counter() - t
    return job


# ------------------------------------------------------------------ figures
def _shrink_png(path: str, limit: int = 250_000) -> None:
    """Contours with smooth shading make large PNGs: an adaptive 256-colour
    palette keeps them readable and below the size limit of docs/figures."""
    if os.path.getsize(path) <= limit:
        return
    from PIL import Image
    with Image.open(path) as im:
        q = im.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
    q.save(path, optimize=True)


def hertz_contour(vtu: str, out: str, title: str) -> dict:
    """Fig. 6: the mesh (A) and the S_yy contour near the contact zone (B).
    Returns the smallest nodal S_yy in the window, where, and the disc's."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.tri import Triangulation
    from vctools.plot.contour import fan_triangles
    from vctools.plot.results import field_values, read_vtu, step_files

    res = read_vtu(step_files(vtu)[-1])
    xy = res.points
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 5.0), dpi=110, gridspec_kw={"width_ratios": [0.55, 1.45]})
    verts = [xy[p] for p in res.polygons]
    a1.add_collection(PolyCollection(verts, facecolors="#dde8f4", edgecolors="k", linewidths=0.25))
    a1.autoscale_view()
    a1.set_aspect("equal")
    a1.set_xlabel("x [m]")
    a1.set_ylabel("y [m]")
    a1.set_title(f"(A) mesh, {len(verts)} elements (half model)", fontsize=10)
    v, _, _ = field_values(res, "S:yy")
    win = (0.0, 4.0, 7.5, 12.5)
    inside = (xy[:, 0] <= win[1] + 1) & (xy[:, 1] >= win[2] - 1) & (xy[:, 1] <= win[3] + 1)
    tri = Triangulation(xy[:, 0], xy[:, 1], fan_triangles(res.polygons))
    lo = float(v[inside].min())
    m = a2.tripcolor(tri, v, shading="gouraud", cmap="viridis", vmin=lo, vmax=0.0)
    a2.add_collection(PolyCollection(verts, facecolors="none", edgecolors="k", linewidths=0.2, alpha=0.5))
    a2.set_xlim(win[0], win[1])
    a2.set_ylim(win[2], win[3])
    a2.set_aspect("equal")
    a2.set_xlabel("x [m]")
    a2.set_ylabel("y [m]")
    cb = fig.colorbar(m, ax=a2, shrink=0.85)
    cb.set_label("S_yy [Pa] (nodal, compression < 0)")
    a2.set_title("(B) normal stress S_yy near the contact (colour range clipped at 0)", fontsize=10)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    _shrink_png(out)
    # the smallest S_yy in the window on each side (material 1 = the disc, the deck's first)
    mat = np.asarray(res.cell_data.get("MATERIAL", np.ones(len(verts))))
    disc = np.zeros(len(xy), dtype=bool)
    for poly, mm in zip(res.polygons, mat):
        if mm == 1:
            disc[poly] = True
    sel = inside & (xy[:, 0] <= win[1]) & (xy[:, 1] >= win[2]) & (xy[:, 1] <= win[3])
    ids = np.flatnonzero(sel)
    i_lo = ids[np.argmin(v[ids])]
    di = ids[disc[ids]]
    return {"min": float(v[i_lo]), "at": xy[i_lo], "in_disc": bool(disc[i_lo]),
            "disc_min": float(v[di].min()) if len(di) else float("nan")}


def contour(vtu_or_pvd: str, spec: str, out: str, units: str, title: str, lines=None) -> None:
    from vctools.plot.contour import plot
    from vctools.plot.results import read_vtu, step_files
    res = read_vtu(step_files(vtu_or_pvd)[-1])
    plot(res, spec, out, units=units, title=title, lines=lines)
    _shrink_png(out)


# ------------------------------------------------------------------ numbers
def interface_stats(c: rr.ContactCurve) -> dict:
    o = np.argsort(c.x)
    x, p = c.x[o], c.cpress[o]
    mean = float(np.trapz(p, x) / (x[-1] - x[0])) if len(x) > 1 else float("nan")
    mid = (x > x[0] + 0.25 * (x[-1] - x[0])) & (x < x[-1] - 0.25 * (x[-1] - x[0]))
    return {"mean": mean, "min": float(p.min()), "max": float(p.max()),
            "mid_min": float(p[mid].min()) if mid.any() else float("nan"),
            "mid_max": float(p[mid].max()) if mid.any() else float("nan"),
            "closed": int(c.closed.sum()), "n": len(c.x), "nelem": None}


def hertz_hard_stats(c: rr.ContactCurve) -> dict:
    """Peak and half-width of a Hertz run.  The half-width a is the least-squares fit of the
    Hertz shape p^2 = p0^2 (1 - x^2/a^2), a line in x^2, to the closed nodes; the contact edge
    itself lies between the last closed and the first open node."""
    o = np.argsort(c.x)
    x, p, cl, g = c.x[o], c.cpress[o], c.closed[o], c.copen[o]
    slope, icpt = np.polyfit(x[cl] ** 2, p[cl] ** 2, 1) if cl.sum() >= 2 else (float("nan"), float("nan"))
    last = int(np.flatnonzero(cl)[-1]) if cl.any() else -1
    return {"peak": float(p.max()), "at": float(x[int(np.argmax(p))]), "nclosed": int(cl.sum()), "n": len(x),
            "a_fit": float(np.sqrt(-icpt / slope)) if slope < 0 < icpt else float("nan"),
            "last_closed": float(x[last]) if last >= 0 else float("nan"),
            "first_open": float(x[last + 1]) if 0 <= last < len(x) - 1 else float("nan"),
            "overclosure": float(max(0.0, -g[cl].min())) if cl.any() else 0.0}


def element_stress(run: str) -> np.ndarray:
    """The element stresses (xx, yy, zz, xy) of the last step of a run."""
    import h5py
    f = rr.h5_file(run)
    try:
        with h5py.File(f, "r") as h:
            return h[f"steps/{sorted(h['steps'])[-1]}/S_element"][()]
    except (OSError, KeyError) as exc:
        raise ResultError(f"{f}: no element stresses ({' '.join(str(exc).split())})") from None


def patch_stats(run: str, p: float = P_INTERFACE) -> dict:
    """Example 3 on rollers against its exact solution, the uniform compression
    S_yy = -p, S_xx = S_xy = 0: the largest |CPRESS/p - 1| over the slave nodes and
    the largest and rms element stress error max(|S_xx|, |S_yy + p|, |S_xy|) / p."""
    c = rr.read_contact(run)
    s = element_stress(run)
    e = np.abs(s[:, [0, 1, 3]] - np.array([0.0, -p, 0.0])).max(axis=1) / p
    return {"n": len(c.x), "closed": int(c.closed.sum()), "cpress": float(np.abs(c.cpress / p - 1).max()),
            "stress_max": float(e.max()), "stress_rms": float(np.sqrt(np.mean(e ** 2))),
            "slip": float(np.abs(c.cslip).max()) if c.cslip is not None else float("nan")}


def node_by_node(nts: rr.ContactCurve, sts: rr.ContactCurve) -> dict:
    """NODE TO SURFACE against SURFACE TO SURFACE at the deck's slave nodes: the surface-to-
    surface pair keeps them (same ids) and adds the inserted nodes.  Returns the largest
    |p_NTS - p_STS| over the common nodes relative to the mean STS pressure there."""
    at = {int(n): k for k, n in enumerate(sts.node)}
    common = [(i, at[int(n)]) for i, n in enumerate(nts.node) if int(n) in at]
    if not common:
        return {"n": 0, "max": float("nan"), "mean": float("nan")}
    a = np.array([nts.cpress[i] for i, _ in common])
    b = np.array([sts.cpress[j] for _, j in common])
    ref = float(np.mean(np.abs(b))) or 1.0
    return {"n": len(common), "max": float(np.abs(a - b).max() / ref), "mean": ref,
            "extra": len(sts.node) - len(common)}


def joint_coordinate(c: rr.ContactCurve) -> np.ndarray:
    """Distance along the dam's joint from the heel (4, 10) toward the tip (10, 4)."""
    (x0, y0), (x1, y1) = JOINT_LINE
    d = np.array([x1 - x0, y1 - y0]) / math.hypot(x1 - x0, y1 - y0)
    return (c.x - x0) * d[0] + (c.y - y0) * d[1]


def tip_ratio(c: rr.ContactCurve) -> float:
    """CPRESS of the slave node nearest the joint tip (the tip itself excluded: it is shared by
    both faces) over the mean of its two neighbours along the joint; the old joint-tip defect
    gave about 2."""
    s = joint_coordinate(c)
    o = np.argsort(s)
    length = math.hypot(JOINT_LINE[1][0] - JOINT_LINE[0][0], JOINT_LINE[1][1] - JOINT_LINE[0][1])
    keep = [k for k in o if length - s[k] > 1e-9]
    if len(keep) < 3:
        return float("nan")
    p = c.cpress[keep]
    return float(p[-1] / (0.5 * (p[-2] + p[-3]))) if p[-2] + p[-3] else float("nan")


def plot_interface_nodes(pairs: list, out: str, title: str) -> None:
    """CPRESS / p along the interface, node by node, one panel per (label, NTS, STS, exact)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(pairs), 1, figsize=(8.0, 3.4 * len(pairs)), dpi=110, squeeze=False)
    for ax, (label, nts, sts, exact) in zip(axes[:, 0], pairs):
        for c, style, name in ((sts, dict(marker=".", ms=4, lw=1.0, color="C0"), "SURFACE TO SURFACE, HARD"),
                               (nts, dict(marker="o", ms=5, lw=0.8, color="C3", mfc="none"),
                                "NODE TO SURFACE, penalty K = 1e12")):
            o = np.argsort(c.x)
            ax.plot(c.x[o], c.cpress[o] / P_INTERFACE, label=f"{name} ({len(c.x)} slave nodes)", **style)
        if exact:
            ax.axhline(1.0, color="k", lw=0.8, ls="--", label="exact (uniform)")
        ax.set_ylabel("CPRESS / (E/(1-nu^2) x 0.05)")
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel("x [m]")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    _shrink_png(out)


def plot_joint(runs: list, out: str, title: str) -> None:
    """CPRESS and CSLIP along the dam's joint for both steps, one curve per (label, folder)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 6.6), dpi=110, sharex=True)
    styles = (dict(marker="o", ms=5, mfc="none", lw=0.8, color="C3"), dict(marker=".", ms=4, lw=1.0, color="C0"))
    for (label, folder), st in zip(runs, styles):
        for j, step in enumerate((1, 2)):
            c = rr.read_contact(folder, step=step)
            s = joint_coordinate(c)
            o = np.argsort(s)
            axes[0, j].plot(s[o], c.cpress[o] / 1e3, label=label, **st)
            if c.cslip is not None:
                axes[1, j].plot(s[o], c.cslip[o] * 1e6, label=label, **st)
    for j, name in enumerate(("step 1, self-weight (geostatic)", "step 2, reservoir")):
        axes[0, j].set_title(name, fontsize=10)
        axes[0, j].set_ylabel("CPRESS [kPa]")
        axes[1, j].set_ylabel("CSLIP [um]")
        axes[1, j].set_xlabel("distance along the joint from the heel (4, 10) [m]")
        for i in (0, 1):
            axes[i, j].grid(alpha=0.3)
            axes[i, j].legend(fontsize=8)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    _shrink_png(out)


def dam_stats(h5: str) -> dict:
    import h5py
    with h5py.File(h5, "r") as f:
        xy = f["mesh/coordinates"][()]
        last = sorted(f["steps"])[-1]
        u = f[f"steps/{last}/U"][()]
        s = f[f"steps/{last}/S_node"][()]
        cp = f[f"steps/{last}/contact/pair_1/CPRESS"][()] if f"steps/{last}/contact/pair_1" in f else np.zeros(0)
        st = f[f"steps/{last}/contact/pair_1/STATUS"][()] if f"steps/{last}/contact/pair_1" in f else np.zeros(0)
        nelem = len(f["mesh/element_ids"])
    c, r = 0.5 * (s[:, 0] + s[:, 1]), np.hypot(0.5 * (s[:, 0] - s[:, 1]), s[:, 3])
    s1, s3 = c + r, c - r
    i1, i3 = int(np.argmax(s1)), int(np.argmin(s3))
    tip = np.array([10.0, 4.0])
    return {"nelem": nelem, "nnode": len(xy), "ux": (float(u[:, 0].min()), float(u[:, 0].max())),
            "uy": (float(u[:, 1].min()), float(u[:, 1].max())),
            "s1max": float(s1[i1]), "s1at": xy[i1], "s1tip": float(np.hypot(*(xy[i1] - tip))),
            "s3min": float(s3[i3]), "s3at": xy[i3], "s3tip": float(np.hypot(*(xy[i3] - tip))),
            "joint_closed": int(np.sum(st != 0)) if st.dtype.kind in "iu" else None, "joint_n": len(cp),
            "joint_pmax": float(cp.max()) if len(cp) else 0.0}


# ------------------------------------------------------------------ main
@entry("vc-paper")
def main(argv=None) -> int:
    doc = __doc__.split("\n\n")
    p = argparse.ArgumentParser(prog="vc-paper", description=doc[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog="\n\n".join(doc[1:]))
    p.add_argument("--out", default=os.path.join(ROOT, "docs"),
                   help="folder of paper-reproduction.md and figures/ (default: the repository's docs/)")
    p.add_argument("--work", default=None, help="folder for the decks and runs (default: out/paper, or out/paper-quick)")
    p.add_argument("--exe", default=None, help="vemcontact executable (default: $VEMCONTACT_EXE, else build/vemcontact)")
    p.add_argument("--quick", action="store_true", help="a small subset, for tests")
    p.add_argument("-j", "--jobs", type=int, default=2, help="runs at the same time (default 2)")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    try:
        exe = a.exe or os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build", "vemcontact")
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            raise ResultError(f"{exe}: no vemcontact executable (build it: bash scripts/build.sh Release, or give --exe)")
        exe = os.path.abspath(exe)
        work = os.path.abspath(a.work or os.path.join(ROOT, "out", "paper-quick" if a.quick else "paper"))
        out = os.path.abspath(a.out)
        figs = os.path.join(out, "figures")
        os.makedirs(figs, exist_ok=True)
        plan = make_plan(a.quick)
        write_jobs(plan, work)
        with cf.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            # the largest runs first so that two workers finish together
            order = sorted(plan.jobs.values(), key=lambda j: ("dam" not in j.key, "1155" not in j.key, j.key))
            list(pool.map(lambda j: run_job(exe, j), order))
        t_runs = time.perf_counter() - t0
        failed = [j for j in plan.jobs.values() if not j.ok]
        for j in failed:
            print(f"vc-paper: warning: {j.key} failed (status {j.rc}): {j.message}", file=sys.stderr)
        from .document import write_document
        path = write_document(plan, work, out, figs, t_runs)
    except ResultError as exc:
        print(f"vc-paper: error: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"vc-paper: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 1
    print(f"{path}  ({len(plan.jobs)} runs, {len(failed)} failed, {time.perf_counter() - t0:.1f} s)")
    return 1 if failed else 0
