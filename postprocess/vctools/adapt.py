"""vc-adapt: adaptive mesh refinement driven by vemcontact's error estimate.

    vc-adapt DECK --scene SCENE.toml --target-error 1% [--max-unknowns N] [-o DIR]
             [--refine split|remesh]

The first cycle meshes the scene (vctools.mesh); each cycle runs the deck on its mesh and
reads the error estimate of every step from the HDF5 results (ERROR_INDICATOR, error_estimate,
energy_norm: docs/error-estimate.md).  The loop stops when the estimated relative energy
error of every step is at most the target, when the next mesh would exceed the budget of
unknowns, or after --max-cycles.  Otherwise the cells are marked by the bulk (Doerfler)
criterion on the step with the largest relative error: the fewest cells, largest
indicators first, that hold the fraction theta of its squared estimate.  The next mesh:

- split (the default when every body is VEM): the marked cells of the previous mesh are
  split into quadrilaterals (vctools.mesh.refine: centre and side midpoints; a midpoint on
  an unmarked neighbour is one more vertex of it, which the virtual element takes as is).
  Joints, contact surfaces, loaded surfaces, node and element sets are carried over; no
  remeshing after the first cycle.  Refused for FEM bodies (a FEM cell takes no hanging
  node).
- remesh (the default with FEM bodies): marked cells get half their size (four times the
  cells per area), the others keep theirs; the scene is meshed again with that size field
  (a `grading = [{ field = ... }]` for every Voronoi body, its `cells` the sum over its old
  cells), so joints, contact surfaces and named selections are made anew by the mesher
  exactly as in the scene.  Structured bodies (quad, tri) are meshed as the scene says,
  unrefined.

Every cycle is kept in DIR/cycle_NN/: the size field (size.npz, remesh only), the mesh (mesh.inp), the
deck (JOB.inp, its *INCLUDE of the mesh pointing at mesh.inp, other includes at the
original files) and vemcontact's results and log.  DIR/adapt.csv has the table that is
also printed: cycle, cells, unknowns, estimated relative error, estimate, mesh time, run time.
"""
from __future__ import annotations

import argparse
import copy
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

from .cli import entry
from .mesh.deck import write_deck
from .mesh.errors import MeshError
from .mesh.geometry import points_in_polygon
from .mesh.refine import refine as split_cells
from .mesh.scene import FemType, build, load

ROOT = Path(__file__).resolve().parents[2]
INCLUDE = re.compile(r"^(\*include\s*,.*?input\s*=\s*)([^,\s]+)(.*)$", re.IGNORECASE)


class AdaptError(Exception):
    """A user error: one line, no traceback."""


def parse_fraction(text):
    """'1%' -> 0.01, '0.01' -> 0.01."""
    t = text.strip()
    try:
        v = float(t[:-1]) / 100.0 if t.endswith("%") else float(t)
    except ValueError:
        raise AdaptError(f"--target-error: not a number or percentage: {text!r}") from None
    if not (0.0 < v < 1.0):
        raise AdaptError(f"--target-error must lie between 0 and 100 %, got {text!r}")
    return v


def find_executable(exe=None):
    for cand in (exe, os.environ.get("VEMCONTACT_EXE"), shutil.which("vemcontact"),
                 str(ROOT / "build" / "vemcontact"), str(ROOT / "build-debug" / "vemcontact")):
        if cand and os.path.isfile(cand) and os.access(cand, os.X_OK):
            return cand
    raise AdaptError("vemcontact executable not found: give --exe or set VEMCONTACT_EXE")


def _is_vctools_mesh(path):
    try:
        with open(path) as f:
            return "written by vctools.mesh" in f.readline() + f.readline()
    except OSError:
        return True          # not made yet: the scene will make it


def deck_includes(deck):
    """[(line index, include path as written)] of a deck's *INCLUDE lines."""
    out = []
    for i, line in enumerate(Path(deck).read_text().splitlines()):
        m = INCLUDE.match(line.strip())
        if m:
            out.append((i, m.group(2).strip("'\"")))
    return out


