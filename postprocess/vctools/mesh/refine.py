"""Local refinement of a mesh by splitting marked cells (no remeshing).

A marked cell is split at its geometric corners: the vertices where its boundary turns
(a vertex on a straight run between two corners, a hanging node left by an earlier split of
a neighbour, is no corner; of two corners closer than SHORT times the cell's longest side
the one that turns less is dropped, so that a short side does not make a sliver child).
Each geometric side gets a split point: the vertex already on it nearest to its middle if
one lies within a quarter of the side from it (the neighbour's earlier midpoint), else a new
node at the middle of the mesh edge there, shared with the cell on the other side of that
edge.  The cell becomes one quadrilateral per corner: split point before the corner, the corner (and
the hanging nodes between), split point after it, and the centre, the mean of the corners
(for a quadrilateral the centre of its bilinear map, so a quadrilateral splits into the
images of the four sub-squares and the children stay as regular as their parent over
repeated cycles; a Voronoi n-gon gives n quadrilaterals in the first cycle, then
quadrilaterals split into four).  If the mean of the corners is not strictly inside the
cell's kernel (a non-convex cell), the centre is the point of the kernel farthest from the
sides (linear program).

The virtual element needs nothing at a hanging node: a new middle node on a side of an
unmarked neighbour becomes one more vertex of that neighbour.  A FEM cell cannot take one,
so cells of FEM bodies are neither split nor given hanging nodes: refine() refuses them.

What survives, with new indices:
- joints: the two faces of a joint have different (duplicated) nodes, so their edges get
  different middle nodes: a split joint edge stays a joint edge; an edge split on one face
  is split on the other too (the faces keep matching nodes);
- node sets and node surfaces: a new middle node joins every set that holds both ends of
  its edge; on a joint's slave face also when the other end is the joint's tip (shared,
  not in the slave set);
- element sets: the children of a cell inherit its sets (and its body);
- element-face surfaces: a face (cell, side) becomes the faces of the children (or of the
  refined cell) on the two halves of its edge;
- curved boundaries: a new middle node of a boundary edge whose ends lie on one of the
  mesh's arcs (m.info["arcs"], (body name, centre, radius) from the scene's half discs) is
  placed on the circle.
"""
from __future__ import annotations

import bisect
import copy
import math

import numpy as np

from .errors import MeshError
from .mesh import Mesh

# a vertex is a hanging node (no corner) when its two sides turn by less than this (rad)
STRAIGHT = 1e-7
# a side between corners shorter than this fraction of the cell's longest is merged away
SHORT = 0.3


def _is_fem(etype):
    return callable(etype) or str(etype).upper().startswith("C")


def corners(P, straight=STRAIGHT, short=SHORT):
    """Boolean mask of the geometric corners of a polygon P (n, 2), counter-clockwise: the
    vertices where the boundary turns by more than `straight` (rad); at least three, the
    ones that turn most; and no side between corners shorter than `short` times the longest
    (module docstring)."""
    nxt = np.r_[1:len(P), 0]
    b = P[nxt] - P
    a = b[np.r_[len(P) - 1, 0:len(P) - 1]]
    turn = np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1)))
    mask = turn > straight
    if mask.sum() < 3:
        mask[np.argsort(-turn, kind="stable")[:3]] = True
    if short > 0:
        # a side between two corners much shorter than the longest is no side: of its two
        # corners the one that turns less becomes a vertex on a bent side
        while mask.sum() > 3:
            ic = np.flatnonzero(mask)
            Q = P[ic]
            L = np.hypot(*(Q[np.r_[1:len(Q), 0]] - Q).T)
            j = int(np.argmin(L))
            if L[j] >= short * L.max():
                break
            i0, i1 = ic[j], ic[(j + 1) % len(ic)]
            mask[i0 if turn[i0] < turn[i1] else i1] = False
    return mask


