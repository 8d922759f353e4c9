"""The error estimate of second-order models (estimate_error2 in src/post/estimate.f90,
docs/error-estimate.md) against the true energy-norm error of the element's own stress:
the effectivity index (estimate / true error) must lie in [0.5, 3].

The true error: sqrt(sum_e int_e (s_h - s)^T C^-1 (s_h - s)) with s_h the element's own
stress field, integrated with a rule exact far beyond the degrees involved (a collapsed
8 x 8 Gauss rule, degree 15, on every fan triangle (corner mean, v_k, v_k+1); the 8-node
quad in its natural coordinates).

- k = 2 VEM: s_h is linear per cell, but the HDF5 file holds its mean (S_element, the
  value at the cell's centroid) and the nodal average of the cells' values at each node
  (S_node).  Both are linear in the cells' gradients, and there are about 2.5 nodes per
  cell for 2 gradient unknowns: the gradients are the least-squares solution, the test
  asserts that it reproduces S_node to round-off and that the system has full rank, so
  the reconstruction is the element's own field, not an approximation.
- 6-node triangle (CPE6, straight sides): s_h = D eps of the quadratic through the six
  nodal displacements (the reconstruction above is not unique on structured triangles).
- 8-node quad (CPE8): s_h = D B(xi, eta) u_e from the written displacements, integrated
  in natural coordinates with 8 x 8 Gauss points (exact on these rectangular cells).
"""
import math
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "accuracy"))
import cases  # noqa: E402
import fields  # noqa: E402
import meshes  # noqa: E402


def _triangle_rule(n=8):
    """Collapsed Gauss rule on the reference triangle: barycentric weights (m, 3), weights
    summing to 1; exact for degree 2n - 1."""
    g, w = np.polynomial.legendre.leggauss(n)
    g, w = (g + 1) / 2, w / 2
    a, b = np.meshgrid(g, g, indexing="ij")
    wa, wb = np.meshgrid(w, w, indexing="ij")
    l1 = a.ravel()
    l2 = (b * (1 - a)).ravel()
    ww = (wa * wb * (1 - a)).ravel() * 2
    return np.stack([1 - l1 - l2, l1, l2], -1), ww


def _corner_fans(res):
    off, conn = fields._corners(res["off"], res["conn"])
    return off, conn, fields._fan(res["x"], off, conn)


def vem2_linear_stress(res):
    """Per cell (xx, yy, xy) value at the corner polygon's centroid and gradient (ncell, 3, 3):
    [:, c, 0] the value, [:, c, 1:] the gradient, reconstructed from S_element and S_node."""
    x, off, conn = res["x"], res["off"], res["conn"]
    coff, cconn, (elem, A, B, Cc, area) = _corner_fans(res)
    ne = len(off) - 1
    ea = np.bincount(elem, area, minlength=ne)
    # area centroid of each cell (straight sides)
    cen = np.stack([np.bincount(elem, area * (A[:, i] + B[:, i] + Cc[:, i]) / 3, minlength=ne) / ea
                    for i in range(2)], -1)
    se = res["Se"][:, [0, 1, 3]]
    sn = res["Sn"][:, [0, 1, 3]]
    n = np.diff(off)
    el = np.repeat(np.arange(ne), n)
    cnt = np.bincount(conn, minlength=len(x))
    # node i: (1/cnt_i) sum_e (mean_e + g_e . (x_i - c_e)) = S_node_i
    M = np.zeros((len(x), 2 * ne))
    dx = x[conn] - cen[el]
    np.add.at(M, (conn, 2 * el), dx[:, 0] / cnt[conn])
    np.add.at(M, (conn, 2 * el + 1), dx[:, 1] / cnt[conn])
    out = np.zeros((ne, 3, 3))
    sv = np.linalg.svd(M, compute_uv=False)
    assert sv[-1] > 1e-8 * sv[0], "the nodal averages do not determine the cell gradients"
    for c in range(3):
        rhs = sn[:, c] - np.bincount(conn, se[el, c] / cnt[conn], minlength=len(x))
        g, *_ = np.linalg.lstsq(M, rhs, rcond=None)
        scale = np.abs(sn[:, c]).max() + np.abs(se[:, c]).max()
        # a consistent system: the written fields are one linear field per cell
        assert np.abs(M @ g - rhs).max() <= 1e-9 * scale
        out[:, c, 0] = se[:, c]
        out[:, c, 1:] = g.reshape(ne, 2)
    return out, cen


def true_error_vem2(res, case):
    lin, cen = vem2_linear_stress(res)
    _, _, (elem, A, B, Cc, area) = _corner_fans(res)
    lam, w = _triangle_rule()
    S = fields.compliance(case.E, case.nu, case.plane)
    num = 0.0
    for lq, wq in zip(lam, w):
        p = lq[0] * A + lq[1] * B + lq[2] * Cc
        d = p - cen[elem]
        sh = lin[elem, :, 0] + lin[elem, :, 1] * d[:, :1] + lin[elem, :, 2] * d[:, 1:]
        e = sh - case.sigma(p[:, 0], p[:, 1])
        num += (wq * area * np.einsum("ij,jk,ik->i", e, S, e)).sum()
    return math.sqrt(num)


