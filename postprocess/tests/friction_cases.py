"""Decks and closed forms of the friction verification cases (docs/friction-verification.md),
shared by the tests (test_friction_verification.py) and the convergence study
(bench/friction_verification.py).

F4, a closed inclined crack with Coulomb friction under far-field compression, and F5,
Cattaneo-Mindlin partial slip of a cylinder on a half-plane of the same material (the
friction anchors' numbering).  Each deck is a structured mesh of quadrilaterals (CPE4 or
VPE), graded geometrically away from the contact zone, written with Python floats.
"""
import pathlib
import subprocess

import h5py
import numpy as np


def graded(inner, h, outer, ratio):
    """Coordinates from 0 to `outer`: spacing h up to `inner` (a multiple of h), then
    growing by `ratio` per element; the last element ends exactly at `outer`."""
    n = int(round(inner / h))
    xs = [i * h for i in range(n + 1)]
    step = h
    while xs[-1] < outer:
        step *= ratio
        xs.append(xs[-1] + step)
    # the last spacing taken up to `outer` (merged with the one before when too short)
    if len(xs) > n + 2 and outer - xs[-2] < 0.5 * step:
        xs.pop()
    xs[-1] = outer
    return np.array(xs)


def symmetric(inner, h, outer, ratio):
    """Graded coordinates from -outer to outer, spacing h on [-inner, inner]."""
    half = graded(inner, h, outer, ratio)
    return np.concatenate([-half[:0:-1], half])


def write(path, lines):
    path.write_text("\n".join(lines) + "\n")
    return path


def quads(ids):
    """Counter-clockwise quadrilaterals of a node id grid ids[j, i] (row j along y)."""
    ny, nx = ids.shape[0] - 1, ids.shape[1] - 1
    return [(ids[j, i], ids[j, i + 1], ids[j + 1, i + 1], ids[j + 1, i]) for j in range(ny) for i in range(nx)]


def edge_forces(xs, traction):
    """Consistent nodal forces of a uniform traction (2-vector) on the polyline of
    coordinates xs (1D, along the edge): each node takes half of its adjacent edges."""
    lengths = np.diff(xs)
    trib = np.zeros(len(xs))
    trib[:-1] += 0.5 * lengths
    trib[1:] += 0.5 * lengths
    return np.outer(trib, traction)


# ------------------------------------------------------------------------------------------------
# F4: closed inclined crack


CRACK = dict(E=1.0e4, nu=0.25, sigma=10.0, a=1.0)


def crack_slip(x, beta_deg, mu, cohesion=0.0, E=CRACK["E"], nu=CRACK["nu"], sigma=CRACK["sigma"], a=CRACK["a"]):
    """Sliding displacement delta(x) = 4 (1 - nu^2) tau_eff sqrt(a^2 - x^2) / E of a closed
    crack of half-length a under uniaxial compression sigma at beta to the crack, plane
    strain, Mohr-Coulomb friction mu with cohesion c: tau_eff = sigma sin(b) cos(b) - c
    - mu sigma sin^2(b), 0 when negative (the crack sticks)."""
    b = np.radians(beta_deg)
    tau_eff = max(0.0, sigma * np.sin(b) * (np.cos(b) - mu * np.sin(b)) - cohesion)
    return 4.0 * (1.0 - nu**2) * tau_eff * np.sqrt(np.clip(a**2 - np.asarray(x) ** 2, 0.0, None)) / E