def _in_kernel(P, c, eps=1e-9):
    e = P[np.r_[1:len(P), 0]] - P
    d = c - P
    cr = e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]
    return bool((cr > eps * np.hypot(*e.T) * np.ptp(P, axis=0).max()).all())


def _corner_list(xs, ys, turn, straight=STRAIGHT, short=SHORT):
    """corners() on plain lists (the vertex turns given): sorted corner positions."""
    n = len(xs)
    ic = [i for i in range(n) if turn[i] > straight]
    if len(ic) < 3:
        ic = sorted(sorted(range(n), key=lambda i: -turn[i])[:3])
    while short > 0 and len(ic) > 3:
        k = len(ic)
        L = [math.hypot(xs[ic[(j + 1) % k]] - xs[ic[j]], ys[ic[(j + 1) % k]] - ys[ic[j]]) for j in range(k)]
        j = min(range(k), key=L.__getitem__)
        if L[j] >= short * max(L):
            break
        i0, i1 = ic[j], ic[(j + 1) % k]
        ic.remove(i0 if turn[i0] < turn[i1] else i1)
    return ic


def _in_kernel_list(xs, ys, cx, cy, eps=1e-9):
    """_in_kernel on plain lists."""
    n = len(xs)
    ext = max(max(xs) - min(xs), max(ys) - min(ys))
    for k in range(n):
        ex, ey = xs[(k + 1) % n] - xs[k], ys[(k + 1) % n] - ys[k]
        if ex * (cy - ys[k]) - ey * (cx - xs[k]) <= eps * math.hypot(ex, ey) * ext:
            return False
    return True


def _kernel_center(P, where):
    """The point of the polygon's kernel farthest from its side lines (Chebyshev centre)."""
    from scipy.optimize import linprog
    e = np.roll(P, -1, axis=0) - P
    L = np.hypot(*e.T)
    keep = L > 0
    n = np.column_stack([-e[keep, 1], e[keep, 0]]) / L[keep, None]     # inward normals (CCW)
    # n . (c - p) >= r  <=>  -n . c + r <= -n . p
    A = np.column_stack([-n, np.ones(len(n))])
    res = linprog([0, 0, -1], A_ub=A, b_ub=-(n * P[keep]).sum(1), bounds=[(None, None)] * 2 + [(0, None)])
    if not res.success or res.x[2] <= 0:
        raise MeshError(f"{where}: the cell is not star-shaped; it cannot be split")
    return res.x[:2]


def _arc_of(m):
    """Per body index: [(centre, radius)] of its arcs."""
    names = [b[0] for b in m.bodies]
    out = {}
    for body, c, r in m.info.get("arcs", []):
        if body in names:
            out.setdefault(names.index(body), []).append((np.asarray(c, float), float(r)))
    return out


