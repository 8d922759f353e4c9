"""Named boundary selections from geometry: node sets and element-side surfaces."""
from __future__ import annotations

import numpy as np

from .errors import MeshError
from .geometry import as_points, distance_to_segments, polyline_segments

GEOMETRY_KEYS = ("x", "y", "segment", "polyline", "circle", "point")


def predicate(spec, tol, where):
    """Function xy -> bool for the geometry of a selection table."""
    kinds = [k for k in GEOMETRY_KEYS if k in spec]
    if len(kinds) != 1:
        raise MeshError(f"{where}: give exactly one of {', '.join(GEOMETRY_KEYS)}; got {sorted(spec)}")
    kind = kinds[0]
    rng = [float(spec.get(k, d)) for k, d in (("xmin", -np.inf), ("xmax", np.inf), ("ymin", -np.inf), ("ymax", np.inf))]

    def in_range(xy):
        return ((xy[:, 0] >= rng[0] - tol) & (xy[:, 0] <= rng[1] + tol)
                & (xy[:, 1] >= rng[2] - tol) & (xy[:, 1] <= rng[3] + tol))
    if kind in ("x", "y"):
        c = float(spec[kind])
        k = 0 if kind == "x" else 1
        base = lambda xy: np.abs(xy[:, k] - c) <= tol   # noqa: E731
    elif kind in ("segment", "polyline"):
        segs = polyline_segments(as_points(spec[kind], f"{where}: {kind}"), closed=False)
        base = lambda xy: distance_to_segments(xy, segs) <= tol   # noqa: E731
    elif kind == "circle":
        c = spec[kind]
        if not isinstance(c, dict) or "center" not in c or "radius" not in c:
            raise MeshError(f"{where}: circle = {{center = [x, y], radius = r}}")
        cen, r = np.asarray(c["center"], float), float(c["radius"])
        base = lambda xy: np.abs(np.hypot(*(xy - cen).T) - r) <= tol   # noqa: E731

        def chord(pa, pb):
            # the midpoint of a chord lies inside the arc by the sagitta r - sqrt(r^2 - L^2 / 4)
            # (exactly: its small-angle form L^2 / (8 r) is short by L^4 / (128 r^3), which
            # rejected the sides of a coarse arc)
            mid = 0.5 * (pa + pb)
            L2 = ((pb - pa) ** 2).sum(1)
            d = r - np.hypot(*(mid - cen).T)
            sag = r - np.sqrt(np.maximum(r * r - 0.25 * L2, 0.0))
            return (base(pa) & base(pb) & (d >= -tol) & (d <= sag * (1 + 1e-9) + tol)
                    & in_range(pa) & in_range(pb))
        f = lambda xy: base(xy) & in_range(xy)   # noqa: E731
        f.edge = chord
        return f
    else:
        p = np.asarray(spec[kind], float)
        base = lambda xy: np.hypot(*(xy - p).T) <= tol   # noqa: E731
    return lambda xy: base(xy) & in_range(xy)


def body_cells(m, spec, where):
    names = [b[0] for b in m.bodies]
    want = spec.get("body")
    if want is None:
        return np.ones(m.ncell, bool)
    want = [want] if isinstance(want, str) else list(want)
    mask = np.zeros(m.ncell, bool)
    for w in want:
        if w not in names:
            raise MeshError(f"{where}: no body named {w!r} (bodies: {names})")
        mask |= m.cell_body == names.index(w)
    return mask


