"""Voronoi meshes of bodies with joints: seeds, Lloyd iterations, cells, split joints."""
from __future__ import annotations

import time

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .errors import MeshError
from .progress import Progress
from .geometry import points_in_polygon, polyline_segments, signed_area
from .mesh import Mesh, _compact, insert_hanging_nodes, merge_close, split_joint
from .sizing import Density, Grading
from .voronoi import Context, Tessellator, _snap, far_ring, reflect, shadows


class VBody:
    def __init__(self, name, polygon, cells, grading=None, etype="VPE"):
        self.name = name
        self.polygon = np.asarray(polygon, float)
        self.cells = int(cells)
        self.grading = grading if grading is not None else Grading([], name)
        self.etype = etype
        if self.cells < 1:
            raise MeshError(f"body {name!r}: cells must be >= 1, got {cells}")


class Joint:
    def __init__(self, name, polyline, master="right"):
        self.name = name
        self.polyline = np.asarray(polyline, float)
        if master not in ("left", "right"):
            raise MeshError(f"joint {name!r}: master must be 'left' or 'right', got {master!r}")
        self.master = master


def _arclength_positions(poly, spacing_fn, name, min_count):
    """Parameters of seed pairs along a polyline, equidistributed in the local spacing."""
    segs = polyline_segments(poly, closed=False)
    lens = np.hypot(*(segs[:, 1] - segs[:, 0]).T)
    total = lens.sum()
    m = 2000
    s = (np.arange(m) + 0.5) / m * total
    pts = _point_at(poly, lens, s)
    h = spacing_fn(pts)
    cum = np.concatenate([[0.0], np.cumsum(total / m / h)])
    count = int(round(cum[-1]))
    if count < min_count:
        raise MeshError(
            f"line {name!r} of length {total:.6g} would get {count} cell(s) along it with the local "
            f"cell size {float(h.min()):.4g}; the target number of cells is too small to honour "
            f"the geometry (raise 'cells' or grade toward the line)")
    targets = (np.arange(count) + 0.5) / count * cum[-1]
    sgrid = np.concatenate([[0.0], (np.arange(m) + 1.0) / m * total])
    return np.interp(targets, cum, sgrid), total, h


def _point_at(poly, lens, s):
    cum = np.concatenate([[0.0], np.cumsum(lens)])
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(lens) - 1)
    t = (s - cum[k]) / lens[k]
    return poly[k] + t[:, None] * (poly[k + 1] - poly[k])


def _dir_at(poly, lens, s):
    cum = np.concatenate([[0.0], np.cumsum(lens)])
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(lens) - 1)
    d = poly[k + 1] - poly[k]
    return d / lens[k][:, None]


def _sample(rng, poly, n, density, shape_contains):
    """n points in the polygon with probability density ~ density (rejection sampling)."""
    lo, hi = poly.min(0), poly.max(0)
    probe = lo + rng.random((4096, 2)) * (hi - lo)
    probe = probe[points_in_polygon(probe, poly)]
    rmax = 1.5 * float(density(probe).max()) if len(probe) else 1.0
    out = []
    have = 0
    while have < n:
        batch = max(1024, 2 * (n - have))
        p = lo + rng.random((batch, 2)) * (hi - lo)
        u = rng.random(batch)
        p = p[points_in_polygon(p, poly) & (u * rmax < density(p))]
        out.append(p)
        have += len(p)
    return np.concatenate(out)[:n]