def refine(m, marked):
    """The mesh with the marked cells split (module docstring); returns (new mesh, parent),
    parent[i] the index of new cell i's cell in `m`.  `m` is not changed."""
    if m.side_nodes is not None:
        raise MeshError("refinement by splitting works on first-order meshes only")
    marked = np.asarray(marked, bool)
    if marked.shape != (m.ncell,):
        raise MeshError(f"refine: {len(marked)} marks for {m.ncell} cells")
    n0 = len(m.nodes)
    nxt = m.next_index()
    a, b = m.conn, m.conn[nxt]
    ekey = np.minimum(a, b).astype(np.int64) * (n0 + 1) + np.maximum(a, b)
    uk, inv, cnt = np.unique(ekey, return_inverse=True, return_counts=True)
    boundary = (cnt == 1)[inv]
    size = np.ptp(m.nodes, axis=0).max() if n0 else 1.0
    tol = 1e-9 * size
    arcs = _arc_of(m)
    new_xy = []
    mid = {}            # edge key -> new node
    mid_edge = []       # (u, w, boundary) of each new node

    def midpoint(pos):
        k = int(ekey[pos])
        if k in mid:
            return mid[k]
        u, w = int(a[pos]), int(b[pos])
        p = 0.5 * (m.nodes[u] + m.nodes[w])
        if boundary[pos]:
            for c, r in arcs.get(int(m.cell_body[cell_of[pos]]), ()):
                du, dw = np.hypot(*(m.nodes[u] - c)), np.hypot(*(m.nodes[w] - c))
                L = np.hypot(*(m.nodes[w] - m.nodes[u]))
                if abs(du - r) <= tol and abs(dw - r) <= tol and L < r:
                    p = c + r * (p - c) / np.hypot(*(p - c))
        mid[k] = n0 + len(new_xy)
        new_xy.append(p)
        mid_edge.append((u, w, bool(boundary[pos])))
        return mid[k]

    cell_of = m.cell_index()
    fem = [k for k, (_, et) in enumerate(m.bodies) if _is_fem(et)]
    is_fem = np.isin(m.cell_body, fem)
    if fem and marked[is_fem].any():
        k = int(m.cell_body[np.flatnonzero(marked & is_fem)[0]])
        raise MeshError(f"body {m.bodies[k][0]!r} is FEM: its cells cannot be split (a FEM cell takes no "
                        f"hanging node); use formulation = 'vem' or refinement by remeshing")
    # plain Python lists in the per-cell loops (small polygons: numpy per cell is slower)
    X, Y = m.nodes[:, 0].tolist(), m.nodes[:, 1].tolist()
    conn_l, ptr_l = m.conn.tolist(), m.ptr.tolist()
    P = m.nodes[m.conn]
    e_out = P[nxt] - P
    e_in = np.empty_like(e_out)
    e_in[nxt] = e_out
    turn_l = np.abs(np.arctan2(e_in[:, 0] * e_out[:, 1] - e_in[:, 1] * e_out[:, 0],
                               (e_in * e_out).sum(1))).tolist()
    # pass 1: split points of the marked cells' geometric sides (new middle nodes where needed)
    split = {}
    for c in np.flatnonzero(marked).tolist():
        s, e = ptr_l[c], ptr_l[c + 1]
        n = e - s
        v = conn_l[s:e]
        ic = _corner_list([X[q] for q in v], [Y[q] for q in v], turn_l[s:e])
        sp = []
        for j in range(len(ic)):
            i0, i1 = ic[j], ic[(j + 1) % len(ic)]
            inner = [(i0 + t) % n for t in range(1, (i1 - i0) % n)]
            x0, y0, x1, y1 = X[v[i0]], Y[v[i0]], X[v[i1]], Y[v[i1]]
            gx, gy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            half = 0.5 * math.hypot(x1 - x0, y1 - y0)
            best = min(inner, key=lambda q: math.hypot(X[v[q]] - gx, Y[v[q]] - gy)) if inner else None
            if best is not None and math.hypot(X[v[best]] - gx, Y[v[best]] - gy) <= 0.25 * half:
                sp.append(("old", best))
            else:
                # no vertex near the middle: a new node at the middle of the edge that holds it
                run = [i0] + inner
                t = [(X[v[q]] - x0) * (x1 - x0) + (Y[v[q]] - y0) * (y1 - y0) for q in run] + [4 * half * half]
                q = run[bisect.bisect_left(t, 2 * half * half) - 1]
                sp.append(("new", midpoint(s + q)))
        split[c] = (ic, sp)
    # the two faces of a joint are split together: a boundary edge with the same end points
    # as an edge that got a middle node (its twin across the joint) gets one too, so the
    # faces keep matching nodes (a slave face coarser than its master lets the master's new
    # nodes pass through it)
    bpos = np.flatnonzero(boundary).tolist()
    twins = {}
    for pos in bpos:
        pa, pb = (X[a[pos]], Y[a[pos]]), (X[b[pos]], Y[b[pos]])
        twins.setdefault((min(pa, pb), max(pa, pb)), []).append(pos)
    for pos in bpos:
        if int(ekey[pos]) in mid:
            pa, pb = (X[a[pos]], Y[a[pos]]), (X[b[pos]], Y[b[pos]])
            for q in twins[(min(pa, pb), max(pa, pb))]:
                midpoint(q)
    # pass 2: every cell's vertices with the new middle nodes of its edges (vectorized)
    new_nodes = np.vstack([m.nodes, np.asarray(new_xy).reshape(-1, 2)])
    has = np.zeros(len(ekey), bool)
    mid_at = np.zeros(len(ekey), np.int64)
    if mid:
        ks = np.fromiter(mid.keys(), np.int64, len(mid))
        vs = np.fromiter(mid.values(), np.int64, len(mid))
        o = np.argsort(ks)
        ks, vs = ks[o], vs[o]
        i = np.minimum(np.searchsorted(ks, ekey), len(ks) - 1)
        has = ks[i] == ekey
        mid_at = vs[i]
    bad = np.flatnonzero(has & is_fem[cell_of])
    if len(bad):
        c = int(cell_of[bad[0]])
        raise MeshError(f"body {m.bodies[int(m.cell_body[c])][0]!r} is FEM: cell {c + 1} would take a "
                        f"hanging node next to a split cell; use formulation = 'vem' or refinement by remeshing")
    lens = 1 + has.astype(np.int64)
    first = np.cumsum(lens) - lens             # position in augc of each old vertex
    augc = np.empty(int(lens.sum()), np.int64)
    augc[first] = m.conn
    augc[first[has] + 1] = mid_at[has]
    aptr = np.concatenate([[0], np.cumsum(np.add.reduceat(lens, m.ptr[:-1]))]) if m.ncell else np.zeros(1, np.int64)
    augl, aptr_l, first_l = augc.tolist(), aptr.tolist(), first.tolist()
    XN, YN = new_nodes[:, 0].tolist(), new_nodes[:, 1].tolist()
    centres = []
    parts, parent = [], []
    marked_l = marked.tolist()
    nn = len(new_nodes)
    for c in range(m.ncell):
        a0, a1 = aptr_l[c], aptr_l[c + 1]
        if not marked_l[c]:
            parts.append(augc[a0:a1])
            parent.append(c)
            continue
        s = ptr_l[c]
        aug = augl[a0:a1]
        ic, sp = split[c]
        cut = [first_l[s + v] - a0 if kind == "old" else aug.index(v) for kind, v in sp]
        cx = sum(X[conn_l[s + i]] for i in ic) / len(ic)
        cy = sum(Y[conn_l[s + i]] for i in ic) / len(ic)
        if not _in_kernel_list([XN[q] for q in aug], [YN[q] for q in aug], cx, cy):
            cx, cy = _kernel_center(new_nodes[aug], f"cell {c + 1}")
        ci = nn + len(centres)
        centres.append((cx, cy))
        na = len(aug)
        for j in range(len(ic)):
            p0, p1 = cut[j - 1], cut[j]
            parts.append(np.array([aug[(p0 + t) % na] for t in range((p1 - p0) % na + 1)] + [ci], np.int64))
            parent.append(c)
    parent = np.asarray(parent, np.int64)
    new_nodes = np.vstack([new_nodes, np.asarray(centres, float).reshape(-1, 2)])
    ptr = np.concatenate([[0], np.cumsum([len(q) for q in parts])]).astype(np.int64)
    out = Mesh(new_nodes, ptr, np.concatenate(parts) if parts else np.zeros(0, np.int64),
               m.cell_body[parent].copy(), list(m.bodies), info=copy.deepcopy(m.info))
    _carry_sets(m, out, parent, mid, mid_edge)
    return out, parent


