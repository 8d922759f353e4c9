"""Structured quad and triangle meshes: graded rectangles, the Hertz half-disc, example 1's
two-element distorted cantilever."""
from __future__ import annotations

import numpy as np

from .errors import MeshError
from .mesh import Mesh, merge_points


def graded(a, b, n, toward=None, ratio=1.0):
    """n+1 coordinates from a to b; cells shrink geometrically toward `toward` down to
    `ratio` times the largest cell (toward inside [a, b] grades both sides)."""
    n = int(n)
    if n < 1:
        raise MeshError(f"a structured direction needs at least 1 division, got {n}")
    if toward is None or ratio == 1.0:
        return a + (b - a) * np.arange(n + 1) / n
    if not 0 < ratio <= 1:
        raise MeshError(f"grading ratio must be in (0, 1], got {ratio}")
    L = b - a
    c = min(max(toward, a), b)

    def one(n1, length):      # fine at 0, coarse at length
        if n1 == 1:
            return np.array([0.0, length])
        q = (1.0 / ratio) ** (1.0 / (n1 - 1))
        s = q ** np.arange(n1)
        return np.concatenate([[0.0], np.cumsum(s) / s.sum() * length])
    if c - a <= 1e-12 * abs(L):
        x = a + one(n, L)
    elif b - c <= 1e-12 * abs(L):
        x = b - one(n, L)[::-1]
    else:
        n1 = max(1, min(n - 1, int(round(n * (c - a) / L))))
        left = c - one(n1, c - a)[::-1]
        right = c + one(n - n1, b - c)
        x = np.concatenate([left[:-1], right])
    x[0], x[-1] = a, b
    return x


def fractions(n, fine_at_start=False, ratio=1.0):
    t = graded(0.0, 1.0, n, 0.0 if fine_at_start else None, ratio)
    return t


def _grid_cells(nu, nv, offset=0):
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    n0 = offset + i * (nv + 1) + j
    quads = np.stack([n0, n0 + (nv + 1), n0 + (nv + 1) + 1, n0 + 1], axis=-1).reshape(-1, 4)
    return quads


def _orient(nodes, quads):
    P = nodes[quads]
    x, y = P[..., 0], P[..., 1]
    area = 0.5 * (x * np.roll(y, -1, 1) - np.roll(x, -1, 1) * y).sum(1)
    quads = quads.copy()
    quads[area < 0] = quads[area < 0][:, ::-1]
    return quads


def _to_triangles(quads):
    """Each quad into two triangles; the diagonal alternates so that no direction is favoured."""
    k = np.arange(len(quads))
    alt = (k % 2).astype(bool)
    t1 = np.where(alt[:, None], quads[:, [0, 1, 2]], quads[:, [0, 1, 3]])
    t2 = np.where(alt[:, None], quads[:, [0, 2, 3]], quads[:, [1, 2, 3]])
    return np.concatenate([t1, t2])


def _mesh(nodes, quads, name, etype, shape, tol):
    quads = _orient(nodes, quads)
    nodes, inv = merge_points(nodes, tol)
    quads = inv[quads]
    cells = quads if shape == "quad" else _to_triangles(quads)
    if shape == "tri":
        cells = _orient(nodes, cells)
    ncell, k = cells.shape
    ptr = np.arange(ncell + 1, dtype=np.int64) * k
    return Mesh(nodes, ptr, cells.ravel().astype(np.int64), np.zeros(ncell, np.int64), [(name, etype)])


def rectangle(name, box, divisions, shape="quad", etype="CPE4", toward=None, ratio=1.0):
    x0, y0, x1, y1 = map(float, box)
    if not (x1 > x0 and y1 > y0):
        raise MeshError(f"body {name!r}: rectangle needs x0 < x1 and y0 < y1, got {box}")
    nx, ny = map(int, divisions)
    tx, ty = (None, None) if toward is None else toward
    xs = graded(x0, x1, nx, tx, ratio)
    ys = graded(y0, y1, ny, ty, ratio)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    nodes = np.column_stack([X.ravel(), Y.ravel()])
    tol = 1e-12 * np.hypot(x1 - x0, y1 - y0)
    return _mesh(nodes, _grid_cells(nx, ny), name, etype, shape, tol)


def _coons(B, T, L, R, u, v):
    """Transfinite patch from its four sides (B, T indexed by u; L, R by v)."""
    U = u[:, None, None]
    V = v[None, :, None]
    P = ((1 - V) * B[:, None, :] + V * T[:, None, :] + (1 - U) * L[None, :, :] + U * R[None, :, :]
         - ((1 - U) * (1 - V) * B[0] + U * (1 - V) * B[-1] + (1 - U) * V * T[0] + U * V * T[-1]))
    P[:, 0], P[:, -1], P[0, :], P[-1, :] = B, T, L, R
    return P


