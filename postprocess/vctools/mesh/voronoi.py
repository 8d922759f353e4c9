"""Bounded centroidal Voronoi tessellation of a polygonal domain with constraint lines.

Generators are the real seeds (free ones that Lloyd moves, fixed ones in mirrored pairs
along joints and bonded interfaces), helpers that never own a cell (PolyMesher-style
reflections across the boundary, a far ring that bounds every cell) .

The diagram is computed in tiles: each tile triangulates its own seeds plus a halo, and a
cell is accepted only when every vertex v of its (clipped) polygon has its empty disc
B(v, |v - seed|) inside the tile's extended box.  Then no generator outside the tile can
change the cell (the emptiness test is affine along the cell, so the vertices suffice);
otherwise the tile is redone with a wider halo.  Qhull is superlinear on large inputs
(14 s for 1e6 points, 3.4 us per point in tiles of 1e4), which is why the tiles paid off;
Triangle (0.8 us per point) is used when installed, and the tiles still run in parallel.
Circumcentres are computed from the vertices sorted by global id so that a vertex shared by
tiles has bit-identical coordinates.
"""
from __future__ import annotations

import multiprocessing as mp
import os

import numpy as np
import shapely
from scipy.spatial import Delaunay

try:  # Shewchuk's Triangle: the same triangulation as Qhull, about 5x faster in 2D
    import triangle as _triangle
except ImportError:  # pragma: no cover - the pinned requirements install it
    _triangle = None

from .geometry import distance_to_segments, polygon_moments_csr

SQRT3 = np.sqrt(3.0)


def delaunay(P, backend=None):
    """Delaunay triangles of P as a canonical (m, 3) index array.

    Each triangle is rotated to start at its smallest index (orientation kept) and the
    triangles are sorted, so that everything computed from them (sums over triangles
    included) does not depend on the library's output order: Triangle and Qhull give
    identical meshes unless four generators are cocircular, where the diagonal (and so
    the last bits of a zero-length Voronoi edge) may differ.
    """
    backend = backend or ("triangle" if _triangle is not None else "qhull")
    if backend == "triangle":
        tri = _triangle.triangulate({"vertices": P}, "Qz")["triangles"].astype(np.int64)
    else:
        tri = Delaunay(P).simplices.astype(np.int64)
    r = np.argmin(tri, axis=1)
    tri = tri[np.arange(len(tri))[:, None], (r[:, None] + np.arange(3)) % 3]
    n = np.int64(len(P))
    return tri[np.argsort((tri[:, 0] * n + tri[:, 1]) * n + tri[:, 2], kind="stable")]


def circumcenters(A, B, C):
    b = B - A
    c = C - A
    d = 2.0 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    b2 = (b * b).sum(1)
    c2 = (c * c).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (c[:, 1] * b2 - b[:, 1] * c2) / d
        uy = (b[:, 0] * c2 - c[:, 0] * b2) / d
    cen = A + np.column_stack([ux, uy])
    return cen, np.hypot(ux, uy)


class Context:
    """What a tile needs to know about the domain (picklable for worker processes)."""

    def __init__(self, shape, segs, lines, tips, size, density):
        self.shape = shape                  # shapely Polygon of the domain
        self.segs = segs                    # (m, 2, 2) boundary segments
        self.lines = lines                  # list of (k, 2) constraint polylines
        self.line_segs = (np.concatenate([np.stack([p[:-1], p[1:]], 1) for p in lines])
                          if lines else np.zeros((0, 2, 2)))
        self.tips = tips                    # list of (point, direction) at interior line ends
        self.size = size
        self.tol = 1e-10 * size             # merge/snap tolerance: far below any cell size
        self.density = density
        self.backend = None                 # Delaunay library: None = Triangle if installed


def _snap(xy, ctx):
    """Project vertices lying within tol of a boundary or constraint segment onto it."""
    segs = np.concatenate([ctx.segs, ctx.line_segs]) if len(ctx.line_segs) else ctx.segs
    out = xy.copy()
    best = np.full(len(xy), ctx.tol * 10)
    for a, b in segs:
        ab = b - a
        t = np.clip(((xy - a) @ ab) / (ab @ ab), 0.0, 1.0)
        proj = a + t[:, None] * ab
        d = np.hypot(*(xy - proj).T)
        m = d < best
        # endpoints snap exactly onto the segment ends
        pe = np.where((t == 0.0)[:, None], a, np.where((t == 1.0)[:, None], b, proj))
        out[m] = pe[m]
        best[m] = d[m]
    return out


