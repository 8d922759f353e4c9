"""Import of Gmsh .msh files through meshio: formats 2.2 and 4.1, ASCII and binary.

Cells: 3-node triangles and 4-node quads, or (one order per file) 6-node triangles and
8-node quads, whose side nodes go to `Mesh.side_nodes`.  Physical groups become sets:
physical surfaces -> element sets (the first one of a cell names its body); physical
curves -> node sets and element-side surfaces; physical points -> node sets.
A file that cannot be read is a MeshError naming the file and the reason.
"""
from __future__ import annotations

import contextlib
import io
import warnings
from pathlib import Path

import numpy as np

from .errors import MeshError
from .mesh import Mesh

CELL_TYPES = {"triangle": 3, "quad": 4}
# second-order cells: meshio type -> corners (6-node triangle, 8-node quad); gmsh (and
# meshio) list the corners, then the side nodes in side order, as Abaqus does
CELL_TYPES2 = {"triangle6": 3, "quad8": 4}
LINE_TYPES = {"line", "line3"}      # 2- and 3-node lines (end, end[, middle])
DIM = {"vertex": 0, "line": 1, "line3": 1, "triangle": 2, "quad": 2, "triangle6": 2, "quad8": 2}


def _read(path):
    import meshio
    p = Path(path)
    if not p.is_file():
        raise MeshError(f"{path}: no such file")
    said = io.StringIO()
    try:
        # meshio prints its diagnosis and, for some bad files, calls sys.exit
        with warnings.catch_warnings(), contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            warnings.simplefilter("ignore")
            return meshio.read(p, file_format="gmsh")
    except (Exception, SystemExit) as exc:  # ReadError, ValueError, KeyError, ... on bad files
        what = " ".join((said.getvalue() + " " + str(exc if not isinstance(exc, SystemExit) else "")).split())
        raise MeshError(f"{path}: not a readable Gmsh mesh (2.2 or 4.1, ASCII or binary): "
                        f"{what or type(exc).__name__}") from None


def _group_names(mesh, i, block):
    """The physical group names of each cell of block i (a list of lists)."""
    dim = DIM[block.type]
    names = [[] for _ in range(len(block.data))]
    by_tag = {int(v[0]): k for k, v in mesh.field_data.items() if len(v) > 1 and int(v[1]) == dim}
    sets = {k: v for k, v in (mesh.cell_sets or {}).items()
            if k in mesh.field_data and int(mesh.field_data[k][1]) == dim}
    if any(v[i] is not None and len(v[i]) for v in sets.values()):
        # format 4.1: meshio lists every physical group of the cell's entity
        for k, v in sets.items():
            if v[i] is not None:
                for c in np.asarray(v[i], int):
                    names[c].append(k)
        return names
    phys = mesh.cell_data.get("gmsh:physical")
    if phys is not None and i < len(phys):
        for c, t in enumerate(np.asarray(phys[i], int)):
            if t > 0:
                names[c].append(by_tag.get(int(t), f"PHYS{int(t)}"))
    return names