def crack_deck(path, n_half, beta_deg, mu, etype="CPE4", slope=None, width=20.0, ratio=1.15, cohesion=0.0,
               pair="NODE TO SURFACE, SMALL SLIDING"):
    """A crack along y = 0 from x = -a to a (a = 1) inside the plate [-W, W]^2, W = width a,
    n_half elements along the half-crack (h = a / n_half) and the mesh graded by `ratio`
    beyond [-1.5 a, 1.5 a] x [-0.5 a, 0.5 a].  The crack's faces are the nodes of y = 0
    with |x| < a doubled (the tips shared, as vctools.mesh's joints): the upper face is
    the slave node surface (tips left out), the lower face's element sides the master,
    NODE TO SURFACE, SMALL SLIDING, HARD (or `pair`: SURFACE TO SURFACE takes the upper
    face's element sides as the slave); `*FRICTION` mu (with the stick slope when given,
    else exact stick; `COHESION=` when cohesion > 0).  The uniform stress -sigma d d^T, d = (cos b, sin b), is
    applied as the consistent nodal forces of its tractions on the four sides; two
    corner nodes hold the rigid motions (the loads balance, so their reactions vanish)."""
    a, sigma = CRACK["a"], CRACK["sigma"]
    h = a / n_half
    xs = symmetric(1.5 * a, h, width * a, ratio)
    ys = symmetric(0.5 * a, h, width * a, ratio)
    nx, ny = len(xs), len(ys)
    ids = 1 + np.arange(nx * ny).reshape(ny, nx)
    j0 = int(np.argmin(np.abs(ys)))
    on_crack = [i for i in range(nx) if abs(xs[i]) < a - 0.5 * h]
    dup = {int(ids[j0, i]): nx * ny + 1 + k for k, i in enumerate(on_crack)}
    lines = ["*HEADING", f"F4 closed inclined crack, beta {float(beta_deg)!r}, mu {float(mu)!r}, h = a/{n_half}", "*NODE"]
    lines += [f"{ids[j, i]}, {float(xs[i])!r}, {float(ys[j])!r}" for j in range(ny) for i in range(nx)]
    lines += [f"{dup[int(ids[j0, i])]}, {float(xs[i])!r}, 0.0" for i in on_crack]
    lower = quads(ids[: j0 + 1])
    upper = [tuple(dup.get(int(n), int(n)) for n in q) for q in quads(ids[j0:])]
    lines += [f"*ELEMENT, TYPE={etype}, ELSET=LOWER"] + [f"{e + 1}, " + ", ".join(map(str, q)) for e, q in enumerate(lower)]
    nl = len(lower)
    lines += [f"*ELEMENT, TYPE={etype}, ELSET=UPPER"]
    lines += [f"{nl + e + 1}, " + ", ".join(map(str, q)) for e, q in enumerate(upper)]
    # the lower row of elements under the crack: their side S3 (nodes 3-4) lies on y = 0
    master = [nl - (nx - 1) + i + 1 for i in range(nx - 1) if abs(xs[i] + xs[i + 1]) * 0.5 < a]
    lines += ["*MATERIAL, NAME=ROCK", "*ELASTIC", f"{float(CRACK['E'])!r}, {float(CRACK['nu'])!r}",
              "*SOLID SECTION, ELSET=LOWER, MATERIAL=ROCK", "1.0", "*SOLID SECTION, ELSET=UPPER, MATERIAL=ROCK", "1.0",
              ]
    if pair.startswith("SURFACE TO SURFACE"):
        # the upper row's elements over the crack: their side S1 (nodes 1-2) lies on y = 0
        lines += ["*SURFACE, NAME=CRACK_SLAVE"] + [f"{e + nx - 1}, S1" for e in master]
    else:
        lines += ["*SURFACE, NAME=CRACK_SLAVE, TYPE=NODE"] + [str(v) for v in dup.values()]
    lines += ["*SURFACE, NAME=CRACK_MASTER"] + [f"{e}, S3" for e in master]
    friction = f"{float(mu)!r}" + (f", {float(slope)!r}" if slope is not None else "")
    param = f", COHESION={float(cohesion)!r}" if cohesion > 0.0 else ""
    lines += ["*SURFACE INTERACTION, NAME=JOINT", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD", f"*FRICTION{param}",
              friction, f"*CONTACT PAIR, INTERACTION=JOINT, TYPE={pair}", "CRACK_SLAVE, CRACK_MASTER",
              "*BOUNDARY", f"{ids[0, 0]}, 1, 2", f"{ids[0, -1]}, 2, 2"]
    b = np.radians(beta_deg)
    d = np.array([np.cos(b), np.sin(b)])
    stress = -sigma * np.outer(d, d)
    forces = np.zeros((nx * ny + 1, 2))
    for side_ids, coords, normal in ((ids[0], xs, (0.0, -1.0)), (ids[-1], xs, (0.0, 1.0)),
                                     (ids[:, 0], ys, (-1.0, 0.0)), (ids[:, -1], ys, (1.0, 0.0))):
        forces[side_ids] += edge_forces(coords, stress @ np.array(normal))
    lines += ["*STEP", "*STATIC", "*CLOAD"]
    for n in range(1, nx * ny + 1):
        for dof in (0, 1):
            if forces[n, dof] != 0.0:
                lines.append(f"{n}, {dof + 1}, {float(forces[n, dof])!r}")
    lines += ["*NODE FILE", "U, RF", "*CONTACT FILE", "CDIS, CSTR", "*END STEP"]
    return write(path, lines)


