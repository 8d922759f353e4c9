"""Scene files (TOML) -> meshes.  See docs/meshing.md for the format."""
from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import numpy as np

from .deck import element_type, write_deck
from .errors import MeshError
from .geometry import as_points, check_simple_polygon, diameter
from .mesh import add_side_nodes, add_side_nodes_to_sets, concatenate, spatial_order
from .polymesh import Joint, VBody, voronoi_group
from .quality import report_lines
from .select import add_contact, add_selection
from .sizing import Grading
from . import structured

MESH_KEYS = {"seed", "lloyd", "formulation", "plane", "title", "tile", "order"}
BODY_KEYS = {"name", "polygon", "rectangle", "half_disc", "cantilever", "mesher", "cells", "divisions",
             "grading", "group", "formulation", "plane", "seed"}


def load(path):
    with open(path, "rb") as f:
        try:
            return tomllib.load(f)
        except tomllib.TOMLDecodeError as exc:
            raise MeshError(f"{path}: {exc}") from exc


def variants(scene):
    """[(suffix, scene)] for the scene's [[variant]] tables (or the scene itself)."""
    vs = scene.get("variant")
    if not vs:
        return [("", scene)]
    out = []
    for k, v in enumerate(vs):
        if "name" not in v:
            raise MeshError(f"variant {k + 1}: needs a name")
        s = copy.deepcopy({key: val for key, val in scene.items() if key != "variant"})
        for dotted, value in v.get("set", {}).items():
            _set(s, dotted, value, f"variant {v['name']!r}")
        out.append((str(v["name"]), s))
    return out


def _set(tree, dotted, value, where):
    parts = dotted.split(".")
    node = tree
    for p in parts[:-1]:
        if isinstance(node, list):
            try:
                node = node[int(p)]
            except (ValueError, IndexError) as exc:
                raise MeshError(f"{where}: bad path {dotted!r}") from exc
        else:
            node = node.setdefault(p, {})
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


class FemType:
    """FEM element type chosen by the number of nodes of a cell (CPE3/CPE4, CPS3/CPS4)."""

    def __init__(self, plane, where):
        element_type("fem", plane, 4, where)      # validates the names
        self.plane, self.where = plane, where

    def __call__(self, n):
        return element_type("fem", self.plane, n, self.where)

    def __str__(self):
        return f"{self(3)}/{self(4)}"


def _etype(formulation, plane, where):
    if formulation == "vem":
        return element_type("vem", plane, 0, where)
    if formulation != "fem":
        raise MeshError(f"{where}: formulation must be 'vem' or 'fem', got {formulation!r}")
    return FemType(plane, where)