def read_msh(path, etype="VPE", default_body="BODY"):
    mesh = _read(path)
    if len(mesh.points) == 0 or not mesh.cells:
        raise MeshError(f"{path}: no nodes or elements (an empty or truncated Gmsh mesh)")
    xy = np.asarray(mesh.points, float)[:, :2]
    cells, cell_groups, lines, line_groups, points, point_groups = [], [], [], [], [], []
    cell_sides = []
    seen = {}
    for i, block in enumerate(mesh.cells):
        if block.type not in DIM:
            raise MeshError(f"{path}: element type {block.type!r} is not supported "
                            f"(3- and 6-node triangles, 4- and 8-node quads, lines and points are)")
        groups = _group_names(mesh, i, block)
        for c, g in zip(np.asarray(block.data, int), groups):
            if block.type in CELL_TYPES or block.type in CELL_TYPES2:
                # format 2.2 repeats a cell once per physical group: merge them
                key = tuple(sorted(c.tolist()))
                if key in seen:
                    for n in g:
                        if n not in cell_groups[seen[key]]:
                            cell_groups[seen[key]].append(n)
                    continue
                seen[key] = len(cells)
                nc = CELL_TYPES2.get(block.type, len(c))
                cells.append(c[:nc])
                cell_sides.append(c[nc:2 * nc] if block.type in CELL_TYPES2 else None)
                cell_groups.append(list(g))
            elif block.type in LINE_TYPES:
                lines.append(c)
                line_groups.append(g)
            else:
                points.append(int(c[0]))
                point_groups.append(g)
    if not cells:
        raise MeshError(f"{path}: no triangles or quads")
    bodies = []
    for g in cell_groups:
        name = g[0] if g else default_body
        if name not in bodies:
            bodies.append(name)
    body = np.array([bodies.index(g[0] if g else default_body) for g in cell_groups])
    conn = np.concatenate(cells)
    ptr = np.concatenate([[0], np.cumsum([len(c) for c in cells])]).astype(np.int64)
    m = Mesh(xy, ptr, conn.astype(np.int64), body, [(b, etype) for b in bodies])
    second = [sd is not None for sd in cell_sides]
    if any(second) and not all(second):
        raise MeshError(f"{path}: mixes first- and second-order cells; give one order")
    if all(second):
        m.side_nodes = np.concatenate(cell_sides).astype(np.int64)
    # counter-clockwise cells; reversed corners c_(n-1) .. c_0 have as side j the
    # original side n-2-j (mod n)
    area = m.cell_areas()
    for c in np.flatnonzero(area < 0):
        m.conn[m.ptr[c]:m.ptr[c + 1]] = m.conn[m.ptr[c]:m.ptr[c + 1]][::-1].copy()
        if m.side_nodes is not None:
            n = m.ptr[c + 1] - m.ptr[c]
            sd = m.side_nodes[m.ptr[c]:m.ptr[c + 1]].copy()
            m.side_nodes[m.ptr[c]:m.ptr[c + 1]] = sd[(n - 2 - np.arange(n)) % n]
    # extra element sets: further physical surfaces
    for c, g in enumerate(cell_groups):
        for nm in g[1:]:
            m.elsets[nm] = np.union1d(m.elsets.get(nm, np.zeros(0, int)), [c])
    # physical curves: node sets and element sides
    a, b, cell, side = m.edges()
    key = {(min(u, w), max(u, w)): i for i, (u, w) in enumerate(zip(a, b))}
    groups = {}
    for v, g in zip(lines, line_groups):
        for nm in g:
            groups.setdefault(nm, []).append(v)
    for nm, segs in groups.items():
        # every node of the curve, middle nodes of 3-node lines included
        nodes = np.unique(np.concatenate(segs))
        ends = [(min(sg[0], sg[1]), max(sg[0], sg[1])) for sg in segs]
        es = [key[k] for k in ends if k in key]
        m.nsets[nm] = nodes
        if es:
            es = np.asarray(es)
            o = np.lexsort((side[es], cell[es]))
            m.esurfaces[nm] = (cell[es][o], side[es][o])
    for v, g in zip(points, point_groups):
        for nm in g:
            m.nsets[nm] = np.union1d(m.nsets.get(nm, np.zeros(0, int)), [v])
    # drop nodes used by nothing (gmsh keeps geometry points)
    used = np.zeros(len(m.nodes), bool)
    used[m.conn] = True
    if m.side_nodes is not None:
        used[m.side_nodes] = True
    for v in m.nsets.values():
        used[v] = True
    new = np.cumsum(used) - 1
    m.nodes = m.nodes[used]
    m.conn = new[m.conn]
    if m.side_nodes is not None:
        m.side_nodes = new[m.side_nodes]
    m.nsets = {k: new[v] for k, v in m.nsets.items()}
    return m