def mesh_include(deck, name=None):
    """Index (into deck_includes) of the *INCLUDE that holds the scene's mesh: the one named
    `name`, else the only one, else the only one written by vctools.mesh."""
    inc = deck_includes(deck)
    if name is not None:
        hits = [k for k, (_, p) in enumerate(inc) if p == name or os.path.basename(p) == name]
        if len(hits) != 1:
            raise AdaptError(f"{deck}: no single *INCLUDE of {name!r} (includes: {[p for _, p in inc]})")
        return hits[0]
    if len(inc) == 1:
        return 0
    base = Path(deck).parent
    hits = [k for k, (_, p) in enumerate(inc) if _is_vctools_mesh(base / p)]
    if len(hits) != 1:
        raise AdaptError(f"{deck}: cannot tell which *INCLUDE is the mesh; give --include NAME "
                         f"(includes: {[p for _, p in inc]})")
    return hits[0]


def write_cycle_deck(deck, which, cycle_dir, mesh_name="mesh.inp"):
    """The deck in `cycle_dir`: its mesh include replaced by `mesh_name`, the other
    includes pointing at the original files."""
    deck = Path(deck)
    lines = deck.read_text().splitlines()
    for k, (i, p) in enumerate(deck_includes(deck)):
        m = INCLUDE.match(lines[i].strip())
        target = mesh_name if k == which else os.path.relpath((deck.parent / p).resolve(), cycle_dir)
        lines[i] = m.group(1) + target + m.group(3)
    out = Path(cycle_dir) / deck.name
    out.write_text("\n".join(lines) + "\n")
    return out


def read_estimate(h5path):
    """Per step: (name, relative error, estimate, energy norm, indicators); and the mesh."""
    steps = []
    with h5py.File(h5path, "r") as f:
        x = f["mesh/coordinates"][...]
        off = f["mesh/element_offsets"][...]
        conn = f["mesh/element_connectivity"][...]
        for key in sorted(f["steps"]):
            g = f["steps"][key]
            if "ERROR_INDICATOR" not in g:
                raise AdaptError(f"{h5path}: step {key} has no ERROR_INDICATOR (the deck's output requests "
                                 "leave out S (add S under *EL FILE), or the model has second-order "
                                 "elements, which get no estimate)")
            est, en = float(g.attrs["error_estimate"]), float(g.attrs["energy_norm"])
            rel = est / math.hypot(est, en) if est > 0 else 0.0
            name = g.attrs["name"]
            name = name.decode() if isinstance(name, bytes) else str(name)
            steps.append((name, rel, est, en, g["ERROR_INDICATOR"][...]))
    return steps, x, off, conn


def read_element_ids(h5path):
    """User element ids of the HDF5 mesh, in its element order."""
    with h5py.File(h5path, "r") as f:
        return f["mesh/element_ids"][...].astype(np.int64)


def fem_bodies(m):
    """Names of the mesh's FEM bodies."""
    return [name for name, et in m.bodies if isinstance(et, FemType) or str(et).upper().startswith("C")]


def cell_geometry(x, off, conn):
    """Centroids (n, 2) and areas (n,) of the cells (shoelace)."""
    n = np.diff(off)
    nxt = np.arange(len(conn)) + 1
    nxt[off[1:] - 1] = off[:-1]
    a, b = x[conn], x[conn[nxt]]
    cr = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
    area = np.add.reduceat(cr, off[:-1]) / 2
    cx = np.add.reduceat((a[:, 0] + b[:, 0]) * cr, off[:-1]) / (6 * area)
    cy = np.add.reduceat((a[:, 1] + b[:, 1]) * cr, off[:-1]) / (6 * area)
    assert (n >= 3).all()
    return np.column_stack([cx, cy]), area


def doerfler(eta, theta):
    """Boolean mask of the fewest cells, largest first, with sum eta^2 >= theta * total."""
    e2 = eta ** 2
    order = np.argsort(-e2, kind="stable")
    cum = np.cumsum(e2[order])
    m = int(np.searchsorted(cum, theta * cum[-1])) + 1 if cum[-1] > 0 else len(eta)
    mark = np.zeros(len(eta), bool)
    mark[order[:min(m, len(eta))]] = True
    return mark


def voronoi_bodies(scene):
    """(index, polygon) of the scene's Voronoi bodies."""
    out = []
    for k, b in enumerate(scene.get("body", [])):
        mesher = b.get("mesher", "voronoi" if "polygon" in b else "quad")
        if mesher != "voronoi":
            continue
        if "polygon" in b:
            out.append((k, np.asarray(b["polygon"], float)))
        elif "rectangle" in b:
            x0, y0, x1, y1 = map(float, b["rectangle"])
            out.append((k, np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])))
    return out