def build(scene, seed=None, verbose=False, processes=None):
    """Mesh of a scene dictionary."""
    unknown = set(scene) - {"mesh", "body", "joint", "selection", "contact", "variant"}
    if unknown:
        raise MeshError(f"scene: unknown tables {sorted(unknown)}")
    opts = scene.get("mesh", {})
    bad = set(opts) - MESH_KEYS
    if bad:
        raise MeshError(f"[mesh]: unknown keys {sorted(bad)}")
    seed = int(opts.get("seed", 0) if seed is None else seed)
    lloyd = int(opts.get("lloyd", 20))
    bodies = scene.get("body", [])
    if not bodies:
        raise MeshError("scene: no [[body]]")
    groups = {}
    meshes = []
    order = []
    arcs = []     # (center, radius) of the circular boundaries, for second-order FEM sides
    arc_bodies = []   # (body name, center, radius): m.info["arcs"], for refinement by splitting
    for k, b in enumerate(bodies):
        name = b.get("name")
        if not name:
            raise MeshError(f"body {k + 1}: needs a name")
        where = f"body {name!r}"
        bad = set(b) - BODY_KEYS
        if bad:
            raise MeshError(f"{where}: unknown keys {sorted(bad)}")
        form = b.get("formulation", opts.get("formulation", "vem"))
        plane = b.get("plane", opts.get("plane", "strain"))
        et = _etype(form, plane, where)
        shapes = [s for s in ("polygon", "rectangle", "half_disc", "cantilever") if s in b]
        if len(shapes) != 1:
            raise MeshError(f"{where}: give exactly one of polygon, rectangle, half_disc, cantilever")
        shape = shapes[0]
        mesher = b.get("mesher", "voronoi" if shape in ("polygon",) else "quad")
        if shape == "rectangle" and mesher == "voronoi":
            x0, y0, x1, y1 = map(float, b["rectangle"])
            poly = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
            shape = "polygon"
        else:
            poly = b.get("polygon")
        if shape == "polygon":
            if mesher != "voronoi":
                raise MeshError(f"{where}: polygons are meshed with mesher = 'voronoi'")
            if "cells" not in b:
                raise MeshError(f"{where}: needs 'cells' (target number of cells)")
            P = check_simple_polygon(as_points(poly, where), name)
            gr = b.get("grading", [])
            gr = [gr] if isinstance(gr, dict) else gr
            vb = VBody(name, P, b["cells"], Grading(gr, where), et)
            g = b.get("group", f"__{name}")
            if g not in groups:
                groups[g] = []
                order.append(("group", g))
            groups[g].append(vb)
            continue
        if mesher not in ("quad", "tri"):
            raise MeshError(f"{where}: mesher must be 'quad' or 'tri' for a {shape}, got {mesher!r}")
        gr = b.get("grading", {}) or {}
        if isinstance(gr, list):
            gr = gr[0] if gr else {}
        if shape == "rectangle":
            m = structured.rectangle(name, b["rectangle"], b.get("divisions", [10, 10]), mesher, et,
                                     gr.get("point"), float(gr.get("ratio", 1.0)))
        elif shape == "half_disc":
            hd = b["half_disc"]
            arcs.append((hd.get("center", [0, 0]), float(hd["radius"])))
            arc_bodies.append((name, list(hd.get("center", [0, 0])), float(hd["radius"])))
            m = structured.half_disc(name, hd.get("center", [0, 0]), hd["radius"], b.get("divisions", [4, 4, 4]),
                                     mesher, et, float(gr.get("ratio", 1.0)), float(gr.get("radial_ratio", 1.0)),
                                     float(hd.get("core", 0.5)))
        else:
            c = b["cantilever"]
            if mesher != "quad":
                raise MeshError(f"{where}: the cantilever is two quads")
            m = structured.cantilever(name, c.get("length", 40.0), c.get("height", 8.0), c.get("distortion", 0.0), et)
        order.append(("mesh", m))
    joints_by_group = {g: [] for g in groups}
    for k, j in enumerate(scene.get("joint", [])):
        name = j.get("name") or f"JOINT{k + 1}"
        pl = as_points(j.get("polyline"), f"joint {name!r}")
        jt = Joint(name, pl, j.get("master", "right"))
        # the group whose region holds the joint
        import shapely
        ls = shapely.LineString(pl)
        hit = [g for g, bs in groups.items()
               if shapely.unary_union([shapely.Polygon(x.polygon) for x in bs]).buffer(1e-9 * diameter(pl)).intersects(ls)]
        if not hit:
            raise MeshError(f"joint {name!r} leaves its body: it lies in no Voronoi body")
        if len(hit) > 1:
            raise MeshError(f"joint {name!r} runs through unbonded bodies {hit}; bond them (same group)")
        joints_by_group[hit[0]].append(jt)
    # joints crossing each other
    js = [j for g in joints_by_group.values() for j in g]
    for i in range(len(js)):
        for k in range(i + 1, len(js)):
            import shapely
            a, b2 = shapely.LineString(js[i].polyline), shapely.LineString(js[k].polyline)
            x = a.intersection(b2)
            if not x.is_empty:
                ends = shapely.MultiPoint([js[i].polyline[0], js[i].polyline[-1], js[k].polyline[0], js[k].polyline[-1]])
                if x.length > 0 or not ends.buffer(1e-9 * diameter(js[i].polyline)).covers(x):
                    raise MeshError(f"joints {js[i].name!r} and {js[k].name!r} cross at "
                                    f"{np.round(shapely.get_coordinates(x)[0], 12).tolist()}")
    gi = 0
    for kind, item in order:
        if kind == "mesh":
            meshes.append(item)
        else:
            meshes.append(voronoi_group(groups[item], joints_by_group[item], seed=seed + 1000 * gi, lloyd=lloyd,
                                        per_tile=int(opts.get("tile", 4000)), processes=processes, verbose=verbose))
            gi += 1
    m = concatenate(meshes)
    m.info["arcs"] = arc_bodies
    counts = np.diff(m.ptr)
    for k, (bname, et) in enumerate(m.bodies):
        if isinstance(et, FemType):
            big = counts[m.cell_body == k]
            if len(big) and big.max() > 4:
                raise MeshError(f"body {bname!r}: FEM elements are triangles and quads; its cells have up to "
                                f"{big.max()} nodes (use formulation = 'vem')")
    elem_order = opts.get("order", 1)
    if elem_order not in (1, 2):
        raise MeshError(f"[mesh]: order must be 1 or 2, got {elem_order!r}")
    if elem_order == 2:
        add_side_nodes(m, arcs)
    size = diameter(m.nodes)
    tol = 1e-8 * size
    for k, s in enumerate(scene.get("selection", [])):
        add_selection(m, s.get("name") or f"SEL{k + 1}", {kk: v for kk, v in s.items() if kk != "name"}, tol)
    for k, c in enumerate(scene.get("contact", [])):
        add_contact(m, c.get("name") or f"CONTACT{k + 1}", c, tol)
    add_side_nodes_to_sets(m)
    # nodes and cells numbered along a Hilbert curve: cache-friendly assembly
    spatial_order(m)
    m.info["title"] = opts.get("title", "")
    m.info["seed"] = seed
    return m