def select(m, spec, tol, where):
    """(cells, sides, nodes) of the boundary edges and boundary nodes matching a selection."""
    pred = predicate(spec, tol, where)
    a, b, cell, side = m.edges()
    bnd = m.boundary_edge_mask() & body_cells(m, spec, where)[cell]
    mid = 0.5 * (m.nodes[a] + m.nodes[b])
    sel = np.zeros(len(a), bool)
    idx = np.flatnonzero(bnd)
    if hasattr(pred, "edge"):
        sel[idx] = pred.edge(m.nodes[a[idx]], m.nodes[b[idx]])
    else:
        sel[idx] = pred(m.nodes[a[idx]]) & pred(m.nodes[b[idx]]) & pred(mid[idx])
    bnodes = np.unique(np.concatenate([a[bnd], b[bnd]]))
    nodes = np.union1d(np.concatenate([a[sel], b[sel]]), bnodes[pred(m.nodes[bnodes])])
    o = np.lexsort((side[sel], cell[sel]))
    if len(nodes) == 0:
        raise MeshError(f"{where}: the selection matches no boundary node")
    return cell[sel][o], side[sel][o], nodes


def check_faces(m, spec, cells, sides, nodes, tol, where):
    """A selection along a line (x, y, segment, polyline, circle) must find element sides,
    every boundary node it matches must lie on one of them, and a segment or polyline
    must be covered over its whole length; else the selection missed (part of) its face."""
    kind = next(k for k in GEOMETRY_KEYS if k in spec)
    if kind == "point":
        return
    if len(cells) == 0:
        raise MeshError(f"{where}: the selection ({kind}) matches {len(nodes)} boundary node(s) but no "
                        f"element side: it misses the face it names (check its coordinates and tolerance)")
    ends = np.array([[m.cell(c)[s - 1], m.cell(c)[s % len(m.cell(c))]] for c, s in zip(cells, sides)])
    loose = np.setdiff1d(nodes, ends.ravel())
    if len(loose):
        raise MeshError(f"{where}: {len(loose)} matched boundary node(s) lie on no selected element side, "
                        f"e.g. at {m.nodes[loose[0]].round(6).tolist()}: the selection covers fewer faces "
                        f"than its geometry implies")
    if kind in ("segment", "polyline"):
        pts = as_points(spec[kind], where)
        want = np.hypot(*np.diff(pts, axis=0).T).sum()
        got = np.hypot(*(m.nodes[ends[:, 1]] - m.nodes[ends[:, 0]]).T).sum()
        if got < want - 2 * tol * len(pts):
            raise MeshError(f"{where}: the selected sides cover a length {got:.6g} of the {kind}'s "
                            f"{want:.6g}: part of it lies on no boundary side")


def add_selection(m, name, spec, tol):
    where = f"selection {name!r}"
    cells, sides, nodes = select(m, spec, tol, where)
    check_faces(m, spec, cells, sides, nodes, tol, where)
    if name in m.nsets or name in m.esurfaces:
        raise MeshError(f"{where}: the name is already used")
    m.nsets[name] = nodes
    if len(cells):
        m.esurfaces[name] = (cells, sides)
    return m


def add_contact(m, name, spec, tol):
    """A contact interface between two bodies: slave nodes and master element sides."""
    where = f"contact {name!r}"
    for k in ("slave", "master"):
        if k not in spec:
            raise MeshError(f"{where}: needs '{k}' (a body name)")
    geo = {k: v for k, v in spec.items() if k not in ("slave", "master", "name", "slave_where", "master_where")}
    sgeo = dict(spec.get("slave_where", geo))
    mgeo = dict(spec.get("master_where", geo))
    sc, ss, sn = select(m, dict(sgeo, body=spec["slave"]), tol, where + " (slave side)")
    mc, ms, mn = select(m, dict(mgeo, body=spec["master"]), tol, where + " (master side)")
    if len(sc) == 0 or len(mc) == 0:
        raise MeshError(f"{where}: no element side of the {'slave' if len(sc) == 0 else 'master'} body "
                        f"lies on the interface")
    m.nsurfaces[f"{name}_SLAVE"] = sn
    m.nsets[f"{name}_SLAVE"] = sn
    m.esurfaces[f"{name}_MASTER"] = (mc, ms)
    m.nsets[f"{name}_MASTER"] = mn
    return m