def graded_sizes(points, size, gamma=0.3, k=12):
    """Sizes limited so that they grow by at most gamma per unit distance between
    neighbouring points (s_i <= s_j + gamma |x_i - x_j| over the k nearest): a marked cell
    next to unmarked ones then gets a gradual transition, not a jump the Voronoi mesher
    would turn into slivers."""
    from scipy.spatial import cKDTree
    k = min(k, len(points))
    dist, nb = cKDTree(points).query(points, k=k)
    s = size.copy()
    for _ in range(200):                     # each pass spreads a small size by one neighbour
        t = np.minimum(s, (s[nb] + gamma * dist).min(axis=1))
        if np.array_equal(t, s):
            break
        s = t
    return s


def refined_scene(scene, centroids, area, factor, field_path):
    """The scene with every Voronoi body graded by the size field sqrt(area/factor) at the
    old centroids, gradation-limited (graded_sizes; written to field_path), and its cell
    target sum over its old cells of area/size^2."""
    size = graded_sizes(centroids, np.sqrt(area / factor))
    factor = area / size ** 2
    np.savez(field_path, points=centroids, size=size)
    new = copy.deepcopy(scene)
    for k, poly in voronoi_bodies(scene):
        inside = points_in_polygon(centroids, poly)
        b = new["body"][k]
        b["cells"] = max(int(round(factor[inside].sum())), int(b["cells"]))
        b["grading"] = [{"field": str(field_path)}]
    return new


def adapt(deck, scene_path, target, out_dir, max_unknowns=1_000_000, max_cycles=10, theta=0.5,
          uniform=False, exe=None, include=None, processes=1, lloyd=None, refine="auto", echo=print):
    """Run the adaptive loop; returns the table rows (dicts).  `refine`: "split", "remesh"
    or "auto" (split if every body is VEM).  `lloyd`: Lloyd iterations of the remeshed
    cycles' meshes (default: the scene's)."""
    deck = Path(deck).resolve()
    if not deck.is_file():
        raise AdaptError(f"deck not found: {deck}")
    scene0 = load(scene_path)
    if scene0.get("variant"):
        raise AdaptError(f"{scene_path}: scenes with [[variant]] are not supported; keep one variant")
    if refine not in ("auto", "split", "remesh"):
        raise AdaptError(f"--refine must be split, remesh or auto, got {refine!r}")
    exe = find_executable(exe)
    which = mesh_include(deck, include)
    out_dir = Path(out_dir).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    scene = scene0
    pending = None
    echo(f"{'cycle':>5} {'cells':>8} {'unknowns':>9} {'rel. error':>10} {'estimate':>11} {'mesh s':>7} {'run s':>7}")
    for cycle in range(max_cycles + 1):
        cdir = out_dir / f"cycle_{cycle:02d}"
        cdir.mkdir(exist_ok=True)
        t0 = time.perf_counter()
        if pending is not None:
            try:
                m = split_cells(*pending)[0]      # the previous mesh, its marked cells split
            except MeshError as e:
                raise AdaptError(f"cycle {cycle}: splitting failed: {e}") from None
        else:
            try:
                m = build(scene, processes=processes)
            except MeshError as e:
                raise AdaptError(f"cycle {cycle}: meshing failed: {e}") from None
        if cycle == 0:
            fem = fem_bodies(m)
            if refine == "auto":
                refine = "remesh" if fem else "split"
            if refine == "split" and fem:
                raise AdaptError(f"{scene_path}: refinement by splitting needs VEM bodies (a FEM cell takes no "
                                 f"hanging node); FEM: {', '.join(fem)}; use --refine remesh or formulation = 'vem'")
            if refine == "remesh" and not voronoi_bodies(scene0):
                raise AdaptError(f"{scene_path}: no Voronoi body to remesh (structured bodies are not remeshed; "
                                 "with VEM bodies use --refine split)")
        how = "the scene meshed" if pending is None else "the marked cells of cycle {} split".format(cycle - 1)
        write_deck(m, cdir / "mesh.inp", [f"vemcontact mesh written by vctools.mesh (vc-adapt cycle {cycle})",
                                          f"scene: {scene_path}", how])
        t_mesh = time.perf_counter() - t0
        cdeck = write_cycle_deck(deck, which, cdir)
        t0 = time.perf_counter()
        r = subprocess.run([exe, "-q", str(cdeck), "-o", str(cdir)], capture_output=True, text=True)
        t_run = time.perf_counter() - t0
        if r.returncode != 0:
            raise AdaptError(f"cycle {cycle}: vemcontact failed (exit {r.returncode}), see {cdir / cdeck.stem}.log:\n"
                             + (r.stdout + r.stderr).strip())
        steps, x, off, conn = read_estimate(cdir / (cdeck.stem + ".h5"))
        worst = max(range(len(steps)), key=lambda k: steps[k][1])
        name, rel, est, en, eta = steps[worst]
        row = dict(cycle=cycle, cells=len(off) - 1, unknowns=2 * len(x), relative_error=rel, estimate=est,
                   step=name, mesh_s=t_mesh, run_s=t_run)
        rows.append(row)
        echo(f"{cycle:5d} {row['cells']:8d} {row['unknowns']:9d} {100 * rel:9.3f}% {est:11.4e} {t_mesh:7.2f} {t_run:7.2f}")
        _write_table(out_dir / "adapt.csv", rows)
        if rel <= target:
            echo(f"target {100 * target:g} % reached: {100 * rel:.3f} % with {row['unknowns']} unknowns ({cdir})")
            break
        cen, area = cell_geometry(x, off, conn)
        mark = np.ones(len(eta), bool) if uniform else doerfler(eta, theta)
        if refine == "split":
            # cells by their deck ids (write_deck: cell index + 1), not the HDF5 order
            cmark = np.zeros(m.ncell, bool)
            cmark[read_element_ids(cdir / (cdeck.stem + ".h5"))[mark] - 1] = True
            mark = cmark
        factor = np.where(mark, 4.0, 1.0)
        predicted = row["unknowns"] * factor.sum() / len(factor)
        if predicted > max_unknowns:
            echo(f"stopped: the next mesh would have about {predicted:.0f} unknowns, beyond the budget {max_unknowns}")
            break
        if cycle == max_cycles:
            echo(f"stopped after {max_cycles} cycles")
            break
        if refine == "split":
            pending = (m, mark)
            continue
        scene = refined_scene(scene0, cen, area, factor, cdir / "size.npz")
        if lloyd is not None:
            scene.setdefault("mesh", {})["lloyd"] = int(lloyd)
    return rows