def _split_by_lines(poly, ctx):
    """Pieces of a polygon cut by the constraint lines (tip cells get the line extended).

    Whole lines are noded with the ring (not their intersection with the polygon, whose end
    points may miss the ring by an ulp and leave a dangle); parts outside are dangles that
    polygonize ignores.
    """
    cuts = []
    tol = ctx.tol
    for line in ctx.lines:
        ls = shapely.LineString(line)
        inter = poly.intersection(ls)
        if inter.is_empty or inter.length <= tol:
            continue
        if poly.exterior.buffer(tol * 10).covers(inter):
            continue
        cuts.append(ls)
    if not cuts:
        return [poly]
    lo, hi = np.array(poly.bounds[:2]), np.array(poly.bounds[2:])
    diam = float(np.hypot(*(hi - lo)))
    for tip, direction in ctx.tips:
        p = shapely.Point(tip)
        if poly.contains(p) and poly.exterior.distance(p) > tol:
            cuts.append(shapely.LineString([tip, tip + direction * 2.0 * diam]))
    noded = shapely.unary_union([poly.exterior] + cuts)
    faces = list(shapely.get_parts(shapely.polygonize(shapely.get_parts(noded))))
    amin = 1e-12 * poly.area
    faces = [f for f in faces if f.area > amin and poly.covers(f.representative_point())]
    return faces or [poly]


def _ccw_coords(poly):
    xy = shapely.get_coordinates(poly.exterior)[:-1]
    x, y = xy[:, 0], xy[:, 1]
    if np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y) < 0:
        xy = xy[::-1]
    return xy


def _ring_coords(rings):
    """Coordinates of linear rings without their closing points: (xy, ptr)."""
    xy, idx = shapely.get_coordinates(rings, return_index=True)
    cnt = np.bincount(idx, minlength=len(rings))
    last = np.cumsum(cnt) - 1
    keep = np.ones(len(xy), dtype=bool)
    keep[last[cnt > 0]] = False
    return xy[keep], np.concatenate([[0], np.cumsum(np.maximum(cnt - 1, 0))])


def _ccw_csr(rings):
    """_ccw_coords of many exterior rings at once: (xy, ptr), each ring counter-clockwise."""
    xy, ptr = _ring_coords(rings)
    n = len(ptr) - 1
    cnt = np.diff(ptr)
    cell = np.repeat(np.arange(n), cnt)
    nxt = np.arange(len(xy)) + 1
    nxt[ptr[1:][cnt > 0] - 1] = ptr[:-1][cnt > 0]
    x, y = xy[:, 0], xy[:, 1]
    s1 = np.bincount(cell, weights=x * y[nxt], minlength=n)
    s2 = np.bincount(cell, weights=x[nxt] * y, minlength=n)
    sgn = s1 - s2
    # near-zero areas: decide exactly as _ccw_coords does
    scale = np.bincount(cell, weights=np.abs(x * y[nxt]) + np.abs(x[nxt] * y), minlength=n)
    for k in np.flatnonzero(np.abs(sgn) <= 1e-6 * scale):
        xk, yk = x[ptr[k]:ptr[k + 1]], y[ptr[k]:ptr[k + 1]]
        sgn[k] = np.dot(xk, np.roll(yk, -1)) - np.dot(np.roll(xk, -1), yk)
    rev = np.repeat(sgn < 0, cnt)
    pos = np.arange(len(xy))
    start = np.repeat(ptr[:-1], cnt)
    pos[rev] = (np.repeat(ptr[1:], cnt) - 1 - (pos - start))[rev]
    return xy[pos], ptr