def true_error_t6(res, case):
    """6-node triangles (straight sides): u_h is the quadratic through the six nodal
    displacements, s_h = D eps(u_h) is linear."""
    x, off, conn, U = res["x"], res["off"], res["conn"], res["U"]
    D = fields.stiffness(case.E, case.nu, case.plane)
    S = fields.compliance(case.E, case.nu, case.plane)
    lam, w = _triangle_rule()
    num = 0.0
    for e in range(len(off) - 1):
        nodes = conn[off[e]:off[e + 1]]
        assert len(nodes) == 6
        X, ue = x[nodes], U[nodes]
        c = X[:3].mean(0)
        P = lambda p: np.array([1, p[0], p[1], p[0] ** 2, p[0] * p[1], p[1] ** 2])  # noqa: E731
        coef = np.linalg.solve(np.array([P(p - c) for p in X]), ue)                 # (6, 2)
        for k in range(3):
            a, b = X[k], X[(k + 1) % 3]
            ar = 0.5 * ((a[0] - c[0]) * (b[1] - c[1]) - (b[0] - c[0]) * (a[1] - c[1]))
            for lq, wq in zip(lam, w):
                p = lq[0] * c + lq[1] * a + lq[2] * b
                q = p - c
                dx = coef[1] + 2 * coef[3] * q[0] + coef[4] * q[1]       # d u / d x
                dy = coef[2] + coef[4] * q[0] + 2 * coef[5] * q[1]       # d u / d y
                d = D @ np.array([dx[0], dy[1], dy[0] + dx[1]]) - case.sigma(p[0:1], p[1:2])[0]
                num += wq * ar * d @ S @ d
    return math.sqrt(num)


XI8 = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)


def _q8(xi, eta):
    """Serendipity shape functions and their natural derivatives at one point (8,), (8, 2)."""
    a, b = XI8[:, 0], XI8[:, 1]
    N = np.where((a != 0) & (b != 0), 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1),
                 np.where(a == 0, 0.5 * (1 - xi * xi) * (1 + b * eta), 0.5 * (1 + a * xi) * (1 - eta * eta)))
    dxi = np.where((a != 0) & (b != 0), 0.25 * a * (1 + b * eta) * (2 * a * xi + b * eta),
                   np.where(a == 0, -xi * (1 + b * eta), 0.5 * a * (1 - eta * eta)))
    deta = np.where((a != 0) & (b != 0), 0.25 * b * (1 + a * xi) * (a * xi + 2 * b * eta),
                    np.where(a == 0, 0.5 * b * (1 - xi * xi), -eta * (1 + a * xi)))
    return N, np.stack([dxi, deta], -1)


def true_error_q8(res, case):
    """In natural coordinates: 8 x 8 Gauss points on [-1, 1]^2, weights times det J."""
    x, off, conn, U = res["x"], res["off"], res["conn"], res["U"]
    assert (np.diff(off) == 8).all()
    D = fields.stiffness(case.E, case.nu, case.plane)
    S = fields.compliance(case.E, case.nu, case.plane)
    g, w = np.polynomial.legendre.leggauss(8)
    cells = conn.reshape(-1, 8)
    X, ue = x[cells], U[cells]                               # (ne, 8, 2)
    num = 0.0
    for a, wa in zip(g, w):
        for b, wb in zip(g, w):
            N, dN = _q8(a, b)
            J = np.einsum("eni,nj->eij", X, dN)               # J[i, j] = d x_i / d xi_j
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
            G = np.einsum("nj,eji->eni", dN, np.linalg.inv(J))  # d N / d x_i
            du = np.einsum("eni,enk->eki", G, ue)             # du[:, k, i] = d u_k / d x_i
            eps = np.stack([du[:, 0, 0], du[:, 1, 1], du[:, 0, 1] + du[:, 1, 0]], -1)
            p = np.einsum("n,eni->ei", N, X)
            d = eps @ D.T - case.sigma(p[:, 0], p[:, 1])
            num += (wa * wb * det * np.einsum("ij,jk,ik->i", d, S, d)).sum()
    return math.sqrt(num)


class Kolosov:
    """Unit square, plane strain, no body force: the Kolosov-Muskhelishvili field of
    phi(z) = psi(z) = exp(z) (every polynomial degree present), exact u on the boundary.
    2 mu (u_x + i u_y) = kappa phi - z conj(phi') - conj(psi), kappa = 3 - 4 nu;
    s_xx + s_yy = 4 Re phi', s_yy - s_xx + 2 i s_xy = 2 (conj(z) phi'' + psi')."""
    name, plane = "kolosov", "strain"
    E, nu = 1.0, 0.3

    def u(self, x, y):
        z = x + 1j * y
        mu, kap = self.E / (2 * (1 + self.nu)), 3 - 4 * self.nu
        w = (kap * np.exp(z) - z * np.conj(np.exp(z)) - np.conj(np.exp(z))) / (2 * mu)
        return np.stack([w.real, w.imag], -1)

    def sigma(self, x, y):
        z = x + 1j * y
        t = 4 * np.exp(z).real
        d = 2 * (np.conj(z) * np.exp(z) + np.exp(z))
        return np.stack([(t - d.real) / 2, (t + d.real) / 2, d.imag / 2], -1)