def _write_table(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def _parser():
    p = argparse.ArgumentParser(prog="vc-adapt", description=__doc__.split("\n\n")[0] + ": refine where the "
                                "error estimate says, until a target error or a budget of unknowns.")
    p.add_argument("deck", help="the deck; its *INCLUDE of the scene's mesh is replaced in every cycle")
    p.add_argument("--scene", required=True, help="the scene (TOML) that makes the deck's mesh")
    p.add_argument("--target-error", default="1%", help="estimated relative energy error to reach (default 1%%)")
    p.add_argument("--max-unknowns", type=float, default=1e6, help="budget of unknowns (default 1e6)")
    p.add_argument("--max-cycles", type=int, default=10, help="refinement cycles at most (default 10)")
    p.add_argument("--theta", type=float, default=0.5, help="bulk (Doerfler) fraction of the squared estimate "
                   "the marked cells hold (default 0.5)")
    p.add_argument("--uniform", action="store_true", help="refine every cell (for comparison)")
    p.add_argument("--include", help="file name of the deck's mesh *INCLUDE (default: found)")
    p.add_argument("-o", "--output", help="output folder (default: DECK_adapt next to the deck)")
    p.add_argument("--exe", help="vemcontact executable (default: VEMCONTACT_EXE, PATH, the build tree)")
    p.add_argument("--processes", type=int, default=1, help="mesher worker processes (default 1)")
    p.add_argument("--refine", choices=("auto", "split", "remesh"), default="auto",
                   help="split the marked cells of the previous mesh (VEM only) or remesh the scene with a size "
                   "field; default: split if every body is VEM, else remesh")
    p.add_argument("--lloyd", type=int, help="Lloyd iterations of the remeshed meshes (default: the scene's [mesh] lloyd)")
    return p


@entry("vc-adapt")
def main(argv=None):
    a = _parser().parse_args(argv)
    try:
        if not (0.0 < a.theta <= 1.0):
            raise AdaptError(f"--theta must lie in (0, 1], got {a.theta}")
        out = a.output or str(Path(a.deck).with_suffix("")) + "_adapt"
        adapt(a.deck, a.scene, parse_fraction(a.target_error), out, max_unknowns=a.max_unknowns,
              max_cycles=a.max_cycles, theta=a.theta, uniform=a.uniform, exe=a.exe, include=a.include,
              processes=a.processes, lloyd=a.lloyd, refine=a.refine)
    except (AdaptError, MeshError) as e:
        print(f"vc-adapt: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
