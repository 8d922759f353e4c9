"""Exact fields of the three cases with smooth solutions, and the discrete error norms.

Norms (all relative, computed from the HDF5 output):

* ``u_l2``: nodal displacement error, sqrt(sum_i w_i |u_h(x_i) - u(x_i)|^2 / sum_i w_i |u(x_i)|^2)
  with w_i = sum over the elements e at node i of area(e)/n_nodes(e) (a lumped-area
  quadrature of the L2 norm of the nodal interpolant of the error);
* ``energy``: energy norm of the stress error of the element stress (S_element, the
  element's constant, for VEM projected, stress that the code reports),
  sqrt(sum_e int_e (s_h - s)^T C^-1 (s_h - s) / int_Omega s^T C^-1 s), integrated exactly
  (the integrand is a polynomial of degree <= 2 in every case but the Lame cylinder,
  where the 3-point rule on a fan of triangles per element is accurate to O(h^2) relative
  to the error itself).  This is the energy norm of the error of the strain that the code
  reports (sigma_h = C eps_h), i.e. |u - u_h|_E for FEM and its computable counterpart
  (projection) for VEM.

Second-order elements (k = 2 VEM, Q8, T6; ``order=2``): the element stress is linear, not
constant, and the HDF5 file holds its mean (S_element) and the nodal average (S_node), not
the element's own linear field.  ``energy`` then measures the nodal stress S_node,
interpolated linearly on the fan triangles (centroid value = mean of the element's
corner values): the stress a user of a second-order element looks at.  It is a
recovered (averaged) stress, so for k = 2 the number is that of the nodal stress field,
for k = 1 that of the raw element stress: the comparison favours neither in rate (both
are one order below the displacement: O(h) for k = 1, O(h^2) for k = 2) but the averaged
field can be somewhat more accurate than the raw one at the same mesh.  The fan uses the
corners only (the side nodes are the middles of straight sides); ``u_l2`` spreads each
element's area over all its 2n nodes.
"""
from __future__ import annotations

import math

import h5py
import numpy as np


def compliance(E, nu, plane):
    """3x3 compliance (xx, yy, xy) -> (eps_xx, eps_yy, gamma_xy) for in-plane stresses."""
    if plane == "stress":
        return np.array([[1, -nu, 0], [-nu, 1, 0], [0, 0, 2 * (1 + nu)]]) / E
    return np.array([[1 - nu * nu, -nu * (1 + nu), 0], [-nu * (1 + nu), 1 - nu * nu, 0],
                     [0, 0, 2 * (1 + nu)]]) / E


def stiffness(E, nu, plane):
    return np.linalg.inv(compliance(E, nu, plane))


# --------------------------------------------------------------------------- cases
class Manufactured:
    """Unit square, plane strain, u quadratic: u_x = c(x^2 + 2y^2 - xy), u_y = c(-2x^2 +
    y^2 + 3xy).  Then sigma is linear and -div sigma = b is constant, which a GRAV load
    reproduces exactly; the exact u is prescribed at every boundary node."""
    name, plane = "manufactured", "strain"
    E, nu, c = 100.0, 0.3, 0.01

    def u(self, x, y):
        c = self.c
        return np.stack([c * (x * x + 2 * y * y - x * y), c * (-2 * x * x + y * y + 3 * x * y)], -1)

    def grad(self, x, y):
        c = self.c
        return (c * (2 * x - y), c * (4 * y - x), c * (-4 * x + 3 * y), c * (2 * y + 3 * x))

    def sigma(self, x, y):
        uxx, uxy, uyx, uyy = self.grad(x, y)
        eps = np.stack([uxx, uyy, uxy + uyx], -1)
        return eps @ stiffness(self.E, self.nu, self.plane).T

    def body_force(self):
        lam = self.E * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))
        mu = self.E / (2 * (1 + self.nu))
        c = self.c
        # div u = c(2x - y) + c(2y + 3x) = c(5x + y); lap u = (c(2+4), c(-4+2))
        grad_div = np.array([5 * c, c])
        lap = np.array([6 * c, -2 * c])
        return -((lam + mu) * grad_div + mu * lap)