def _run(exe, work, name, deck_text):
    deck = os.path.join(work, name + ".inp")
    with open(deck, "w") as f:
        f.write(deck_text)
    r = subprocess.run([exe, "-q", deck, "-o", work + "/out"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    base = f"{work}/out/{name}"
    with h5py.File(base + ".h5") as f:
        step = f["steps/0001"]
        eta = step["ERROR_INDICATOR"][...]
        est, energy = step.attrs["error_estimate"], step.attrs["energy_norm"]
    assert (eta >= 0).all()
    assert est == pytest.approx(math.sqrt((eta ** 2).sum()), rel=1e-12)
    return fields.read_result(base + ".h5"), est, energy


def _kolosov_deck(work, shape, n, fam):
    case = Kolosov()
    mform = "vem" if fam.startswith("vem") else "fem"
    if shape == "voronoi":
        mp = meshes.rectangle(work + "/meshes", f"ko_{fam}_{n}", (0, 0, 1, 1), "voronoi", n, formulation=mform, order=2)
    else:
        mp = meshes.rectangle(work + "/meshes", f"ko_{fam}_{n}", (0, 0, 1, 1), shape, (n, n), formulation=mform,
                              order=2)
    m = meshes.read_inp(mp)
    u = case.u(m.xy[:, 0], m.xy[:, 1])
    lines = [f"*INCLUDE, INPUT={mp}", "*MATERIAL, NAME=M", "*ELASTIC", f"{float(case.E)!r}, {float(case.nu)!r}",
             f"*SOLID SECTION, ELSET=B, MATERIAL=M, FORMULATION={mform.upper()}", "1.0", "*BOUNDARY"]
    for k, i in enumerate(m.ids):
        x, y = m.xy[k]
        if min(x, y, 1 - x, 1 - y) < 1e-9:
            lines += [f"{i}, 1, 1, {float(u[k, 0])!r}", f"{i}, 2, 2, {float(u[k, 1])!r}"]
    lines += ["*STEP", "*STATIC", "*END STEP"]
    return case, "\n".join(lines) + "\n"


TRUE = {"vem2-voronoi": true_error_vem2, "vem2-quad": true_error_vem2, "fem-q8": true_error_q8,
        "fem-t6": true_error_t6}


@pytest.mark.parametrize("fam,shape,levels", [
    ("vem2-voronoi", "voronoi", (64, 256)),
    ("fem-q8", "quad", (4, 8)),
    ("fem-t6", "tri", (4, 8)),
])
def test_effectivity_manufactured(tmp_path, exe, fam, shape, levels):
    work = str(tmp_path)
    os.makedirs(work + "/meshes", exist_ok=True)
    for n in levels:
        case, deck = _kolosov_deck(work, shape, n, fam)
        res, est, energy = _run(exe, work, f"ko_{fam}_{n}", deck)
        true = TRUE[fam](res, case)
        eff = est / true
        print(f"kolosov {fam} {n}: estimate {est:.4e} true {true:.4e} effectivity {eff:.3f}")
        assert 0.5 <= eff <= 3.0, f"{fam} {n}: effectivity {eff:.3f}"


# levels 2 and 4 (16 x 2 ... 64 x 4 cells); level 1, a single row of four cells, is
# pre-asymptotic (observed 0.54 for Q8, 0.76 for the VEM)
@pytest.mark.parametrize("fam,levels", [("vem2-voronoi", (2, 4)), ("vem2-quad", (2, 4)), ("fem-q8", (2, 4))])
def test_effectivity_cantilever(tmp_path, exe, fam, levels):
    case = fields.Timoshenko()
    work = str(tmp_path)
    os.makedirs(work + "/decks", exist_ok=True)
    seen = 0
    for run in cases.timoshenko(work, quick=True, families=(fam,)):
        if run.level not in levels:
            continue
        name = f"tc_{fam}_{run.level}"
        with open(f"{work}/decks/{name}.inp", "w") as f:
            f.write(run.deck)
        r = subprocess.run([exe, "-q", f"{work}/decks/{name}.inp", "-o", work + "/out"], capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
        res = fields.read_result(f"{work}/out/{name}.h5")
        with h5py.File(f"{work}/out/{name}.h5") as f:
            est = f["steps/0001"].attrs["error_estimate"]
        true = TRUE[fam](res, case)
        eff = est / true
        print(f"cantilever {fam} {run.level}: estimate {est:.4e} true {true:.4e} effectivity {eff:.3f}")
        assert 0.5 <= eff <= 3.0, f"{fam} {run.level}: effectivity {eff:.3f}"
        seen += 1
    assert seen == len(levels)
