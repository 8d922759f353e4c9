"""Size grading: relative cell size g(x) and the seed density rho(x) ~ 1/g(x)^2."""
from __future__ import annotations

import numpy as np

from .errors import MeshError
from .geometry import as_points, distance_to_segments, points_in_polygon, polyline_segments


class Grading:
    """Relative size g = ratio + (1 - ratio) * min(1, d / radius), d = distance to a point or line.

    Several gradings combine by the minimum.  g = 1 far away, `ratio` at the point or line.
    A `field` entry (a .npz file with arrays `points` (n, 2) and `size` (n,), as vc-adapt
    writes them) gives g = the size interpolated from the nearest points / largest size.
    """

    def __init__(self, specs, where: str):
        self.items = []
        self.fields = []
        for _k, s in enumerate(specs or []):
            if not isinstance(s, dict):
                raise MeshError(f"{where}: grading entries are tables, got {s!r}")
            if "field" in s:
                self.fields.append(_size_field(s["field"], where))
                continue
            ratio = float(s.get("ratio", 0.25))
            radius = float(s.get("radius", 0.0))
            if not (0.0 < ratio <= 1.0):
                raise MeshError(f"{where}: grading ratio must be in (0, 1], got {ratio}")
            if radius <= 0.0:
                raise MeshError(f"{where}: grading radius must be > 0, got {radius}")
            if "point" in s:
                pts = as_points([s["point"], s["point"]], f"{where}: grading point")
            elif "line" in s:
                pts = as_points(s["line"], f"{where}: grading line")
            else:
                raise MeshError(f"{where}: grading needs 'point' or 'line'")
            self.items.append((polyline_segments(pts, closed=False), ratio, radius))

    def __bool__(self):
        return bool(self.items) or bool(self.fields)

    def relative_size(self, xy: np.ndarray) -> np.ndarray:
        g = np.ones(len(xy))
        for tree, size in self.fields:
            np.minimum(g, _interpolate(tree, size, xy), out=g)
        for segs, ratio, radius in self.items:
            d = distance_to_segments(xy, segs)
            np.minimum(g, ratio + (1.0 - ratio) * np.minimum(1.0, d / radius), out=g)
        return g


def _interpolate(tree, size, xy, k=8):
    """Size at xy: inverse-distance-squared mean of log(size) over the k nearest points, a
    continuous field (the nearest point's size alone jumps between neighbours, and the
    mesher's seed pairs along joints and interfaces then meet at a jump and leave slivers)."""
    k = min(k, tree.n)
    if k == 1:
        return size[tree.query(xy)[1]]
    d, nb = tree.query(xy, k=k)
    # on (within round-off of) a point: its size
    at = d[:, 0] <= 1e-12 * d[:, -1]
    w = 1.0 / np.where(at[:, None], 1.0, d) ** 2
    out = np.exp((w * np.log(size[nb])).sum(1) / w.sum(1))
    out[at] = size[nb[at, 0]]
    return out


def _size_field(path, where):
    """(KD-tree of the points, sizes relative to the largest) of a size-field file."""
    from scipy.spatial import cKDTree
    try:
        with np.load(path) as z:
            pts, size = np.asarray(z["points"], float), np.asarray(z["size"], float)
    except (OSError, KeyError, ValueError) as e:
        raise MeshError(f"{where}: grading field {path!r}: cannot read points and size ({e})") from None
    if pts.ndim != 2 or pts.shape[1] != 2 or size.shape != (len(pts),) or len(pts) == 0:
        raise MeshError(f"{where}: grading field {path!r}: needs points (n, 2) and size (n,), n > 0")
    if not (np.isfinite(pts).all() and np.isfinite(size).all() and (size > 0).all()):
        raise MeshError(f"{where}: grading field {path!r}: sizes must be finite and > 0")
    return cKDTree(pts), size / size.max()


class Density:
    """Seeds per unit area, piecewise over the bodies of a group, integrating to the targets."""

    def __init__(self, polygons, targets, gradings):
        self.polygons = [np.asarray(p, float) for p in polygons]
        self.gradings = list(gradings)
        self.scale = []
        for poly, n, grad in zip(self.polygons, targets, self.gradings):
            lo, hi = poly.min(0), poly.max(0)
            m = 300
            xs = lo[0] + (np.arange(m) + 0.5) / m * (hi[0] - lo[0])
            ys = lo[1] + (np.arange(m) + 0.5) / m * (hi[1] - lo[1])
            X, Y = np.meshgrid(xs, ys)
            pts = np.column_stack([X.ravel(), Y.ravel()])
            inside = points_in_polygon(pts, poly)
            area = abs(0.5 * np.dot(poly[:, 0], np.roll(poly[:, 1], -1)) - 0.5 * np.dot(np.roll(poly[:, 0], -1), poly[:, 1]))
            g = grad.relative_size(pts[inside]) if grad else np.ones(int(inside.sum()))
            integral = float(np.mean(1.0 / g ** 2)) * area if inside.any() else area
            self.scale.append(n / integral)

    @property
    def uniform(self):
        return len(self.polygons) == 1 and not self.gradings[0]

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        rho = np.full(len(xy), self.scale[0])
        if len(self.polygons) > 1 or self.gradings[0]:
            assigned = np.zeros(len(xy), dtype=bool)
            for poly, c, grad in zip(self.polygons, self.scale, self.gradings):
                m = ~assigned & points_in_polygon(xy, poly) if len(self.polygons) > 1 else ~assigned
                if m.any():
                    g = grad.relative_size(xy[m]) if grad else 1.0
                    rho[m] = c / g ** 2
                assigned |= m
        return rho

    def max_spacing(self) -> float:
        """An upper bound of spacing(): the grading only refines (g <= 1, rho >= scale)."""
        return float(np.sqrt(2.0 / (np.sqrt(3.0) * min(self.scale))))

    def spacing(self, xy: np.ndarray) -> np.ndarray:
        """Seed spacing of a hexagonal pattern with this density: cell area sqrt(3)/2 h^2."""
        return np.sqrt(2.0 / (np.sqrt(3.0) * self(xy)))