class Timoshenko:
    """Cantilever [0, L] x [-D/2, D/2], plane stress, parabolic end shear P at x = L
    (Timoshenko & Goodier; the form of Augarde & Deeks 2008): sigma_xx = -P(L-x)y/I,
    tau = P/(2I)(D^2/4 - y^2); exact u prescribed on x = 0."""
    name, plane = "timoshenko", "stress"
    L, D, E, nu, P = 48.0, 12.0, 3.0e7, 0.3, 1000.0

    @property
    def I(self):
        return self.D ** 3 / 12

    def u(self, x, y):
        L, D, E, nu, P, I = self.L, self.D, self.E, self.nu, self.P, self.I
        ux = -P * y / (6 * E * I) * ((6 * L - 3 * x) * x + (2 + nu) * (y * y - D * D / 4))
        uy = P / (6 * E * I) * (3 * nu * y * y * (L - x) + (4 + 5 * nu) * D * D * x / 4 + (3 * L - x) * x * x)
        return np.stack([ux, uy], -1)

    def sigma(self, x, y):
        L, D, P, I = self.L, self.D, self.P, self.I
        return np.stack([-P * (L - x) * y / I, 0 * x, P / (2 * I) * (D * D / 4 - y * y)], -1)

    def tip(self):
        return float(self.u(np.array(self.L), np.array(0.0))[1])


class Lame:
    """Thick cylinder a <= r <= b under internal pressure p, plane strain, quarter model."""
    name, plane = "lame", "strain"
    a, b, p, E, nu = 1.0, 2.0, 1.0, 1000.0, 0.3

    def ur(self, r):
        a, b, p, E, nu = self.a, self.b, self.p, self.E, self.nu
        return (1 + nu) * a * a * p / (E * (b * b - a * a)) * ((1 - 2 * nu) * r + b * b / r)

    def u(self, x, y):
        r = np.hypot(x, y)
        ur = self.ur(r)
        return np.stack([ur * x / r, ur * y / r], -1)

    def polar_stress(self, r):
        a, b, p = self.a, self.b, self.p
        k = a * a * p / (b * b - a * a)
        return k * (1 - b * b / (r * r)), k * (1 + b * b / (r * r))     # s_rr, s_tt

    def sigma(self, x, y):
        r = np.hypot(x, y)
        srr, stt = self.polar_stress(r)
        c, s = x / r, y / r
        return np.stack([srr * c * c + stt * s * s, srr * s * s + stt * c * c, (srr - stt) * s * c], -1)


def check_exact(case, pts=None):
    """Self-check of an exact field: sigma = C eps(u) and div sigma + b = 0 by central
    differences at a few interior points (raises on a typo in the formulas)."""
    rng = np.random.default_rng(0)
    if pts is None:
        pts = rng.uniform(0.2, 0.8, (5, 2))
    h = 1e-5
    C = stiffness(case.E, case.nu, case.plane)
    for x, y in pts:
        du_dx = (case.u(np.array(x + h), np.array(y)) - case.u(np.array(x - h), np.array(y))) / (2 * h)
        du_dy = (case.u(np.array(x), np.array(y + h)) - case.u(np.array(x), np.array(y - h))) / (2 * h)
        eps = np.array([du_dx[0], du_dy[1], du_dy[0] + du_dx[1]])
        s = case.sigma(np.array(x), np.array(y))
        assert np.allclose(C @ eps, s, rtol=1e-5, atol=1e-7 * np.abs(s).max()), (case.name, C @ eps, s)
        ds_dx = (case.sigma(np.array(x + h), np.array(y)) - case.sigma(np.array(x - h), np.array(y))) / (2 * h)
        ds_dy = (case.sigma(np.array(x), np.array(y + h)) - case.sigma(np.array(x), np.array(y - h))) / (2 * h)
        div = np.array([ds_dx[0] + ds_dy[2], ds_dx[2] + ds_dy[1]])
        b = case.body_force() if hasattr(case, "body_force") else np.zeros(2)
        scale = np.abs(s).max() + 1e-30
        assert np.allclose(div + b, 0, atol=1e-5 * scale), (case.name, div, b)