def _clip_moments(clipped, clip_idx, seeds, lo, hi, ctx, ok, mass, cen, energy):
    """Locality test and moments of the clipped cells: the loop of the final pass, vectorised
    (same arithmetic, so the same bits), for the Lloyd iterations."""
    parts, pidx = shapely.get_parts(clipped, return_index=True)
    if len(parts):
        keep = (shapely.get_type_id(parts) == 3) & (shapely.area(parts) > 0)
        parts, pidx = parts[keep], pidx[keep]
    nparts = np.bincount(pidx, minlength=len(clip_idx))
    empty = clip_idx[nparts == 0]
    # the cell misses the domain (a seed on the boundary): it owns nothing
    mass[empty], cen[empty], energy[empty] = 0.0, seeds[empty], 0.0
    if not len(parts):
        return
    xy, cidx = shapely.get_coordinates(parts, return_index=True)
    owner = pidx[cidx]
    s = seeds[clip_idx[owner]]
    d2 = np.hypot(xy[:, 0] - s[:, 0], xy[:, 1] - s[:, 1])
    viol = ~np.all((xy - d2[:, None] >= lo) & (xy + d2[:, None] <= hi), axis=1)
    bad = np.bincount(owner[viol], minlength=len(clip_idx)) > 0
    has = nparts > 0
    ok[clip_idx[has]] = ~bad[has]
    # main part: the only one, else the one covering the seed, else the largest
    first = np.searchsorted(pidx, np.arange(len(clip_idx)))
    sel = first[has]
    for k in np.flatnonzero(nparts > 1):
        grp = parts[first[k]:first[k] + nparts[k]]
        sk = shapely.Point(seeds[clip_idx[k]])
        inside = [q for q, g in enumerate(grp) if g.covers(sk)]
        sel[np.searchsorted(np.flatnonzero(has), k)] = first[k] + (
            inside[0] if inside else max(range(len(grp)), key=lambda q: grp[q].area))
    main_idx = clip_idx[has]
    mxy, mptr = _ccw_csr(shapely.get_exterior_ring(parts[sel]))
    mm, cc, ee = polygon_moments_csr(mptr, mxy, origin=seeds[main_idx], density=ctx.density)
    mass[main_idx], cen[main_idx], energy[main_idx] = mm, cc, ee


