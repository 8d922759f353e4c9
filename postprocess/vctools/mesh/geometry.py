"""Small exact-as-floating-point polygon and segment helpers (numpy, vectorised)."""
from __future__ import annotations

import numpy as np

from .errors import MeshError


def as_points(obj, what: str) -> np.ndarray:
    """(n, 2) float array from a list of pairs, with a clear error otherwise."""
    try:
        arr = np.asarray(obj, dtype=float)
    except (TypeError, ValueError) as exc:
        raise MeshError(f"{what}: expected a list of [x, y] pairs, got {obj!r}") from exc
    if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) < 2:
        raise MeshError(f"{what}: expected a list of at least two [x, y] pairs, got {obj!r}")
    if not np.all(np.isfinite(arr)):
        raise MeshError(f"{what}: coordinates must be finite")
    return arr


def signed_area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def diameter(pts: np.ndarray) -> float:
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    return float(np.hypot(*(hi - lo)))


def _orient(a, b, c):
    return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])


def segments_intersect(p1, p2, q1, q2, tol: float) -> bool:
    """True if closed segments p1p2 and q1q2 share a point (tolerance on the orientation tests)."""
    d1, d2 = _orient(q1, q2, p1), _orient(q1, q2, p2)
    d3, d4 = _orient(p1, p2, q1), _orient(p1, p2, q2)
    lp = np.hypot(*(p2 - p1)) + np.hypot(*(q2 - q1))
    t = tol * lp
    if ((d1 > t and d2 < -t) or (d1 < -t and d2 > t)) and ((d3 > t and d4 < -t) or (d3 < -t and d4 > t)):
        return True

    def on_seg(a, b, c, d):
        return abs(d) <= t and min(a[0], b[0]) - tol <= c[0] <= max(a[0], b[0]) + tol and \
            min(a[1], b[1]) - tol <= c[1] <= max(a[1], b[1]) + tol
    return on_seg(q1, q2, p1, d1) or on_seg(q1, q2, p2, d2) or on_seg(p1, p2, q1, d3) or on_seg(p1, p2, q2, d4)


def check_simple_polygon(poly: np.ndarray, name: str) -> np.ndarray:
    """Validate a body polygon and return it counter-clockwise, without a repeated last point."""
    poly = np.asarray(poly, dtype=float)
    if len(poly) > 1 and np.allclose(poly[0], poly[-1]):
        poly = poly[:-1]
    if len(poly) < 3:
        raise MeshError(f"body {name!r}: a polygon needs at least 3 vertices")
    size = diameter(poly)
    tol = 1e-12 * size
    n = len(poly)
    seglen = np.hypot(*(np.roll(poly, -1, axis=0) - poly).T)
    if np.any(seglen <= tol):
        k = int(np.argmin(seglen))
        raise MeshError(f"body {name!r}: repeated vertex {poly[k].tolist()} (zero-length edge {k + 1})")
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        for j in range(i + 1, n):
            if j == i or (j + 1) % n == i or j == (i + 1) % n:
                continue
            c, d = poly[j], poly[(j + 1) % n]
            if segments_intersect(a, b, c, d, 1e-12):
                raise MeshError(
                    f"body {name!r} is self-intersecting: edge {i + 1} {a.tolist()}-{b.tolist()} "
                    f"meets edge {j + 1} {c.tolist()}-{d.tolist()}")
    area = signed_area(poly)
    if abs(area) <= 1e-14 * size * size:
        raise MeshError(f"body {name!r} has zero area")
    if area < 0:
        poly = poly[::-1].copy()
    return poly


def point_segment_distance(pts: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from each point to segment ab (vectorised over points)."""
    ab = b - a
    L2 = float(ab @ ab)
    t = np.clip(((pts - a) @ ab) / L2, 0.0, 1.0) if L2 > 0 else np.zeros(len(pts))
    proj = a + t[:, None] * ab
    return np.hypot(pts[:, 0] - proj[:, 0], pts[:, 1] - proj[:, 1])


def distance_to_segments(pts: np.ndarray, segs: np.ndarray) -> np.ndarray:
    """Distance from points (n,2) to the nearest of segments (m,2,2)."""
    d = np.full(len(pts), np.inf)
    for a, b in segs:
        np.minimum(d, point_segment_distance(pts, a, b), out=d)
    return d


def polyline_segments(poly: np.ndarray, closed: bool) -> np.ndarray:
    if closed:
        return np.stack([poly, np.roll(poly, -1, axis=0)], axis=1)
    return np.stack([poly[:-1], poly[1:]], axis=1)


def project_to_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = float(np.clip((p - a) @ ab / (ab @ ab), 0.0, 1.0))
    if t == 0.0:
        return a.copy()
    if t == 1.0:
        return b.copy()
    return a + t * ab


def points_in_polygon(pts: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Even-odd point-in-polygon test (boundary points: either answer)."""
    x, y = pts[:, 0], pts[:, 1]
    inside = np.zeros(len(pts), dtype=bool)
    n = len(poly)
    for i in range(n):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % n]
        cond = (y1 > y) != (y2 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xint = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
        inside ^= cond & (x < xint)
    return inside


def polygon_moments_csr(ptr: np.ndarray, xy: np.ndarray, origin: np.ndarray | None = None,
                        density=None):
    """Area, centroid and second moment about `origin` of many polygons stored flat.

    Polygon i has vertices xy[ptr[i]:ptr[i+1]].  Each polygon is cut into the fan of
    triangles (o, v_k, v_k+1) with o = origin[i] (or its first vertex), which gives exact
    signed moments for any simple polygon.  With a density, each fan triangle is weighted by
    the density at its centroid (a one-point rule, enough for Lloyd's size grading).
    Returns (mass, centroid (n,2), energy) where energy = int rho |x - o|^2.
    """
    n = len(ptr) - 1
    counts = np.diff(ptr)
    cell = np.repeat(np.arange(n), counts)
    nxt = np.arange(len(xy)) + 1
    nxt[ptr[1:] - 1] = ptr[:-1]
    o = xy[ptr[:-1]] if origin is None else origin
    oc = o[cell]
    a = xy - oc
    b = xy[nxt] - oc
    area2 = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    tri_area = 0.5 * area2
    if density is not None:
        w = tri_area * density(oc + (a + b) / 3.0)
    else:
        w = tri_area
    mass = np.bincount(cell, weights=w, minlength=n)
    cx = np.bincount(cell, weights=w * (a[:, 0] + b[:, 0]) / 3.0, minlength=n)
    cy = np.bincount(cell, weights=w * (a[:, 1] + b[:, 1]) / 3.0, minlength=n)
    # second moment of triangle (0, a, b) about 0: A/6 (|a|^2 + |b|^2 + a.b)
    e = w / 6.0 * ((a * a).sum(1) + (b * b).sum(1) + (a * b).sum(1))
    energy = np.bincount(cell, weights=e, minlength=n)
    with np.errstate(divide="ignore", invalid="ignore"):
        cen = o + np.stack([cx / mass, cy / mass], axis=1)
    return mass, cen, energy