def run(exe, path, *args):
    """Runs vemcontact on a deck (quiet); returns the HDF5 result path."""
    out = path.parent / ("out_" + path.stem)
    r = subprocess.run([exe, "-q", *args, "-o", str(out), str(path)], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"vemcontact failed on {path}: {r.stderr}")
    return out / (path.stem + ".h5")


def pair_results(h5, step="0001", pair="pair_1"):
    """The slave nodes' results of a pair, sorted by x: a dict of arrays (x, y, CPRESS,
    CSHEAR, CSLIP, COPEN, CNAREA, STATUS) and the contact iterations of the step."""
    with h5py.File(h5, "r") as f:
        g = f[f"steps/{step}/contact/{pair}"]
        res = {k: np.array(g[k]) for k in ("CPRESS", "CSHEAR", "CSLIP", "COPEN", "CNAREA", "STATUS") if k in g}
        xy = np.array(g["coordinates"])
        it = f[f"steps/{step}/contact"].get("iterations")
        iterations = int(np.array(it["iteration"]).size) if it is not None else 0
    order = np.argsort(xy[:, 0])
    res = {k: v[order] for k, v in res.items()}
    res["x"], res["y"] = xy[order, 0], xy[order, 1]
    return res, iterations


def crack_errors(res, beta_deg, mu, cohesion=0.0):
    """Errors of the computed slip against crack_slip: relative error of delta at x = 0
    (delta_max), and the relative L2 error of the profile (tributary-weighted sums over
    the slave nodes)."""
    exact = crack_slip(res["x"], beta_deg, mu, cohesion)
    slip = np.abs(res["CSLIP"])
    i0 = int(np.argmin(np.abs(res["x"])))
    w = res["CNAREA"]
    dmax = slip[i0] / exact[i0] - 1.0
    l2 = np.sqrt(np.sum(w * (slip - exact) ** 2) / np.sum(w * exact**2))
    return dmax, l2


# ------------------------------------------------------------------------------------------------
# F5: Cattaneo-Mindlin


MINDLIN = dict(E=1.0e3, nu=0.3, R=1000.0, mu=0.3)


def hertz_half_width(P, E=MINDLIN["E"], nu=MINDLIN["nu"], R=MINDLIN["R"]):
    """Hertz's contact half-width a = sqrt(4 P R / (pi E*)) of a cylinder pressed by P (per
    unit thickness) on a half-plane, plane strain, both of (E, nu): 1/E* = 2 (1 - nu^2)/E."""
    estar = E / (2.0 * (1.0 - nu**2))
    return np.sqrt(4.0 * P * R / (np.pi * estar))


def mindlin_shear(x, P, Q, mu=MINDLIN["mu"], **kw):
    """Cattaneo-Mindlin's shear traction q(x) (the sign of Q) and stick half-width c for the
    normal load P then the tangential load Q < mu P: q = mu p0 sqrt(1 - x^2/a^2) less
    mu p0 (c/a) sqrt(1 - x^2/c^2) inside the stick zone |x| < c, c/a = sqrt(1 - Q/(mu P))."""
    a = hertz_half_width(P, **kw)
    p0 = 2.0 * P / (np.pi * a)
    c = a * np.sqrt(1.0 - abs(Q) / (mu * P))
    x = np.asarray(x, dtype=float)
    q = mu * p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    q = q - mu * p0 * (c / a) * np.sqrt(np.clip(1.0 - (x / c) ** 2, 0.0, None))
    return np.sign(Q) * q, c, a


def mindlin_slip(x, P, Q, mu=MINDLIN["mu"], E=MINDLIN["E"], nu=MINDLIN["nu"], **kw):
    """Cattaneo-Mindlin's relative slip |s(x)| of the surfaces: 0 in the stick zone, and
    (mu p0 / (a E*)) [|x| sqrt(x^2 - c^2) - c^2 ln((|x| + sqrt(x^2 - c^2)) / c)] for
    c <= |x| <= a (the friction anchors' 1b, derived there and checked numerically)."""
    _, c, a = mindlin_shear(x, P, Q, mu, E=E, nu=nu, **kw)
    estar = E / (2.0 * (1.0 - nu**2))
    p0 = 2.0 * P / (np.pi * a)
    ax = np.abs(np.asarray(x, dtype=float))
    s = np.zeros_like(ax)
    z = (ax > c) & (ax <= a)
    r = np.sqrt(ax[z] ** 2 - c**2)
    s[z] = mu * p0 / (a * estar) * (ax[z] * r - c**2 * np.log((ax[z] + r) / c))
    return s