# --------------------------------------------------------------------------- errors
def read_result(h5path):
    with h5py.File(h5path, "r") as f:
        x = f["mesh/coordinates"][...]
        off = f["mesh/element_offsets"][...]
        conn = f["mesh/element_connectivity"][...]
        step = f["steps"][sorted(f["steps"])[0]]
        U = step["U"][...]
        Se = step["S_element"][...]
        Sn = step["S_node"][...]
        contact = None
        if "contact" in step:
            g = step["contact/pair_1"]
            contact = {k: g[k][...] for k in ("coordinates", "COPEN", "CPRESS", "STATUS", "CNAREA") if k in g}
    return dict(x=x, off=off, conn=conn, U=U, Se=Se, Sn=Sn, contact=contact)


def _fan(x, off, conn):
    """Triangles (centroid-of-vertices, v_k, v_k+1) of every element: element index,
    the three corners and the areas."""
    n = np.diff(off)
    elem = np.repeat(np.arange(len(n)), n)
    pos = np.arange(len(conn))
    nxt = pos + 1
    last = off[1:] - 1
    nxt[last] = off[:-1]
    P = x[conn]
    cen = np.add.reduceat(P, off[:-1], axis=0) / n[:, None]
    A, B, Cc = cen[elem], P, x[conn[nxt]]
    area = 0.5 * ((B[:, 0] - A[:, 0]) * (Cc[:, 1] - A[:, 1]) - (Cc[:, 0] - A[:, 0]) * (B[:, 1] - A[:, 1]))
    return elem, A, B, Cc, area


def _corners(off, conn):
    """Offsets and connectivity of the corners of second-order cells (the first half of
    each cell's nodes: corners first, then the side nodes)."""
    n = np.diff(off) // 2
    keep = np.concatenate([np.arange(o, o + k) for o, k in zip(off[:-1], n)])
    return np.concatenate([[0], np.cumsum(n)]), conn[keep]


def energy_error(res, case, order=1):
    """Relative energy-norm error of the element stress (order 1) or of the nodal stress
    (order 2; see the module docstring)."""
    off, conn = (res["off"], res["conn"]) if order == 1 else _corners(res["off"], res["conn"])
    elem, A, B, Cc, area = _fan(res["x"], off, conn)
    S = compliance(case.E, case.nu, case.plane)
    if order == 1:
        corner_vals = None
        sh = res["Se"][:, [0, 1, 3]][elem]
    else:
        Sn = res["Sn"][:, [0, 1, 3]]
        n = np.diff(off)
        cen = np.add.reduceat(Sn[conn], off[:-1], axis=0) / n[:, None]
        pos = np.arange(len(conn))
        nxt = pos + 1
        nxt[off[1:] - 1] = off[:-1]
        corner_vals = (cen[elem], Sn[conn], Sn[conn[nxt]])       # at A, B, Cc
    num = den = 0.0
    for k, q in enumerate(((A + B) / 2, (B + Cc) / 2, (Cc + A) / 2)):      # edge midpoints: exact for degree 2
        s = case.sigma(q[:, 0], q[:, 1])
        if corner_vals is not None:
            a_, b_ = ((0, 1), (1, 2), (2, 0))[k]
            sh = (corner_vals[a_] + corner_vals[b_]) / 2
        d = sh - s
        num += (area / 3 * np.einsum("ij,jk,ik->i", d, S, d)).sum()
        den += (area / 3 * np.einsum("ij,jk,ik->i", s, S, s)).sum()
    return math.sqrt(num / den)


def nodal_weights(res, order=1):
    x, off, conn = res["x"], res["off"], res["conn"]
    coff, cconn = (off, conn) if order == 1 else _corners(off, conn)
    elem, A, B, Cc, area = _fan(x, coff, cconn)
    ea = np.bincount(elem, area)
    n = np.diff(off)
    w = np.zeros(len(x))
    np.add.at(w, conn, np.repeat(ea / n, n))
    return w


def u_l2_error(res, case, order=1):
    w = nodal_weights(res, order)
    ue = case.u(res["x"][:, 0], res["x"][:, 1])
    d = res["U"] - ue
    return math.sqrt((w * (d * d).sum(1)).sum() / (w * (ue * ue).sum(1)).sum())