def voronoi_group(bodies, joints=(), seed=0, lloyd=20, per_tile=4000, processes=None, verbose=False,
                  delaunay=None):
    """Conforming Voronoi mesh of bonded bodies (one region) with joints split open.

    delaunay: 'triangle' or 'qhull' (None: Triangle when installed); both give the same mesh
    up to the last bits where generators are cocircular.
    """
    names = [b.name for b in bodies]
    shapes = []
    for b in bodies:
        sh = shapely.Polygon(b.polygon)
        if not sh.is_valid:
            raise MeshError(f"body {b.name!r} is not a simple polygon ({shapely.is_valid_reason(sh)})")
        shapes.append(sh)
    union = shapely.unary_union(shapes)
    if union.geom_type != "Polygon" or len(union.interiors):
        raise MeshError(f"bonded bodies {names} must form one region without holes")
    asum = sum(s.area for s in shapes)
    if abs(asum - union.area) > 1e-9 * union.area:
        raise MeshError(f"bonded bodies {names} overlap")
    dom = np.asarray(union.exterior.coords)[:-1]
    if signed_area(dom) < 0:
        dom = dom[::-1].copy()
    lo, hi = dom.min(0), dom.max(0)
    size = float(np.hypot(*(hi - lo)))
    tol = 1e-10 * size
    # simplify collinear vertices of the union (bodies' shared corners) keep them: they are nodes
    segs = polyline_segments(dom, closed=True)

    # constraint lines: shared boundaries of bonded bodies, then joints
    lines, kinds, lnames = [], [], []
    for i in range(len(shapes)):
        for j in range(i + 1, len(shapes)):
            inter = shapely.line_merge(shapely.intersection(shapes[i].boundary, shapes[j].boundary))
            for part in shapely.get_parts(inter):
                if part.geom_type == "LineString" and part.length > tol:
                    lines.append(np.asarray(part.coords))
                    kinds.append("interface")
                    lnames.append(f"{names[i]}/{names[j]}")
    dom_shape = union
    boundary = union.exterior
    tips = []
    for jt in joints:
        ls = shapely.LineString(jt.polyline)
        if not ls.is_simple:
            raise MeshError(f"joint {jt.name!r} intersects itself")
        if not union.buffer(tol).covers(ls):
            raise MeshError(f"joint {jt.name!r} leaves its body (bodies {names})")
        if boundary.buffer(tol).covers(ls):
            raise MeshError(f"joint {jt.name!r} lies on the outer boundary of {names}: nothing to open")
        for other, nm in zip(lines, lnames):
            ol = shapely.LineString(other)
            x = ls.intersection(ol)
            if x.is_empty:
                continue
            ends = shapely.MultiPoint([jt.polyline[0], jt.polyline[-1], other[0], other[-1]])
            if x.length > tol and nm.startswith("joint:"):
                raise MeshError(f"joints {jt.name!r} and {nm[6:]!r} overlap")
            if x.length <= tol and not ends.buffer(tol).covers(x):
                what = f"joint {nm[6:]!r}" if nm.startswith("joint:") else f"bonded interface {nm}"
                raise MeshError(f"joint {jt.name!r} crosses {what} at {shapely.get_coordinates(x)[0].tolist()}")
        for end, nb in ((jt.polyline[-1], jt.polyline[-2]), (jt.polyline[0], jt.polyline[1])):
            p = shapely.Point(end)
            on_other = any(shapely.LineString(o).distance(p) <= tol for o in lines)
            if boundary.distance(p) > tol and not on_other:
                d = end - nb
                tips.append((end.copy(), d / np.hypot(*d)))
        lines.append(jt.polyline.copy())
        kinds.append("joint")
        lnames.append(f"joint:{jt.name}")

    density = Density([b.polygon for b in bodies], [b.cells for b in bodies], [b.grading for b in bodies])
    ctx = Context(dom_shape, segs, lines, tips, size, density)
    ctx.backend = delaunay
    rng = np.random.default_rng(seed)

    def contains(P):
        return points_in_polygon(P, dom)

    # fixed seed pairs along every constraint line, a seed beyond each tip
    fixed = []
    for poly, kind, nm in zip(lines, kinds, lnames):
        label = nm.replace("joint:", "joint ")
        # the count check on the whole line, then pairs placed segment by segment
        _arclength_positions(poly, density.spacing, label, 2 if kind == "joint" else 1)
        segpos = []
        for k in range(len(poly) - 1):
            sk, Lk, _ = _arclength_positions(poly[k:k + 2], density.spacing, label, 0) \
                if True else None
            if len(sk) == 0:
                sk = np.array([0.5 * Lk])
            segpos.append([sk, Lk])
        # at a kink, the last pair before and the first pair after sit at the same distance
        # delta from the kink with the same offset: the kink is equidistant from the four
        # seeds, a Voronoi vertex whose edges follow both segments
        deltas = {}
        for k in range(1, len(poly) - 1):
            sa, La = segpos[k - 1]
            sb, Lb = segpos[k]
            dlt = min(La - sa[-1], sb[0])
            sa[-1] = La - dlt
            sb[0] = dlt
            deltas[k] = dlt
        ends = {}
        for k, (sk, Lk) in enumerate(segpos):
            A, B = poly[k], poly[k + 1]
            D = (B - A) / Lk
            N = np.array([-D[1], D[0]])
            P = A + sk[:, None] * D
            a = 0.45 * density.spacing(P)
            if k in deltas:
                a[0] = 0.9 * deltas[k]
            if k + 1 in deltas:
                a[-1] = 0.9 * deltas[k + 1]
            for sign in (1.0, -1.0):
                fixed.append(P + sign * a[:, None] * N)
            if k == 0:
                ends[0] = (sk[0], a[0])
            if k == len(segpos) - 1:
                ends[1] = (Lk - sk[-1], a[-1])
        for tip, d in tips:
            # a seed beyond the tip, equidistant from the last pair: the tip becomes a
            # Voronoi vertex and the tip cell needs no extension cut
            if np.allclose(tip, poly[-1]):
                fixed.append((tip + d * np.hypot(*ends[1]))[None, :])
            elif np.allclose(tip, poly[0]):
                fixed.append((tip + d * np.hypot(*ends[0]))[None, :])
    fixed = np.concatenate(fixed) if fixed else np.zeros((0, 2))
    if len(fixed):
        # keep fixed seeds well inside and clear of the other constraints
        allsegs = np.concatenate([segs] + [polyline_segments(p, False) for p in lines])
        from .geometry import distance_to_segments
        hloc = density.spacing(fixed)
        ok = contains(fixed) & (distance_to_segments(fixed, segs) > 0.3 * hloc)
        dmin = distance_to_segments(fixed, allsegs)
        ok &= dmin > 0.3 * hloc
        fixed = fixed[ok]
        # drop near-duplicates (pairs of two lines meeting at a corner)
        if len(fixed) > 1:
            tree = cKDTree(fixed)
            pairs = tree.query_pairs(0.3 * float(hloc.min()), output_type="ndarray")
            drop = np.zeros(len(fixed), bool)
            for i, j in pairs:
                if not drop[i]:
                    drop[j] = True
            fixed = fixed[~drop]

    free = []
    for b in bodies:
        nfix = int(points_in_polygon(fixed, b.polygon).sum()) if len(fixed) else 0
        nf = b.cells - nfix
        if nf < 0:
            raise MeshError(f"body {b.name!r}: target of {b.cells} cells is too small for its joints and "
                            f"interfaces, which alone need {nfix} cells")
        if nf:
            free.append(_sample(rng, b.polygon, nf, density, contains))
    free = np.concatenate(free) if free else np.zeros((0, 2))
    if len(fixed) and len(free):
        d, _ = cKDTree(fixed).query(free)
        far = d > 0.5 * density.spacing(free)
        # replace seeds too close to the fixed ones by fresh samples elsewhere
        free = free[far]
    nfree = len(free)
    ring = far_ring(0.5 * (lo + hi), size)
    shadow = shadows(dom_shape, segs)
    tess = Tessellator(ctx, per_tile=per_tile, processes=processes)
    hmax = density.max_spacing()
    energies = []
    t0 = time.time()
    progress = Progress(f"meshing {len(free) + len(fixed)} cells: Lloyd iteration")
    try:
        for it in range(lloyd + 1):
            seeds = np.concatenate([free, fixed])
            helpers = np.concatenate([reflect(seeds, segs, contains, density.spacing, shadow=shadow,
                                              max_spacing=hmax), ring])
            final = it == lloyd
            mass, cen, energy, cells = tess.run(seeds, helpers, final=final)
            energies.append(float(energy.sum()))
            if verbose:
                print(f"  lloyd {it:3d}: energy {energies[-1]:.10g}  ({time.time() - t0:.1f} s)")
            else:
                progress.update(it + 1, lloyd + 1)
            if final:
                break
            move = mass[:nfree] > 0
            free = free.copy()
            free[move] = cen[:nfree][move]
    finally:
        progress.done()
        tess.close()

    # assemble the cells: whole Voronoi cells share vertices identified by their triangle's
    # global generator ids; clipped and cut pieces by coordinates
    key_chunks, xy_chunks, lens, owners = [], [], [], []
    piece_chunks, piece_lens = [], []
    for own, ptr, V, keep, keys, pieces, _owner in cells:
        cnt = np.diff(ptr)[keep]
        starts = ptr[:-1][keep]
        rep = np.repeat(starts, cnt) + (np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt))
        xy_chunks.append(V[rep])
        key_chunks.append(keys[rep])
        lens.append(cnt)
        owners.append(own[keep])
        for pc in pieces:
            piece_chunks.append(pc)
            piece_lens.append(len(pc))
    xyp = np.concatenate(xy_chunks) if xy_chunks else np.zeros((0, 2))
    K = np.concatenate(key_chunks).astype(np.int64) if key_chunks else np.zeros((0, 3), np.int64)
    if len(K) and K.max() < 2 ** 21:
        k64 = (K[:, 0] << 42) | (K[:, 1] << 21) | K[:, 2]
        _, first, inv = np.unique(k64, return_index=True, return_inverse=True)
    else:
        _, first, inv = np.unique(xyp, axis=0, return_index=True, return_inverse=True)
    inv = inv.ravel()
    xypc = np.concatenate(piece_chunks) if piece_chunks else np.zeros((0, 2))
    allxy = np.concatenate([xyp[first], xypc])
    nodes, idmap = merge_close(allxy, tol)
    conn = np.concatenate([idmap[inv], idmap[len(first) + np.arange(len(xypc))]]).astype(np.int64)
    nplain = int(sum(len(x) for x in lens))
    cnt = np.concatenate(lens + [np.asarray(piece_lens, np.int64)])
    ptr = np.concatenate([[0], np.cumsum(cnt)]).astype(np.int64)
    # body of each cell: its seed for whole cells, an interior point for pieces
    seeds = np.concatenate([free, fixed])
    reps = [seeds[np.concatenate(owners)]] if owners else []
    if piece_chunks:
        reps.append(_interior_points(piece_chunks))
    reps = np.concatenate(reps)
    cell_body = np.full(len(reps), -1)
    for k, b in enumerate(bodies):
        m = (cell_body < 0) & points_in_polygon(reps, b.polygon)
        cell_body[m] = k
    if (cell_body < 0).any():
        # a whole cell whose seed sits on a body boundary: take the nearest body
        bad = np.flatnonzero(cell_body < 0)
        for i in bad:
            p = shapely.Point(reps[i])
            cell_body[i] = int(np.argmin([s.distance(p) for s in shapes]))
    # body corners and line vertices are nodes exactly; nodes on a boundary or line lie on it
    # (a vertex of a whole cell is farther than 10 tol from every boundary and line: only the
    # nodes from clipped and cut pieces can move)
    plain = np.zeros(len(nodes), dtype=bool)
    plain[idmap[:len(first)]] = True
    cut = np.flatnonzero(~plain)
    nodes[cut] = _snap(nodes[cut], ctx)
    corners = np.concatenate([dom] + [ln for ln in lines])
    if len(cut):
        d, near_c = cKDTree(corners).query(nodes[cut])
        hit = d <= tol
        nodes[cut[hit]] = corners[near_c[hit]]
    mesh = _compact(Mesh(nodes, ptr, conn, cell_body, [(b.name, b.etype) for b in bodies]))
    # nodes made by clipping and cutting may hang on a neighbour's edge
    if len(xypc):
        # (whole cells come first and _compact drops none of them)
        mesh = insert_hanging_nodes(mesh, np.unique(mesh.conn[mesh.ptr[nplain]:]), tol)
    area = mesh.cell_areas()
    if abs(area.sum() - union.area) > 1e-9 * union.area:
        raise MeshError(f"internal error: the cells of {names} cover {area.sum():.15g} of the area "
                        f"{union.area:.15g}")
    if (area <= 0).any():
        raise MeshError(f"internal error: {int((area <= 0).sum())} cells with non-positive area "
                        f"in bodies {names}")
    cidx = mesh.cell_index()
    pairs = np.unique(cidx.astype(np.int64) * (len(mesh.nodes) + 1) + mesh.conn)
    if len(pairs) != len(mesh.conn):
        bad = int(cidx[0]) if len(cidx) else 0
        raise MeshError(f"internal error: a cell of {names} visits a node twice (a sliver where a cell "
                        f"edge runs along a joint); try another seed or more cells")
    for jt in joints:
        mesh = split_joint(mesh, jt.name, jt.polyline, jt.master, tol)
    mesh.info["lloyd_energy"] = energies
    mesh.info["lloyd_seconds"] = time.time() - t0
    mesh.info.setdefault("bodies_polygons", {})
    for b in bodies:
        mesh.info["bodies_polygons"][b.name] = b.polygon
    mesh.info["tol"] = tol
    return mesh