def header(m, source=None):
    lines = ["vemcontact mesh written by vctools.mesh (vc-mesh)"]
    if source:
        lines.append(f"scene: {source}")
    if m.info.get("title"):
        lines.append(str(m.info["title"]))
    lines.append(f"seed: {m.info.get('seed', 0)}")
    lines.append("quality report:")
    lines += ["  " + s for s in report_lines(m)]
    names = []
    for k, v in (("node sets", m.nsets), ("element surfaces", m.esurfaces), ("node surfaces", m.nsurfaces)):
        if v:
            names.append(f"{k}: {', '.join(v)}")
    lines += names
    return lines


def mesh_scene_file(path, out=None, seed=None, verbose=False, processes=None, echo=print):
    """Mesh every variant of a scene file; returns [(output path, mesh)]."""
    path = Path(path)
    scene = load(path)
    results = []
    for suffix, s in variants(scene):
        m = build(s, seed=seed, verbose=verbose, processes=processes)
        if out is None:
            target = path.with_suffix("").as_posix() + (f"_{suffix}" if suffix else "") + ".inp"
        else:
            out = Path(out)
            if out.suffix == ".inp" and not suffix:
                target = out.as_posix()
            elif out.suffix == ".inp":
                target = out.with_suffix("").as_posix() + f"_{suffix}.inp"
            else:
                target = (out / (path.stem + (f"_{suffix}" if suffix else "") + ".inp")).as_posix()
        Path(target).parent.mkdir(parents=True, exist_ok=True)
        hdr = header(m, path.name + (f" [variant {suffix}]" if suffix else ""))
        write_deck(m, target, hdr)
        if echo:
            echo(f"{target}:")
            for line in hdr[3:]:
                echo("  " + line)
        results.append((target, m))
    return results
