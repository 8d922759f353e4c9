"""Import of Gmsh .msh files through meshio: formats 2.2 and 4.1, ASCII and binary.

Cells: 3-node triangles and 4-node quads.  Physical groups become sets:
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
DIM = {"vertex": 0, "line": 1, "triangle": 2, "quad": 2}


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
    seen = {}
    for i, block in enumerate(mesh.cells):
        if block.type not in DIM:
            raise MeshError(f"{path}: element type {block.type!r} is not supported "
                            f"(3-node triangles, 4-node quads, lines and points are)")
        groups = _group_names(mesh, i, block)
        for c, g in zip(np.asarray(block.data, int), groups):
            if block.type in CELL_TYPES:
                # format 2.2 repeats a cell once per physical group: merge them
                key = tuple(sorted(c.tolist()))
                if key in seen:
                    for n in g:
                        if n not in cell_groups[seen[key]]:
                            cell_groups[seen[key]].append(n)
                    continue
                seen[key] = len(cells)
                cells.append(c)
                cell_groups.append(list(g))
            elif block.type == "line":
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
    # counter-clockwise cells
    area = m.cell_areas()
    for c in np.flatnonzero(area < 0):
        m.conn[m.ptr[c]:m.ptr[c + 1]] = m.conn[m.ptr[c]:m.ptr[c + 1]][::-1].copy()
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
            groups.setdefault(nm, []).append(v[:2])
    for nm, segs in groups.items():
        nodes = np.unique(np.asarray(segs).ravel())
        es = [key[(min(u, w), max(u, w))] for u, w in segs if (min(u, w), max(u, w)) in key]
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
    for v in m.nsets.values():
        used[v] = True
    new = np.cumsum(used) - 1
    m.nodes = m.nodes[used]
    m.conn = new[m.conn]
    m.nsets = {k: new[v] for k, v in m.nsets.items()}
    return m