def hertz_pressure(x, P, **kw):
    """Hertz's pressure p(x) = p0 sqrt(1 - x^2/a^2), p0 = 2 P / (pi a)."""
    a = hertz_half_width(P, **kw)
    return 2.0 * P / (np.pi * a) * np.sqrt(np.clip(1.0 - (np.asarray(x) / a) ** 2, 0.0, None))


def mindlin_deck(path, n_a, press=-0.045, shift=0.010, etype="CPE4", width=25.0, ratio=1.15, increments=4,
                 slope=None, pair="NODE TO SURFACE, SMALL SLIDING"):
    """A cylinder of radius R on a half-plane, both (E, nu), plane strain: the lower body
    [-W, W] x [-W, 0] (bottom held), the upper body [-W, W] x [y(x), W] above the curve
    y = x^2 / (2R) (Hertz's gap: the cylinder's profile near the contact), continued by
    its tangent beyond |x| = 4 a0 (never in contact); W = width a0.  The upper body's top
    is moved as a rigid face (no rotation): step 1 down by -press (HARD contact,
    *FRICTION mu, exact stick or the stick slope), step 2 along x by `shift` in
    `increments` fixed increments, the vertical displacement kept (contact results and
    iteration records of every increment: FREQUENCY=1; the defaults give
    P = 9.89, Q / (mu P) = 0.50).  R = 1000 makes a0 / R = 0.005 (a0 = 4.814, Hertz's
    half-width at P = 10): Hertz's and Mindlin's half-plane theory neglects the
    surface's slope, and the normal traction on the curved face has a tangential part
    of about p x / R, which friction locks in while pressing (measured 0.6 % of mu p0
    at a0 / R = 0.005, 3 % at 0.048, R = 10).  Element size
    h = a0 / n_a on |x| <= 1.6 a0, graded by `ratio` beyond and below.  The contact
    resultants P and Q are measured (sums of CPRESS and CSHEAR times CNAREA) and the
    closed forms evaluated at them.  NODE TO SURFACE, SMALL SLIDING, the upper body's
    bottom the slave (element sides), the flat top of the lower body the master (its
    tangent is x, the direction of Mindlin's shear); the nodes of both faces have the
    same x.  `pair` SURFACE TO SURFACE needs VPE (node insertion)."""
    a0 = hertz_half_width(10.0)
    h = a0 / n_a
    W, R = width * a0, MINDLIN["R"]
    xs = symmetric(round(1.6 * n_a) * h, h, W, ratio)
    ss = graded(0.0, h, W, ratio)                  # depth below the surface: 0 .. W
    x1 = 4.0 * a0

    def profile(x):
        """Hertz's gap x^2 / (2R), continued by its tangent beyond |x| = x1."""
        ax = min(abs(x), x1)
        return ax * ax / (2.0 * R) + (abs(x) - ax) * x1 / R

    nb = len(xs) * len(ss)
    lid = 1 + np.arange(nb).reshape(len(ss), len(xs))[::-1]     # row 0 at the bottom
    uid = nb + 1 + np.arange(nb).reshape(len(ss), len(xs))      # row 0 at the surface
    lines = ["*HEADING", f"F5 Cattaneo-Mindlin, cylinder R = {float(R)!r} on a half-plane, h = a/{n_a}", "*NODE"]
    for j, s in enumerate(ss):
        lines += [f"{lid[::-1][j, i]}, {float(x)!r}, {float(-s)!r}" for i, x in enumerate(xs)]
    for j, s in enumerate(ss):
        for i, x in enumerate(xs):
            y0 = profile(x)
            lines.append(f"{uid[j, i]}, {float(x)!r}, {float(y0 + s * (W - y0) / W)!r}")
    lower, upper = quads(lid), quads(uid)
    lines += [f"*ELEMENT, TYPE={etype}, ELSET=PLANE"] + [f"{e + 1}, " + ", ".join(map(str, q)) for e, q in enumerate(lower)]
    ne = len(lower)
    lines += [f"*ELEMENT, TYPE={etype}, ELSET=CYLINDER"]
    lines += [f"{ne + e + 1}, " + ", ".join(map(str, q)) for e, q in enumerate(upper)]
    nx = len(xs) - 1
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{float(MINDLIN['E'])!r}, {float(MINDLIN['nu'])!r}",
              "*SOLID SECTION, ELSET=PLANE, MATERIAL=M", "1.0", "*SOLID SECTION, ELSET=CYLINDER, MATERIAL=M", "1.0",
              "*SURFACE, NAME=CYL_FACE"] + [f"{ne + i + 1}, S1" for i in range(nx)]
    lines += ["*SURFACE, NAME=PLANE_FACE"] + [f"{ne - nx + i + 1}, S3" for i in range(nx)]
    friction = f"{float(MINDLIN['mu'])!r}" + (f", {float(slope)!r}" if slope is not None else "")
    lines += ["*SURFACE INTERACTION, NAME=I", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD", "*FRICTION", friction,
              f"*CONTACT PAIR, INTERACTION=I, TYPE={pair}", "CYL_FACE, PLANE_FACE",
              "*NSET, NSET=BOTTOM"] + [str(n) for n in lid[0]]
    lines += ["*NSET, NSET=TOP"] + [str(n) for n in uid[-1]]
    lines += ["*BOUNDARY", "BOTTOM, 1, 2",
              "*STEP", "*STATIC", "*BOUNDARY", "TOP, 1, 1, 0.0", f"TOP, 2, 2, {float(press)!r}",
              "*CONTACT FILE, FREQUENCY=1", "CDIS, CSTR", "*END STEP",
              "*STEP", "*STATIC, DIRECT", f"{float(1.0 / increments)!r}, 1.0", "*BOUNDARY",
              f"TOP, 1, 1, {float(shift)!r}", f"TOP, 2, 2, {float(press)!r}", "*END STEP"]
    return write(path, lines)


