"""Import of Gmsh .msh version 4.1 ASCII: triangles and quads; physical groups become sets.

Physical surfaces -> element sets (the first one of a cell names its body); physical curves
-> node sets and element-side surfaces; physical points -> node sets.
"""
from __future__ import annotations

import numpy as np

from .errors import MeshError
from .mesh import Mesh

CELL_TYPES = {2: 3, 3: 4}          # gmsh type -> nodes (3-node triangle, 4-node quad)
# second-order cells: gmsh type -> corners (6-node triangle, 8-node quad); gmsh lists the
# corners, then the side nodes in side order, as Abaqus does
CELL_TYPES2 = {9: 3, 16: 4}
LINE_TYPES = {1, 8}                 # 2- and 3-node lines (end, end[, middle])
OTHER_TYPES = {1: 2, 15: 1}        # 2-node line, 1-node point


def _sections(path):
    with open(path) as f:
        lines = [ln.strip() for ln in f]
    sec, cur, name = {}, None, None
    for k, ln in enumerate(lines):
        if ln.startswith("$End"):
            sec[name] = cur
            cur = None
        elif ln.startswith("$"):
            name, cur = ln[1:], []
        elif cur is not None:
            cur.append((k + 1, ln))
    return sec


def read_msh(path, etype="VPE", default_body="BODY"):
    sec = _sections(path)
    fmt = sec.get("MeshFormat")
    if not fmt:
        raise MeshError(f"{path}: not a Gmsh mesh (no $MeshFormat)")
    ver, ftype = fmt[0][1].split()[:2]
    if not ver.startswith("4.1") or ftype != "0":
        raise MeshError(f"{path}:{fmt[0][0]}: only Gmsh format 4.1 ASCII is read, got version {ver} "
                        f"{'binary' if ftype != '0' else 'ASCII'} (gmsh -format msh41)")
    names = {}
    for ln, text in (sec.get("PhysicalNames") or [])[1:]:
        parts = text.split(maxsplit=2)
        names[(int(parts[0]), int(parts[1]))] = parts[2].strip('"')
    phys = {}
    ent = sec.get("Entities")
    if ent:
        counts = list(map(int, ent[0][1].split()))
        k = 1
        for dim in range(4):
            for _ in range(counts[dim]):
                tok = ent[k][1].split()
                k += 1
                tag = int(tok[0])
                j = 4 if dim == 0 else 7
                n = int(tok[j])
                phys[(dim, tag)] = [int(t) for t in tok[j + 1:j + 1 + n]]
    nodes_sec = sec.get("Nodes")
    if not nodes_sec:
        raise MeshError(f"{path}: no $Nodes")
    tags, xyz = [], []
    it = iter(nodes_sec)
    nblocks = int(next(it)[1].split()[0])
    for _ in range(nblocks):
        ln, head = next(it)
        dim, etag, para, n = map(int, head.split())
        bt = [int(next(it)[1]) for _ in range(n)]
        for _ in range(n):
            ln, t = next(it)
            v = list(map(float, t.split()))
            xyz.append(v[:2])
        tags += bt
    tags = np.asarray(tags)
    xy = np.asarray(xyz, float).reshape(-1, 2)
    index = {t: i for i, t in enumerate(tags)}
    cells, cell_ent, lines_, line_ent, points, point_ent = [], [], [], [], [], []
    cell_sides = []
    it = iter(sec.get("Elements") or [])
    try:
        nblocks = int(next(it)[1].split()[0])
    except StopIteration:
        raise MeshError(f"{path}: no $Elements") from None
    for _ in range(nblocks):
        ln, head = next(it)
        dim, etag, typ, n = map(int, head.split())
        for _ in range(n):
            ln, t = next(it)
            v = [index[int(s)] for s in t.split()[1:]]
            if typ in CELL_TYPES:
                cells.append(v)
                cell_sides.append(None)
                cell_ent.append(etag)
            elif typ in CELL_TYPES2:
                nc = CELL_TYPES2[typ]
                cells.append(v[:nc])
                cell_sides.append(v[nc:2 * nc])
                cell_ent.append(etag)
            elif typ in LINE_TYPES:
                lines_.append(v)
                line_ent.append(etag)
            elif typ == 15:
                points.append(v[0])
                point_ent.append(etag)
            else:
                raise MeshError(f"{path}:{ln}: element type {typ} is not supported "
                                f"(3- and 6-node triangles, 4- and 8-node quads, lines and points are)")
    if not cells:
        raise MeshError(f"{path}: no triangles or quads")
    # bodies: first physical surface of each cell's entity
    body_of_ent, bodies = {}, []
    for e in sorted(set(cell_ent)):
        p = phys.get((2, e), [])
        name = names.get((2, p[0]), f"PHYS{p[0]}") if p else default_body
        if name not in bodies:
            bodies.append(name)
        body_of_ent[e] = bodies.index(name)
    conn = np.concatenate([np.asarray(c) for c in cells])
    ptr = np.concatenate([[0], np.cumsum([len(c) for c in cells])]).astype(np.int64)
    m = Mesh(xy, ptr, conn.astype(np.int64), np.array([body_of_ent[e] for e in cell_ent]),
             [(b, etype) for b in bodies])
    second = [sd is not None for sd in cell_sides]
    if any(second) and not all(second):
        raise MeshError(f"{path}: mixes first- and second-order cells; give one order")
    if all(second):
        m.side_nodes = np.concatenate([np.asarray(sd) for sd in cell_sides]).astype(np.int64)
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
    for e in set(cell_ent):
        for p in phys.get((2, e), [])[1:]:
            nm = names.get((2, p), f"PHYS{p}")
            sel = np.flatnonzero(np.asarray(cell_ent) == e)
            m.elsets[nm] = np.union1d(m.elsets.get(nm, np.zeros(0, int)), sel)
    # physical curves: node sets and element sides
    a, b, cell, side = m.edges()
    key = {}
    for i, (u, w) in enumerate(zip(a, b)):
        key[(min(u, w), max(u, w))] = i
    groups = {}
    for v, e in zip(lines_, line_ent):
        for p in phys.get((1, e), []):
            groups.setdefault(names.get((1, p), f"PHYS{p}"), []).append(v)
    for nm, segs in groups.items():
        nodes = np.unique(np.concatenate([np.asarray(sg) for sg in segs]))
        es = [key[(min(sg[0], sg[1]), max(sg[0], sg[1]))] for sg in segs
              if (min(sg[0], sg[1]), max(sg[0], sg[1])) in key]
        m.nsets[nm] = nodes
        if es:
            es = np.asarray(es)
            o = np.lexsort((side[es], cell[es]))
            m.esurfaces[nm] = (cell[es][o], side[es][o])
    for v, e in zip(points, point_ent):
        for p in phys.get((0, e), []):
            nm = names.get((0, p), f"PHYS{p}")
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