def _carry_sets(m, out, parent, mid, mid_edge):
    """Node sets, node surfaces, element sets and element-face surfaces of `m` on `out`."""
    shared = np.zeros(len(out.nodes), bool)
    slave_sets = set()
    for j in m.info.get("joints", []):
        shared[np.asarray(j.get("shared", []), np.int64)] = True
        slave_sets.add(f"{j['name']}_SLAVE")
    ue = np.array([(u, w) for u, w, _ in mid_edge], np.int64).reshape(-1, 2)
    bnd = np.array([bd for _, _, bd in mid_edge], bool)
    newid = np.arange(len(m.nodes), len(m.nodes) + len(mid_edge))
    for src, dst in ((m.nsets, out.nsets), (m.nsurfaces, out.nsurfaces)):
        for name, nodes in src.items():
            nodes = np.asarray(nodes, np.int64)
            ins = np.zeros(len(out.nodes), bool)
            ins[nodes] = True
            join = ins[ue[:, 0]] & ins[ue[:, 1]]
            if name in slave_sets:
                join |= bnd & ((ins[ue[:, 0]] & shared[ue[:, 1]]) | (shared[ue[:, 0]] & ins[ue[:, 1]]))
            dst[name] = np.union1d(nodes, newid[join])
    children = {}
    for i, p in enumerate(parent):
        children.setdefault(int(p), []).append(i)
    for name, cells in m.elsets.items():
        out.elsets[name] = np.asarray(sorted(i for c in np.asarray(cells) for i in children[int(c)]), np.int64)
    # directed edges of the new cells whose parents hold a face of a surface -> (cell, side)
    a, b, cell, side = out.edges()
    faces = np.concatenate([np.asarray(c, np.int64) for c, _ in m.esurfaces.values()] + [np.zeros(0, np.int64)])
    keep = np.isin(parent[cell], faces)
    where = {}
    for u, w, c, s in zip(a[keep].tolist(), b[keep].tolist(), cell[keep].tolist(), side[keep].tolist()):
        where.setdefault((u, w), []).append((c, s))
    n0 = len(m.nodes)
    for name, (cells, sides) in m.esurfaces.items():
        nc, ns = [], []
        for c, s in zip(np.asarray(cells).tolist(), np.asarray(sides).tolist()):
            cc = m.cell(c)
            u, w = int(cc[s - 1]), int(cc[s % len(cc)])
            k = min(u, w) * (n0 + 1) + max(u, w)
            pieces = [(u, mid[k]), (mid[k], w)] if k in mid else [(u, w)]
            for piece in pieces:
                hit = [(c2, s2) for c2, s2 in where.get(piece, []) if parent[c2] == c]
                if len(hit) != 1:
                    raise MeshError(f"surface {name!r}: face S{s} of cell {c + 1} not found after splitting")
                nc.append(hit[0][0])
                ns.append(hit[0][1])
        nc, ns = np.asarray(nc, np.int64), np.asarray(ns, np.int64)
        o = np.lexsort((ns, nc))
        out.esurfaces[name] = (nc[o], ns[o])
    for j in out.info.get("joints", []):
        n = j["name"]
        if f"{n}_MASTER" in out.esurfaces:
            j["master"] = out.esurfaces[f"{n}_MASTER"]
        if f"{n}_SLAVE" in out.nsets:
            j["slave"] = out.nsets[f"{n}_SLAVE"]


def shape_quality(m):
    """Per cell: (largest diameter^2 / area, smallest corner angle in degrees), hanging
    nodes not counted as corners; for the regularity of repeatedly split meshes."""
    chunk = np.zeros(m.ncell)
    amin = np.zeros(m.ncell)
    area = m.cell_areas()
    for c in range(m.ncell):
        P = m.nodes[m.cell(c)]
        Q = P[corners(P, 1e-7, 0.0)]
        d = np.sqrt(((Q[:, None] - Q[None]) ** 2).sum(-1)).max()
        chunk[c] = d * d / area[c]
        u = np.roll(Q, 1, axis=0) - Q
        v = np.roll(Q, -1, axis=0) - Q
        ang = np.degrees(np.arctan2(v[:, 0] * u[:, 1] - v[:, 1] * u[:, 0], (u * v).sum(1)))
        amin[c] = np.where(ang < 0, ang + 360, ang).min()
    return chunk, amin