def mindlin_errors(res, mu=MINDLIN["mu"], slope=None):
    """From the slave nodes' results of the shear step: the measured P, Q; the stick
    half-width c_h (midway between the outermost STICK node and the next node, averaged
    over both sides) and the closed form's c (at the measured P, Q); the relative L2
    error of CSHEAR against q(x) (tributary-weighted), of CPRESS against Hertz and of
    |CSLIP| against Mindlin's slip (with a stick slope, less the elastic slip
    |CSHEAR| / slope that CSLIP includes and the theory has not); the largest |CSLIP|
    of a sticking node."""
    w = res["CNAREA"]
    P = float(np.sum(res["CPRESS"] * w))
    Q = float(np.sum(res["CSHEAR"] * w))
    q, c, a = mindlin_shear(res["x"], P, Q, mu)
    x, stick = res["x"], res["STATUS"] == 3
    ends = []
    for side in (1.0, -1.0):
        xs = np.sort(side * x[(side * x >= 0.0)])
        st = np.sort(side * x[(side * x >= 0.0) & stick])
        last = st[-1]
        nxt = xs[xs > last][0]
        ends.append(0.5 * (last + nxt))
    c_h = 0.5 * (ends[0] + ends[1])
    # inside the stick zone mu p - |q| = mu p0 (c/a) sqrt(1 - x^2/c^2): its square is
    # linear in x^2 and vanishes at c; a least-squares line through the sticking nodes
    # (the outermost left out: its traction mixes stick and slip) gives c from the
    # tractions rather than from the statuses
    inner = stick & (np.abs(x) < np.abs(x[stick]).max() - 1e-12)
    g = (mu * res["CPRESS"][inner] - np.abs(res["CSHEAR"][inner])) ** 2
    fit_slope, fit_icept = np.polyfit(x[inner] ** 2, g, 1)
    c_fit = np.sqrt(-fit_icept / fit_slope)
    l2q = np.sqrt(np.sum(w * (res["CSHEAR"] - q) ** 2) / np.sum(w * q**2))
    p = hertz_pressure(x, P)
    l2p = np.sqrt(np.sum(w * (res["CPRESS"] - p) ** 2) / np.sum(w * p**2))
    # the slip (CSLIP: the paired nodes' relative tangential displacement) inside the
    # theory's contact |x| <= a (a node closed beyond it has no closed-form slip)
    inside = (res["STATUS"] >= 3) & (np.abs(x) <= a)
    s = mindlin_slip(x, P, Q, mu)
    slip = np.abs(res["CSLIP"])
    if slope is not None:
        slip = slip - np.abs(res["CSHEAR"]) / slope
    l2s = np.sqrt(np.sum((w * (slip - s) ** 2)[inside]) / np.sum((w * s**2)[inside]))
    return dict(P=P, Q=Q, ratio=Q / (mu * P), a=a, c=c, c_h=c_h, c_err=c_h / c - 1.0, c_fit=c_fit,
                c_fit_err=c_fit / c - 1.0, l2q=l2q, l2p=l2p, l2s=l2s, stick_slip=slip[stick].max(),
                edge_slip=s.max())