def half_disc(name, center, radius, divisions, shape="quad", etype="CPE4", ratio=1.0, radial_ratio=1.0,
              core=0.5):
    """The half (x >= center_x) of a disc: a core block and three ring blocks.

    divisions = (n_core_x, n_core_y, n_radial).  Cells are graded toward the lowest point
    of the disc (the Hertz contact point): along the core's x and y, around the lower arc,
    and radially toward the arc.  Cells: nx*ny + nr*(2*nx + ny).
    """
    cx, cy = map(float, center)
    if not float(radius) > 0:
        raise MeshError(f"body {name!r}: the half disc needs radius > 0, got {radius}")
    Rr = float(radius)
    nx, ny, nr = map(int, divisions)
    if min(nx, ny, nr) < 1:
        raise MeshError(f"body {name!r}: half-disc divisions must be >= 1, got {divisions}")
    a = core * Rr
    fx = graded(0.0, 1.0, nx, 0.0, ratio)
    fy = graded(0.0, 1.0, ny, 0.0, ratio)
    fr = graded(0.0, 1.0, nr, 0.0, radial_ratio)

    def arc(theta):
        p = np.column_stack([cx + Rr * np.cos(theta), cy + Rr * np.sin(theta)])
        p[np.isclose(np.abs(theta), np.pi / 2), 0] = cx
        return p

    def seg(p, q, t):
        return p[None, :] + t[:, None] * (q - p)[None, :]
    q = np.pi / 4
    c_bl, c_br = np.array([cx, cy - a]), np.array([cx + a, cy - a])
    c_tl, c_tr = np.array([cx, cy + a]), np.array([cx + a, cy + a])
    P1, P2 = arc(np.array([-q]))[0], arc(np.array([q]))[0]
    bottom, top = np.array([cx, cy - Rr]), np.array([cx, cy + Rr])
    diag1 = seg(P1, c_br, fr)
    diag2 = seg(P2, c_tr, fr)
    patches = []
    # bottom patch: u around (x = 0 to the -45 deg diagonal), v from the arc to the core
    patches.append(_coons(arc(-np.pi / 2 + q * fx), seg(c_bl, c_br, fx), seg(bottom, c_bl, fr), diag1, fx, fr))
    # right patch: u from -45 to +45 deg
    patches.append(_coons(arc(-q + 2 * q * fy), seg(c_br, c_tr, fy), diag1, diag2, fy, fr))
    # top patch: u from x = 0 (top) to the +45 deg diagonal
    patches.append(_coons(arc(np.pi / 2 - q * fx), seg(c_tl, c_tr, fx), seg(top, c_tl, fr), diag2, fx, fr))
    X, Y = np.meshgrid(cx + a * fx, cy - a + 2 * a * fy, indexing="ij")
    core_pts = np.stack([X, Y], -1)
    nodes, quads, off = [], [], 0
    for P in patches + [core_pts]:
        nu, nv = P.shape[0] - 1, P.shape[1] - 1
        nodes.append(P.reshape(-1, 2))
        quads.append(_grid_cells(nu, nv, off))
        off += (nu + 1) * (nv + 1)
    nodes = np.concatenate(nodes)
    quads = np.concatenate(quads)
    return _mesh(nodes, quads, name, etype, shape, 1e-10 * Rr)


def cantilever(name, length=40.0, height=8.0, distortion=0.0, etype="CPE4"):
    """Example 1: two quads, the shared edge from (L/2 - d, 0) to (L/2 + d, b), 2d/b = distortion."""
    L, b = float(length), float(height)
    if not (L > 0 and b > 0):
        raise MeshError(f"body {name!r}: the cantilever needs length > 0 and height > 0, got {length} and {height}")
    d = 0.5 * float(distortion) * b
    if not abs(d) < 0.5 * L:
        raise MeshError(f"cantilever: 2d/b = {distortion} puts the shared edge outside the beam")
    nodes = np.array([[0, 0], [L / 2 - d, 0], [L, 0], [L, b], [L / 2 + d, b], [0, b]], float)
    conn = np.array([0, 1, 4, 5, 1, 2, 3, 4], np.int64)
    return Mesh(nodes, np.array([0, 4, 8], np.int64), conn, np.zeros(2, np.int64), [(name, etype)])
