"""The mesh container and the operations on it that do not depend on how it was made.

Cells are stored flat (CSR): cell i has node indices conn[ptr[i]:ptr[i+1]], 0-based,
counter-clockwise; side k (1-based) runs from its node k to node k+1 (last to first).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .errors import MeshError


@dataclass
class Mesh:
    nodes: np.ndarray                       # (N, 2)
    ptr: np.ndarray                         # (ncell + 1,)
    conn: np.ndarray                        # (ptr[-1],)
    cell_body: np.ndarray                   # (ncell,) index into bodies
    bodies: list = field(default_factory=list)      # [(name, element type)]
    nsets: dict = field(default_factory=dict)       # name -> node indices
    elsets: dict = field(default_factory=dict)      # name -> cell indices
    esurfaces: dict = field(default_factory=dict)   # name -> (cells, sides 1-based)
    nsurfaces: dict = field(default_factory=dict)   # name -> node indices
    info: dict = field(default_factory=dict)        # joints, Lloyd history... for reports/tests
    # second-order meshes: the node of side k of cell i is side_nodes[ptr[i] + k - 1]
    # (aligned with conn); None for a first-order mesh.  conn keeps the corners only,
    # so everything that works on the cell polygons is unchanged.
    side_nodes: np.ndarray | None = None

    @property
    def ncell(self):
        return len(self.ptr) - 1

    def cell(self, i):
        return self.conn[self.ptr[i]:self.ptr[i + 1]]

    def cell_index(self):
        return np.repeat(np.arange(self.ncell), np.diff(self.ptr))

    def next_index(self):
        nxt = np.arange(len(self.conn)) + 1
        nxt[self.ptr[1:] - 1] = self.ptr[:-1]
        return nxt

    def cell_areas(self):
        xy = self.nodes[self.conn]
        nx = xy[self.next_index()]
        cr = xy[:, 0] * nx[:, 1] - xy[:, 1] * nx[:, 0]
        return 0.5 * np.add.reduceat(cr, self.ptr[:-1]) if len(cr) else np.zeros(0)

    def edges(self):
        """Directed edges (a, b, cell, side) of every cell."""
        a = self.conn
        b = self.conn[self.next_index()]
        cell = self.cell_index()
        side = np.arange(len(self.conn)) - self.ptr[cell] + 1
        return a, b, cell, side

    def boundary_edge_mask(self):
        a, b, _, _ = self.edges()
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        key = lo.astype(np.int64) * (len(self.nodes) + 1) + hi
        _, inv, cnt = np.unique(key, return_inverse=True, return_counts=True)
        return cnt[inv] == 1


def check_cells(m, limit=5):
    """Refuse a mesh with a cell vemcontact would refuse: clockwise or of zero area, a
    node used twice, or self-intersecting (MeshError naming the cells, their body and
    a centroid).  A cell whose every corner turns left and whose turns add up to one
    revolution is convex and simple; only the others are tested for self-intersection
    (shapely, vectorized)."""
    import shapely
    n = m.ncell
    if n == 0:
        return
    bad = {}
    area = m.cell_areas()
    scale = max(float(np.ptp(m.nodes[:, 0])), float(np.ptp(m.nodes[:, 1])), 1e-300)
    # zero area relative to the cell's size: 1e-12 of the squared extent is round-off
    cidx = m.cell_index()
    for i in np.flatnonzero(~(area > 1e-24 * scale * scale)):
        bad[int(i)] = "clockwise" if area[i] < 0 else "of zero area"
    key = cidx.astype(np.int64) * (len(m.nodes) + 1) + m.conn
    _, counts = np.unique(key, return_counts=True)
    if (counts > 1).any():
        for i in range(n):
            c = m.cell(i)
            if len(set(c.tolist())) < len(c):
                bad.setdefault(i, "using a node twice")
    xy = m.nodes[m.conn]
    nx = xy[m.next_index()]
    d = nx - xy
    dn = d[m.next_index()]
    cross = d[:, 0] * dn[:, 1] - d[:, 1] * dn[:, 0]
    turn = np.arctan2(cross, (d * dn).sum(axis=1))
    left = np.logical_and.reduceat(cross > 0, m.ptr[:-1])
    total = np.add.reduceat(turn, m.ptr[:-1])
    convex = left & (np.abs(total - 2 * np.pi) < 1e-6)
    test = [i for i in np.flatnonzero(~convex) if int(i) not in bad]
    if test:
        rings = np.array([shapely.Polygon(m.nodes[m.cell(i)]) for i in test], dtype=object)
        for i, ok in zip(test, shapely.is_valid(rings)):
            if not ok:
                bad[int(i)] = "self-intersecting"
    if bad:
        items = sorted(bad.items())
        shown = []
        for i, why in items[:limit]:
            name = m.bodies[int(m.cell_body[i])][0] if m.bodies else "?"
            c = m.nodes[m.cell(i)].mean(axis=0)
            shown.append(f"cell {i + 1} of body {name!r} is {why} (near ({c[0]:.6g}, {c[1]:.6g}))")
        more = f"; and {len(items) - limit} more" if len(items) > limit else ""
        raise MeshError(f"the mesh has {len(items)} invalid cells, not written: " + "; ".join(shown) + more +
                        ". Use more cells (or another seed) for this geometry")


def add_side_nodes(m, arcs=()):
    """Make `m` second order: one new node per side, shared by the two cells on an
    interior side; sides on the two faces of a joint have different corner nodes, so
    they get different side nodes (the side nodes split like the vertices).  A side
    node sits at the middle of its side, except on a boundary side with both corners
    on one of the circular `arcs` (center, radius): there it is placed on the circle,
    at the middle angle, and the side is the quadratic curve through its three nodes
    (isoparametric FEM sides and the k = 2 virtual element's curved sides alike).
    The new nodes follow the old ones; m.side_nodes is set."""
    a, b, cell, _ = m.edges()
    n0 = len(m.nodes)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo.astype(np.int64) * (n0 + 1) + hi
    uniq, first, inv, cnt = np.unique(key, return_index=True, return_inverse=True, return_counts=True)
    mid = 0.5 * (m.nodes[a[first]] + m.nodes[b[first]])
    if len(arcs):
        boundary = cnt == 1
        size = np.ptp(m.nodes, axis=0).max() if n0 else 1.0
        for c, r in arcs:
            c = np.asarray(c, float)
            on = boundary.copy()
            da = np.abs(np.hypot(*(m.nodes[a[first]] - c).T) - r)
            db = np.abs(np.hypot(*(m.nodes[b[first]] - c).T) - r)
            on &= (da <= 1e-9 * size) & (db <= 1e-9 * size)
            v = mid[on] - c
            mid[on] = c + r * v / np.hypot(*v.T)[:, None]
    m.nodes = np.vstack([m.nodes, mid])
    m.side_nodes = (n0 + inv).astype(np.int64)
    return m


def add_side_nodes_to_sets(m):
    """In a second-order mesh, add to every node set and node surface the side nodes
    of the sides whose two corners it holds (the sets are made from the corners)."""
    if m.side_nodes is None:
        return m
    a, b, _, _ = m.edges()
    for sets in (m.nsets, m.nsurfaces):
        for name, nodes in sets.items():
            nodes = np.asarray(nodes, dtype=np.int64)
            inset = np.zeros(len(m.nodes), bool)
            inset[nodes] = True
            extra = np.unique(m.side_nodes[inset[a] & inset[b]])
            sets[name] = np.union1d(nodes, extra)
    return m


def concatenate(meshes):
    """Disjoint union: node and cell indices are offset, names must not clash."""
    nodes, ptrs, conns, cb = [], [], [np.zeros(0, np.int64)], []
    bodies, out = [], Mesh(np.zeros((0, 2)), np.zeros(1, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64))
    noff = coff = boff = 0
    ptrs = [np.zeros(1, np.int64)]
    for m in meshes:
        nodes.append(m.nodes)
        conns.append(m.conn + noff)
        ptrs.append(m.ptr[1:] + ptrs[-1][-1])
        cb.append(m.cell_body + boff)
        bodies += m.bodies
        for dst, src, off in ((out.nsets, m.nsets, noff), (out.nsurfaces, m.nsurfaces, noff),
                              (out.elsets, m.elsets, coff)):
            for k, v in src.items():
                if k in dst:
                    raise MeshError(f"name {k!r} is used twice")
                dst[k] = v + off
        for k, (c, s) in m.esurfaces.items():
            if k in out.esurfaces:
                raise MeshError(f"surface {k!r} is used twice")
            out.esurfaces[k] = (c + coff, s)
        for k, v in m.info.items():
            if isinstance(v, list):
                out.info.setdefault(k, []).extend(v)
            else:
                out.info[k] = v
        noff += len(m.nodes)
        coff += m.ncell
        boff += len(m.bodies)
    out.nodes = np.concatenate(nodes) if nodes else np.zeros((0, 2))
    out.ptr = np.concatenate(ptrs)
    out.conn = np.concatenate(conns)
    out.cell_body = np.concatenate(cb) if cb else np.zeros(0, np.int64)
    out.bodies = bodies
    names = [b[0] for b in bodies]
    if len(set(names)) != len(names):
        raise MeshError(f"body names must be unique, got {names}")
    return out


def merge_points(xy, tol):
    """Merge coordinates closer than tol: (unique points, inverse index)."""
    u, inv = np.unique(xy, axis=0, return_inverse=True)
    inv = inv.ravel()
    if len(u) > 1:
        pairs = cKDTree(u).query_pairs(tol, output_type="ndarray")
        if len(pairs):
            g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(u), len(u)))
            _, lab = connected_components(g, directed=False)
            first = np.full(lab.max() + 1, -1)
            # representative: the lowest index of each group (deterministic)
            idx = np.arange(len(u))[::-1]
            first[lab[idx]] = idx
            rep = first[lab]
            keep, newid = np.unique(rep, return_inverse=True)
            return u[keep], newid[inv]
    return u, inv


def merge_close(xy, tol):
    """Merge points closer than tol (no exact-duplicate pass): (points, index map)."""
    n = len(xy)
    if n < 2:
        return xy.copy(), np.arange(n)
    if n > 20000:
        # two points closer than tol are closer than tol in x: only runs of x-gaps <= tol
        # can hold a pair, and those are few (the same pairs, from a much smaller tree)
        o = np.argsort(xy[:, 0], kind="stable")
        close = np.diff(xy[o, 0]) <= 2.0 * tol
        m = np.zeros(n, dtype=bool)
        m[:-1] |= close
        m[1:] |= close
        sub = np.sort(o[m])
        pairs = sub[cKDTree(xy[sub]).query_pairs(tol, output_type="ndarray")] if len(sub) > 1 \
            else np.zeros((0, 2), np.int64)
    else:
        pairs = cKDTree(xy).query_pairs(tol, output_type="ndarray")
    if len(pairs) == 0:
        return xy.copy(), np.arange(n)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    first = np.full(lab.max() + 1, -1)
    idx = np.arange(n)[::-1]
    first[lab[idx]] = idx
    rep = first[lab]
    keep, newid = np.unique(rep, return_inverse=True)
    return xy[keep], newid


def from_polygons(ptr, xy, cell_body, bodies, tol):
    """Conforming mesh from polygons given by coordinates (merged within tol)."""
    nodes, conn = merge_points(xy, tol)
    return _compact(Mesh(nodes, ptr.astype(np.int64), conn.astype(np.int64), np.asarray(cell_body), bodies))


def _compact(m):
    """Drop repeated consecutive nodes in cells and cells left with fewer than 3 nodes."""
    nxt = m.next_index()
    keep = m.conn != m.conn[nxt]
    cell = m.cell_index()
    cnt = np.bincount(cell[keep], minlength=m.ncell)
    good = cnt >= 3
    keep &= good[cell]
    conn = m.conn[keep]
    ptr = np.concatenate([[0], np.cumsum(cnt[good])])
    m.conn, m.ptr, m.cell_body = conn, ptr, m.cell_body[good]
    used = np.zeros(len(m.nodes), bool)
    used[conn] = True
    if not used.all():
        new = np.cumsum(used) - 1
        m.nodes = m.nodes[used]
        m.conn = new[m.conn]
    return m


def insert_hanging_nodes(m, candidates, tol):
    """Make the mesh conforming: a node lying inside an edge of a cell is added to that cell.

    Only nodes in `candidates` (those created by clipping and cutting) are tested, against
    the edges of cells that touch a candidate (a hanging node on an edge always shares the
    edge's end nodes with the cell that created it).
    """
    candidates = np.unique(candidates)
    if len(candidates) == 0:
        return m
    mark = np.zeros(len(m.nodes), bool)
    mark[candidates] = True
    cell = m.cell_index()
    touch = np.zeros(m.ncell, bool)
    touch[cell[mark[m.conn]]] = True
    tree = cKDTree(m.nodes[candidates])
    inserts = {}
    nxt = m.next_index()
    for c in np.flatnonzero(touch):
        s, e = m.ptr[c], m.ptr[c + 1]
        for k in range(s, e):
            a, b = m.conn[k], m.conn[nxt[k]]
            pa, pb = m.nodes[a], m.nodes[b]
            mid, half = 0.5 * (pa + pb), 0.5 * np.hypot(*(pb - pa))
            hits = tree.query_ball_point(mid, half + tol)
            if not hits:
                continue
            ab = pb - pa
            L2 = ab @ ab
            found = []
            for h in hits:
                v = candidates[h]
                if v in m.conn[s:e]:
                    continue
                p = m.nodes[v]
                t = (p - pa) @ ab / L2
                if 0.0 < t < 1.0:
                    d = abs(ab[0] * (p[1] - pa[1]) - ab[1] * (p[0] - pa[0])) / np.sqrt(L2)
                    if d <= tol:
                        found.append((t, v))
            if found:
                inserts[(c, k - s)] = [v for _, v in sorted(found)]
    if not inserts:
        return m
    newconn, newptr = [], [0]
    for c in range(m.ncell):
        cc = m.conn[m.ptr[c]:m.ptr[c + 1]]
        if not touch[c]:
            newconn.append(cc)
        else:
            lst = []
            for k, v in enumerate(cc):
                lst.append(v)
                lst.extend(inserts.get((c, k), ()))
            newconn.append(np.asarray(lst, np.int64))
        newptr.append(newptr[-1] + len(newconn[-1]))
    m.conn = np.concatenate(newconn)
    m.ptr = np.asarray(newptr, np.int64)
    return m


def node_line_distance(nodes, polyline):
    from .geometry import distance_to_segments
    segs = np.stack([polyline[:-1], polyline[1:]], 1)
    return distance_to_segments(nodes, segs)


def split_joint(m, name, polyline, master_side, tol):
    """Duplicate the nodes on a joint and write its two faces.

    Around each joint node the incident cells are grouped: two cells are in one group when
    they share an edge at the node that is not a joint edge.  Each group gets its own copy
    of the node; a tip (the joint ends inside the body) has one group and stays shared.
    The faces: element sides on the master side (left or right of the polyline's
    direction), nodes on the slave side (the tip excluded: it cannot open).
    """
    polyline = np.asarray(polyline, float)
    dnode = node_line_distance(m.nodes, polyline)
    on = dnode <= tol
    a, b, cell, side = m.edges()
    cand = on[a] & on[b]
    mid = 0.5 * (m.nodes[a[cand]] + m.nodes[b[cand]])
    ok = node_line_distance(mid, polyline) <= tol if len(mid) else np.zeros(0, bool)
    jidx = np.flatnonzero(cand)[ok]
    if len(jidx) == 0:
        raise MeshError(f"joint {name!r}: no cell edge lies on it")
    jkey = set()
    for e in jidx:
        jkey.add((min(a[e], b[e]), max(a[e], b[e])))
    jnodes = np.unique(np.concatenate([a[jidx], b[jidx]]))
    # node -> incident (cell, position)
    order = np.argsort(m.conn, kind="stable")
    sorted_nodes = m.conn[order]
    nxt = m.next_index()
    prv = np.empty_like(nxt)
    prv[nxt] = np.arange(len(nxt))
    copies = {}
    new_nodes = []
    conn = m.conn.copy()
    for v in jnodes:
        lo, hi = np.searchsorted(sorted_nodes, [v, v + 1])
        pos = order[lo:hi]
        cells = cell[pos]
        parent = list(range(len(pos)))

        def find(i, parent=parent):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i
        by_edge = {}
        for i, p in enumerate(pos):
            for u in (m.conn[nxt[p]], m.conn[prv[p]]):
                key = (min(v, u), max(v, u))
                if key in jkey:
                    continue
                if key in by_edge:
                    ra, rb = find(i), find(by_edge[key])
                    parent[ra] = rb
                else:
                    by_edge[key] = i
        roots = sorted({find(i) for i in range(len(pos))}, key=lambda r: min(cells[i] for i in range(len(pos)) if find(i) == r))
        copies[v] = [v]
        for r in roots[1:]:
            nid = len(m.nodes) + len(new_nodes)
            new_nodes.append(m.nodes[v])
            copies[v].append(nid)
            for i in range(len(pos)):
                if find(i) == r:
                    conn[pos[i]] = nid
    if new_nodes:
        m.nodes = np.concatenate([m.nodes, np.asarray(new_nodes)])
    m.conn = conn
    # faces, from the updated connectivity
    a2, b2 = conn[jidx], conn[nxt[jidx]]
    segs = np.stack([polyline[:-1], polyline[1:]], 1)
    mids = 0.5 * (m.nodes[a2] + m.nodes[b2])
    # direction of the nearest polyline segment at each joint edge
    best = np.full(len(mids), np.inf)
    dirs = np.zeros((len(mids), 2))
    for s0, s1 in segs:
        from .geometry import point_segment_distance
        d = point_segment_distance(mids, s0, s1)
        mm = d < best
        best[mm] = d[mm]
        dirs[mm] = s1 - s0
    along = ((m.nodes[b2] - m.nodes[a2]) * dirs).sum(1) > 0   # cell lies left of a->b
    left = along
    is_master = left if master_side == "left" else ~left
    mcells, msides = cell[jidx][is_master], side[jidx][is_master]
    snodes = np.unique(np.concatenate([a2[~is_master], b2[~is_master]]))
    mnodes = np.unique(np.concatenate([a2[is_master], b2[is_master]]))
    shared = np.intersect1d(snodes, mnodes)
    snodes = np.setdiff1d(snodes, shared)
    o = np.lexsort((msides, mcells))
    m.esurfaces[f"{name}_MASTER"] = (mcells[o], msides[o])
    m.nsurfaces[f"{name}_SLAVE"] = snodes
    m.nsets[f"{name}_SLAVE"] = snodes
    m.nsets[f"{name}_MASTER"] = mnodes
    m.info.setdefault("joints", []).append(
        {"name": name, "polyline": polyline, "copies": copies, "shared": shared,
         "master": (mcells[o], msides[o]), "slave": snodes})
    return m


def hilbert_key(xy, bits=16):
    """Index of each point along a Hilbert curve over the points' bounding box
    (2**bits cells a side): points close on the curve are close in the plane."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    if len(xy) == 0:
        return np.zeros(0, np.int64)
    lo, span = xy.min(0), np.ptp(xy, 0)
    span[span == 0] = 1.0
    side = 1 << bits
    x, y = (np.minimum(((xy - lo) / span * side).astype(np.int64), side - 1)).T
    x, y = x.copy(), y.copy()
    key = np.zeros(len(xy), np.int64)
    s = side >> 1
    while s > 0:
        rx = (x & s) > 0
        ry = (y & s) > 0
        key += s * s * ((3 * rx) ^ ry)
        # rotate the quadrant so that the curve inside it starts and ends right
        flip = ~ry
        swap_rx = flip & rx
        x[swap_rx] = side - 1 - x[swap_rx]
        y[swap_rx] = side - 1 - y[swap_rx]
        x[flip], y[flip] = y[flip], x[flip].copy()
        s >>= 1
    return key


def spatial_order(m):
    """Renumber the nodes and the cells of `m` in place along a Hilbert curve (nodes
    by their coordinates, cells by their centroids, cells kept grouped by body in
    body order), so that the nodes of a cell and the cells of a neighbourhood are
    close in memory: the solver's assembly and pattern build run faster on such
    meshes.  Sets, surfaces, second-order side nodes and the joints' records follow."""
    if len(m.nodes) == 0 or m.ncell == 0:
        return m
    norder = np.argsort(hilbert_key(m.nodes), kind="stable")
    nnew = np.empty(len(norder), np.int64)
    nnew[norder] = np.arange(len(norder))
    cell = m.cell_index()
    cent = np.zeros((m.ncell, 2))
    cnt = np.diff(m.ptr)
    for d in range(2):
        cent[:, d] = np.bincount(cell, weights=m.nodes[m.conn, d], minlength=m.ncell) / np.maximum(cnt, 1)
    corder = np.lexsort((hilbert_key(cent), m.cell_body))
    cnew = np.empty(len(corder), np.int64)
    cnew[corder] = np.arange(len(corder))
    # positions of the old conn entries, cell by cell in the new order
    ncnt = cnt[corder]
    ptr = np.concatenate([[0], np.cumsum(ncnt)]).astype(m.ptr.dtype)
    pos = np.repeat(m.ptr[:-1][corder] - ptr[:-1], ncnt) + np.arange(ptr[-1])
    m.nodes = m.nodes[norder]
    m.conn = nnew[m.conn[pos]]
    if m.side_nodes is not None:
        m.side_nodes = nnew[m.side_nodes[pos]]
    m.ptr = ptr
    m.cell_body = m.cell_body[corder]
    m.nsets = {k: nnew[np.asarray(v, np.int64)] for k, v in m.nsets.items()}
    m.nsurfaces = {k: nnew[np.asarray(v, np.int64)] for k, v in m.nsurfaces.items()}
    m.elsets = {k: cnew[np.asarray(v, np.int64)] for k, v in m.elsets.items()}
    m.esurfaces = {k: (cnew[np.asarray(c, np.int64)], s) for k, (c, s) in m.esurfaces.items()}
    for j in m.info.get("joints", []):
        j["shared"] = nnew[np.asarray(j["shared"], np.int64)]
        j["slave"] = nnew[np.asarray(j["slave"], np.int64)]
        c, s = j["master"]
        j["master"] = (cnew[np.asarray(c, np.int64)], s)
        j["copies"] = {int(nnew[k]): [int(nnew[v]) for v in vs] for k, vs in j["copies"].items()}
    return m