def _interior_points(pcs):
    """_interior_point of many polygons: the centroid when it is inside (vectorised), else
    the same fallbacks one by one."""
    cnt = np.array([len(pc) for pc in pcs])
    xy = np.concatenate(pcs)
    n = len(pcs)
    ptr = np.concatenate([[0], np.cumsum(cnt)])
    cell = np.repeat(np.arange(n), cnt)
    nxt = np.arange(len(xy)) + 1
    nxt[ptr[1:] - 1] = ptr[:-1]
    x, y = xy[:, 0], xy[:, 1]
    xn, yn = x[nxt], y[nxt]
    a = x * yn - xn * y
    A = np.bincount(cell, weights=a, minlength=n) / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.column_stack([np.bincount(cell, weights=(x + xn) * a, minlength=n),
                             np.bincount(cell, weights=(y + yn) * a, minlength=n)]) / (6 * A[:, None])
        # even-odd test of each centroid against its own polygon
        py = c[cell, 1]
        px = c[cell, 0]
        cond = (y > py) != (yn > py)
        xint = x + (py - y) * (xn - x) / (yn - y)
    inside = (np.bincount(cell, weights=(cond & (px < xint)).astype(float), minlength=n) % 2) == 1
    good = inside & (A != 0) & np.all(np.isfinite(c), axis=1)
    out = c.copy()
    for k in np.flatnonzero(~good):
        out[k] = _interior_point(pcs[k])
    return out


def _interior_point(pc):
    c = pc.mean(0)
    x, y = pc[:, 0], pc[:, 1]
    a = x * np.roll(y, -1) - np.roll(x, -1) * y
    A = a.sum() / 2
    if A != 0:
        c = np.array([((x + np.roll(x, -1)) * a).sum(), ((y + np.roll(y, -1)) * a).sum()]) / (6 * A)
    if points_in_polygon(c[None, :], pc)[0]:
        return c
    # ear at the vertex with the largest convex turn
    for k in range(len(pc)):
        p0, p1, p2 = pc[k - 1], pc[k], pc[(k + 1) % len(pc)]
        cr = (p1[0] - p0[0]) * (p2[1] - p1[1]) - (p1[1] - p0[1]) * (p2[0] - p1[0])
        if cr > 0:
            c = (p0 + p1 + p2) / 3.0
            if points_in_polygon(c[None, :], pc)[0]:
                return c
    return pc.mean(0)