def tile_cells(P, gid, n_own, lo, hi, ctx, final):
    """Cells of the first n_own points of P (tile seeds; the rest is halo and helpers).

    Returns (ok, mass, centroid, energy, pieces, owner) where ok[i] says whether cell i passed
    the locality test, and pieces/owner (final only) are CCW coordinate arrays of the cells.
    """
    tri = delaunay(P, ctx.backend)
    seeds = P[:n_own]
    if final:
        # canonical vertex order: a Voronoi vertex computed by two tiles is bit-identical
        order = np.argsort(gid[tri], axis=1)
        tri = np.take_along_axis(tri, order, axis=1)
    C, R = circumcenters(P[tri[:, 0]], P[tri[:, 1]], P[tri[:, 2]])
    # counter-clockwise corners for the kites (the circumcentres are already computed)
    Pt = P[tri]
    cw = ((Pt[:, 1, 0] - Pt[:, 0, 0]) * (Pt[:, 2, 1] - Pt[:, 0, 1])
          - (Pt[:, 1, 1] - Pt[:, 0, 1]) * (Pt[:, 2, 0] - Pt[:, 0, 0])) < 0
    tri = tri.copy()
    tri[cw, 1], tri[cw, 2] = tri[cw, 2], tri[cw, 1].copy()
    # incidences (triangle corner -> owned seed); corner j of triangle t, its next corners
    ft = np.repeat(np.arange(len(tri)), 3)
    fp = tri.ravel()
    fq = tri[:, [1, 2, 0]].ravel()
    fr = tri[:, [2, 0, 1]].ravel()
    m = fp < n_own
    fp, ft, fq, fr = fp[m], ft[m], fq[m], fr[m]
    V = C[ft]
    dv = np.hypot(V[:, 0] - seeds[fp, 0], V[:, 1] - seeds[fp, 1])
    rcell = np.zeros(n_own)
    np.maximum.at(rcell, fp, dv)
    # locality test per triangle (its empty disc inside the box), then per cell
    with np.errstate(invalid="ignore"):
        good_t = np.all((C - R[:, None] >= lo) & (C + R[:, None] <= hi), axis=1) & np.isfinite(R)
    ok = np.bincount(fp[~good_t[ft]], minlength=n_own) == 0

    # cells that reach a boundary (or a line, when final); only the segments that can be
    # reached from the tile are measured (the others are farther than any cell's radius)
    segs = ctx.segs
    if final and len(ctx.line_segs):
        segs = np.concatenate([segs, ctx.line_segs])
    near = np.zeros(n_own, dtype=bool)
    if n_own:
        reach = float(np.nanmax(rcell)) + 2e-9 * ctx.size
        slo_ = seeds.min(0) - reach
        shi_ = seeds.max(0) + reach
        smin = segs.min(1)
        smax = segs.max(1)
        cand = np.all((smax >= slo_) & (smin <= shi_), axis=1) | ~np.isfinite(reach)
        if cand.any():
            dist = distance_to_segments(seeds, segs[cand])
            near = rcell >= dist - 1e-9 * ctx.size
    # moments by kites: the cell of seed a is the signed union over its triangles (a, b, c)
    # of (a, m_ab, C) and (a, C, m_ca) -- exact for any Delaunay triangle, obtuse included
    pa = seeds[fp]
    u = 0.5 * (P[fq] - pa)
    w = V - pa
    z = 0.5 * (P[fr] - pa)
    a1 = 0.5 * (u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0])
    a2 = 0.5 * (w[:, 0] * z[:, 1] - w[:, 1] * z[:, 0])
    dens = ctx.density
    c1 = (u + w) / 3.0
    c2 = (w + z) / 3.0
    if dens is not None and not getattr(dens, "uniform", False):
        a1 = a1 * dens(pa + c1)
        a2 = a2 * dens(pa + c2)
    elif dens is not None:
        a1 = a1 * dens.scale[0]
        a2 = a2 * dens.scale[0]
    mass = np.bincount(fp, weights=a1 + a2, minlength=n_own)
    mx = np.bincount(fp, weights=a1 * c1[:, 0] + a2 * c2[:, 0], minlength=n_own)
    my = np.bincount(fp, weights=a1 * c1[:, 1] + a2 * c2[:, 1], minlength=n_own)
    ww = (w * w).sum(1)
    e = a1 / 6.0 * ((u * u).sum(1) + ww + (u * w).sum(1)) + a2 / 6.0 * (ww + (z * z).sum(1) + (w * z).sum(1))
    energy = np.bincount(fp, weights=e, minlength=n_own)
    with np.errstate(divide="ignore", invalid="ignore"):
        cen = seeds + np.column_stack([mx / mass, my / mass])

    # polygons (vertices sorted by angle around the seed): all cells when final, else the
    # cells to clip
    if not final:
        sel = near[fp]
        fp, ft, V = fp[sel], ft[sel], V[sel]
    ang = np.arctan2(V[:, 1] - seeds[fp, 1], V[:, 0] - seeds[fp, 0])
    # one float key: cell index, then angle in [0, 1] (float64 resolves 1e-11 at 1e5 seeds)
    o = np.argsort(fp * 2.0 + (ang + np.pi) * (0.5 / np.pi), kind="stable")
    fp, ft, V = fp[o], ft[o], V[o]
    counts = np.bincount(fp, minlength=n_own)
    ptr = np.concatenate([[0], np.cumsum(counts)])
    pieces, owner = [], []
    if final:
        Vs = _snap(V, ctx) if near.any() else V
    clip_idx = np.flatnonzero(near)
    if len(clip_idx):
        W = Vs if final else V
        cnt = counts[clip_idx]
        rep = np.repeat(ptr[clip_idx], cnt) + (np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt))
        ring_xy = W[rep]
        ring_id = np.repeat(np.arange(len(clip_idx)), cnt)
        # drop near-duplicate consecutive vertices (cocircular generators): a ring with a
        # 1e-18 bow-tie is invalid for GEOS
        nxt = np.arange(len(rep)) + 1
        ends = np.cumsum(cnt)
        nxt[ends - 1] = ends - cnt
        dup = np.hypot(*(ring_xy[nxt] - ring_xy).T) <= ctx.tol
        ring_xy, ring_id = ring_xy[~dup], ring_id[~dup]
        polys = shapely.polygons(shapely.linearrings(ring_xy, indices=ring_id))
        clipped = shapely.intersection(polys, ctx.shape)
        if not final:
            _clip_moments(clipped, clip_idx, seeds, lo, hi, ctx, ok, mass, cen, energy)
        else:
            mains, main_idx = [], []
            for k, i in enumerate(clip_idx):
                parts = [g for g in shapely.get_parts(clipped[k]) if g.geom_type == "Polygon" and g.area > 0]
                s = seeds[i]
                if not parts:
                    # the cell misses the domain (a seed on the boundary): it owns nothing
                    mass[i], cen[i], energy[i] = 0.0, s, 0.0
                    continue
                allxy = np.concatenate([shapely.get_coordinates(g) for g in parts])
                d2 = np.hypot(allxy[:, 0] - s[0], allxy[:, 1] - s[1])
                ok[i] = bool(np.all((allxy - d2[:, None] >= lo) & (allxy + d2[:, None] <= hi)))
                if len(parts) == 1:
                    main = parts[0]
                else:
                    inside = [g for g in parts if g.covers(shapely.Point(s))]
                    main = inside[0] if inside else max(parts, key=lambda g: g.area)
                mains.append(_ccw_coords(main))
                main_idx.append(i)
                for g in parts:
                    for piece in (_split_by_lines(g, ctx) if ctx.lines else [g]):
                        pieces.append(_ccw_coords(piece))
                        owner.append(i)
            if mains:
                main_idx = np.asarray(main_idx)
                mptr = np.concatenate([[0], np.cumsum([len(x) for x in mains])])
                mm, cc, ee = polygon_moments_csr(mptr, np.concatenate(mains), origin=seeds[main_idx],
                                                 density=ctx.density)
                mass[main_idx], cen[main_idx], energy[main_idx] = mm, cc, ee
    if final:
        keep = np.flatnonzero(~near)
        keys = (ptr, V, keep, gid[tri[ft]] if final else None)
        return ok, mass, cen, energy, keys, (pieces, np.asarray(owner, dtype=np.int64))
    return ok, mass, cen, energy, None, None