def crack_voronoi_deck(path, cells, beta_deg, mu, width=20.0, seed=3):
    """F4 on the mesher's Voronoi cells (VPE) and its joint: the plate [-W, W]^2 (W =
    width a) meshed by vctools.mesh with `cells` cells graded toward the crack (ratio
    0.03 within 3 a), the crack a [[joint]] from (-a, 0) to (a, 0), both tips inside
    (CRACK_SLAVE the upper face's nodes, CRACK_MASTER the lower face's sides; the tips
    shared).  The outer boundary is held at the displacement of the uniform state
    (plane strain strain of -sigma d d^T), so no rigid motion is left; NODE TO SURFACE,
    SMALL SLIDING, HARD, exact stick.  Returns the deck's path."""
    from vctools.mesh.scene import mesh_scene_file

    a, sigma, E, nu = CRACK["a"], CRACK["sigma"], CRACK["E"], CRACK["nu"]
    W = width * a
    scene = path.with_suffix(".toml")
    scene.write_text(f"""[mesh]
title = "F4 closed crack on Voronoi cells"
seed = {seed}
lloyd = 20

[[body]]
name = "PLATE"
rectangle = [{-W!r}, {-W!r}, {W!r}, {W!r}]
mesher = "voronoi"
cells = {cells}
grading = [ {{ line = [[{-a!r}, 0.0], [{a!r}, 0.0]], ratio = 0.03, radius = {3.0 * a!r} }} ]

[[joint]]
name = "CRACK"
polyline = [[{-a!r}, 0.0], [{a!r}, 0.0]]
master = "right"
""")
    (mesh_path, m), = mesh_scene_file(scene, out=path.with_name(path.stem + "_mesh.inp"), echo=None)
    xy = m.nodes
    b = np.radians(beta_deg)
    d = np.array([np.cos(b), np.sin(b)])
    s = -sigma * np.outer(d, d)
    exx = ((1.0 - nu**2) * s[0, 0] - nu * (1.0 + nu) * s[1, 1]) / E
    eyy = ((1.0 - nu**2) * s[1, 1] - nu * (1.0 + nu) * s[0, 0]) / E
    gamma = 2.0 * (1.0 + nu) * s[0, 1] / E
    u = np.column_stack([exx * xy[:, 0] + 0.5 * gamma * xy[:, 1], eyy * xy[:, 1] + 0.5 * gamma * xy[:, 0]])
    outer = np.flatnonzero(np.isclose(np.abs(xy[:, 0]), W) | np.isclose(np.abs(xy[:, 1]), W))
    lines = [f"*INCLUDE, INPUT={pathlib.Path(mesh_path).name}", "*MATERIAL, NAME=ROCK", "*ELASTIC",
             f"{float(E)!r}, {float(nu)!r}", "*SOLID SECTION, ELSET=PLATE, MATERIAL=ROCK", "1.0",
             "*SURFACE INTERACTION, NAME=JOINT", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD", "*FRICTION",
             f"{float(mu)!r}", "*CONTACT PAIR, INTERACTION=JOINT, TYPE=NODE TO SURFACE, SMALL SLIDING",
             "CRACK_SLAVE, CRACK_MASTER", "*STEP", "*STATIC", "*BOUNDARY"]
    lines += [f"{i + 1}, {k + 1}, {k + 1}, {float(u[i, k])!r}" for i in outer for k in (0, 1)]
    lines += ["*CONTACT FILE", "CDIS, CSTR", "*END STEP"]
    return write(path, lines)