_CTX = None


def _init_worker(ctx):
    global _CTX
    _CTX = ctx


def _run_tile(args):
    P, gid, n_own, lo, hi, ctx, final = args
    return tile_cells(P, gid, n_own, lo, hi, ctx if ctx is not None else _CTX, final)


class Tessellator:
    """Tiled bounded Voronoi diagram; reusable across Lloyd iterations."""

    halo = 1.5          # halo width, in units of twice the mean seed spacing of the tile

    def __init__(self, ctx, per_tile=4000, processes=None):
        self.ctx = ctx
        self.per_tile = per_tile
        self.processes = processes
        self._pool = None

    def close(self):
        if self._pool is not None:
            self._pool.close()
            self._pool.join()
            self._pool = None

    def _map(self, jobs):
        nproc = self.processes
        if nproc is None:
            nproc = min(os.cpu_count() or 1, 8)
        if nproc > 1 and len(jobs) > 4:
            if self._pool is None:
                self._pool = mp.get_context("fork").Pool(nproc, initializer=_init_worker, initargs=(self.ctx,))
            jobs = [j[:5] + (None,) + j[6:] for j in jobs]
            return self._pool.map(_run_tile, jobs, chunksize=max(1, len(jobs) // (32 * nproc)))
        return [_run_tile(j) for j in jobs]

    def run(self, seeds, helpers, final=False):
        ctx = self.ctx
        n = len(seeds)
        G = np.concatenate([seeds, helpers])
        # (column by column: a reduction along axis 0 of an (n, 2) array is slow)
        lo0 = np.array([seeds[:, 0].min(), seeds[:, 1].min()])
        hi0 = np.array([seeds[:, 0].max(), seeds[:, 1].max()])
        span = np.maximum(hi0 - lo0, 1e-12 * ctx.size)
        ntiles = max(1, int(round(n / self.per_tile)))
        aspect = span[0] / span[1]
        ntx = max(1, int(round(np.sqrt(ntiles * aspect))))
        nty = max(1, int(round(ntiles / ntx)))
        tx = np.minimum((ntx * (seeds[:, 0] - lo0[0]) / span[0]).astype(int), ntx - 1)
        ty = np.minimum((nty * (seeds[:, 1] - lo0[1]) / span[1]).astype(int), nty - 1)
        tile_of = tx * nty + ty
        order = np.argsort(tile_of.astype(np.int16) if ntx * nty < 2 ** 15 else tile_of, kind="stable")
        tile_all = np.concatenate([tile_of, np.full(len(helpers), -1)])
        starts = np.searchsorted(tile_of[order], np.arange(ntx * nty + 1))
        far = helpers[-FAR_RING:] if len(helpers) >= FAR_RING else helpers
        far_gid = np.arange(len(G) - len(far), len(G))

        results = [None] * (ntx * nty)
        halo_factor = np.full(ntx * nty, self.halo)
        ntile = ntx * nty
        counts = np.diff(starts)
        todo = [t for t in range(ntile) if counts[t] > 0]
        # tile boxes, own-seed bounds and mean seed spacing, per tile
        ti, tj = np.divmod(np.arange(ntile), nty)
        blo = lo0 + span * np.column_stack([ti / ntx, tj / nty])
        bhi = lo0 + span * np.column_stack([(ti + 1) / ntx, (tj + 1) / nty])
        blo[ti == 0, 0] = -np.inf
        blo[tj == 0, 1] = -np.inf
        bhi[ti == ntx - 1, 0] = np.inf
        bhi[tj == nty - 1, 1] = np.inf
        nz = np.flatnonzero(counts > 0)
        sorted_seeds = seeds[order]
        omin = np.zeros((ntile, 2))
        omax = np.zeros((ntile, 2))
        if len(nz):
            omin[nz] = np.minimum.reduceat(sorted_seeds, starts[nz], axis=0)
            omax[nz] = np.maximum.reduceat(sorted_seeds, starts[nz], axis=0)
        hloc = np.sqrt(np.prod(span / [ntx, nty]) / np.maximum(counts, 1))
        cellw = span / [ntx, nty]
        # generators other than the far ring, bucketed on a grid K times finer than the tiles
        # (by column, then row): a box of width below a tile cell takes its candidates from a
        # few runs of consecutive buckets
        K = int(max(1, min(8, np.sqrt((2 ** 15 - 1) / ntile))))     # int16 keys: a radix sort
        nbx, nby = ntx * K, nty * K
        nA = len(G) - len(far)
        A = G[:nA]
        bx = np.clip(np.floor(nbx * (A[:, 0] - lo0[0]) / span[0]), 0, nbx - 1).astype(np.int64)
        by = np.clip(np.floor(nby * (A[:, 1] - lo0[1]) / span[1]), 0, nby - 1).astype(np.int64)
        bucket = bx * nby + by
        border = np.argsort(bucket.astype(np.int16) if nbx * nby < 2 ** 15 else bucket, kind="stable")
        bstarts = np.searchsorted(bucket[border], np.arange(nbx * nby + 1))
        # bucket-ordered copies: the candidates of a tile are contiguous runs in memory
        GB = A[border]
        TB = tile_all[:nA][border]
        xorder = xs = None
        while todo:
            jobs = []
            for t in todo:
                own = order[starts[t]:starts[t + 1]]
                w = halo_factor[t] * hloc[t] * 2.0
                slo = np.maximum(blo[t], omin[t]) - w
                shi = np.minimum(bhi[t], omax[t]) + w
                if ntile > 1 and w < 0.9 * cellw.min():
                    # buckets that meet the box (one bucket of slack against round-off)
                    c0, c1 = np.clip(np.floor((slo - lo0) / span * [nbx, nby]).astype(np.int64) - 1,
                                     0, [nbx - 1, nby - 1]), \
                        np.clip(np.floor((shi - lo0) / span * [nbx, nby]).astype(np.int64) + 1,
                                0, [nbx - 1, nby - 1])
                    cols = np.arange(c0[0], c1[0] + 1) * nby
                    runs = [(bstarts[c + c0[1]], bstarts[c + c1[1] + 1]) for c in cols]
                    cand = np.concatenate([border[a:b] for a, b in runs])
                    P = np.concatenate([GB[a:b] for a, b in runs])
                    inb = (P[:, 0] >= slo[0]) & (P[:, 0] < shi[0]) & (P[:, 1] >= slo[1]) & (P[:, 1] <= shi[1])
                    inb &= np.concatenate([TB[a:b] for a, b in runs]) != t
                    halo = cand[inb]
                    Ph = P[inb]
                    # in the order of a stable sort by x, as the strip search below gives them
                    o = np.lexsort((halo, Ph[:, 0]))
                    halo, Ph = halo[o], Ph[o]
                else:
                    if xorder is None:
                        xorder = np.argsort(G[:, 0], kind="stable")
                        xs = G[xorder, 0]
                    a, b = np.searchsorted(xs, [slo[0], shi[0]])
                    cand = xorder[a:b]
                    cand = cand[(G[cand, 1] >= slo[1]) & (G[cand, 1] <= shi[1])]
                    halo = cand[(tile_all[cand] != t) & (cand < len(G) - len(far))]
                    Ph = G[halo]
                ids = np.concatenate([own, halo, far_gid])
                everything = len(halo) + len(own) + len(far_gid) >= len(G)
                jlo = np.full(2, -np.inf) if everything else slo
                jhi = np.full(2, np.inf) if everything else shi
                Pt = np.concatenate([sorted_seeds[starts[t]:starts[t + 1]], Ph, far])
                jobs.append((Pt, ids, len(own), jlo, jhi, ctx, final))
            outs = self._map(jobs)
            again = []
            for t, out in zip(todo, outs):
                if out[0].all():
                    results[t] = out
                else:
                    halo_factor[t] *= 2.0
                    again.append(t)
            todo = again

        mass = np.zeros(n)
        cen = np.zeros((n, 2))
        energy = np.zeros(n)
        for t in range(ntx * nty):
            if results[t] is None:
                continue
            own = order[starts[t]:starts[t + 1]]
            _, m_, c_, e_, _, _ = results[t]
            mass[own], cen[own], energy[own] = m_, c_, e_
        if not final:
            return mass, cen, energy, None
        cells = []
        for t in range(ntx * nty):
            if results[t] is None:
                continue
            own = order[starts[t]:starts[t + 1]]
            _, _, _, _, (ptr, V, keep, keys), (pieces, owner) = results[t]
            cells.append((own, ptr, V, keep, keys, pieces, owner))
        return mass, cen, energy, cells


FAR_RING = 32


def far_ring(center, size):
    ang = 2.0 * np.pi * (np.arange(FAR_RING) + 0.5) / FAR_RING
    return center + 20.0 * size * np.column_stack([np.cos(ang), np.sin(ang)])


def shadows(shape, segs):
    """For each boundary segment, the part of the domain strictly beyond its line (None if
    empty).  A reflection across the segment may only be used far from that part, or it
    would own domain points (non-convex domains, e.g. the foundation top beside a dam)."""
    out = []
    lo, hi = np.array(shape.bounds[:2]), np.array(shape.bounds[2:])
    L = 4.0 * float(np.hypot(*(hi - lo)))
    for a, b in segs:
        d = (b - a) / np.hypot(*(b - a))
        n = np.array([-d[1], d[0]])            # inward normal of a CCW boundary
        half = shapely.Polygon([a - L * d, b + L * d, b + L * d - L * n, a - L * d - L * n])
        parts = [g for g in shapely.get_parts(shape.intersection(half))
                 if g.geom_type == "Polygon" and g.area > 1e-12 * shape.area]
        out.append(shapely.MultiPolygon(parts) if parts else None)
    return out


def reflect(seeds, segs, shape_contains, spacing, alpha=1.5, shadow=None, max_spacing=None):
    """PolyMesher reflections of the seeds close to a boundary segment, kept outside and away
    from the segment's shadow.

    spacing: local seed spacing, an array (one per seed), a number, or a function of points;
    max_spacing (an upper bound of it) lets only the seeds within reach be measured."""
    out = []
    fn = spacing if callable(spacing) else None
    if fn is not None and max_spacing is None:
        spacing = fn(seeds)
        fn = None
    for k, (a, b) in enumerate(segs):
        ab = b - a
        L2 = ab @ ab
        t = ((seeds - a) @ ab) / L2
        if max_spacing is not None:
            # the distance to the segment's line is |cross| / |ab|: a superset of the seeds
            # within alpha * spacing, then the same test as below on those
            cross = (seeds[:, 0] - a[0]) * ab[1] - (seeds[:, 1] - a[1]) * ab[0]
            idx = np.flatnonzero((t > -0.05) & (t < 1.05)
                                 & (np.abs(cross) <= alpha * max_spacing * np.sqrt(L2) * (1 + 1e-6)))
        else:
            idx = np.arange(len(seeds))
        S = seeds[idx]
        tk = t[idx]
        proj = a + tk[:, None] * ab
        d = np.hypot(*(S - proj).T)
        if fn is not None:
            sp_all = fn(S)
        elif np.ndim(spacing):
            sp_all = spacing[idx]
        else:
            sp_all = spacing
        m = (tk > -0.05) & (tk < 1.05) & (d < alpha * sp_all) & (d > 0)
        if m.any():
            R = 2.0 * proj[m] - S[m]
            if shadow is not None and shadow[k] is not None:
                sp = sp_all[m] if np.ndim(sp_all) else sp_all
                R = R[shapely.distance(shapely.points(R), shadow[k]) > 3.0 * sp]
            out.append(R)
    if not out:
        return np.zeros((0, 2))
    R = np.concatenate(out)
    return R[~shape_contains(R)]
