"""Water pressure inside a joint (*UPLIFT, docs/sliding-safety.md), checked against
computations made here without the code under test.

The model is a block (a rectangle, or the Code_Aster ssnp142 dam) on a rigid base: a row
of elements whose nodes are all held, the block's bottom on its top through a
frictionless contact pair.  The block's base nodes are held horizontally: that stands in
for the shear the gravity method lets the base carry, at base level, so that it adds
nothing to the moment balance about a point of the base.

- Equilibrium of the block: sum(CPRESS * CNAREA) = W - U and the moment of
  (CPRESS + CFLUIDP) * CNAREA about the heel equals that of the weight (and of the
  water on the upstream face), with W, U and the moments from the geometry.
- The distributions: CFLUIDP at every slave node equals the guideline formula (linear
  between the heads; USBR's and USACE's drain rules), and U = sum(CFLUIDP * CNAREA)
  their integral (exact for a piecewise linear pressure with the drain at a node).
- Both faces: with HARD contact the joint faces cannot move apart while closed, so
  the water changes the contact force node by node by exactly the uplift:
  CPRESS(wet) + CFLUIDP = CPRESS(dry).
- Pressure penetration on a dam whose base cracks (ssnp142: 69 % of the base in the
  gravity method): the open part from the heel carries the full head, the closed part
  the distribution restarted at the crack tip, and the crack length agrees with the
  no-tension gravity method (computed here by bisection) within a mesh cell.  A rigid
  block on penalty springs has the gravity method's linear base pressure exactly, so
  the only difference is the mesh.
"""
import os
import subprocess

import h5py
import numpy as np
import pytest

G = 9.81
GW = 9810.0        # unit weight of water, N/m^3
RHO = 2400.0       # concrete, kg/m^3 (ssnp142)


def block_deck(path, poly, nx, ny, *, hard=False, penalty=1.0e8, young=1.0e13, water=None, uplift=None,
               two_steps=False, etype="CPE4", pair="NODE TO SURFACE, SMALL SLIDING", extra=None, friction=None,
               after=None):
    """A deck of the quadrilateral block `poly` = heel, toe, top right, top left
    (heel at (0, 0), toe at (B, 0), upstream face x = 0) meshed nx x ny CPE4 on a rigid
    base strip; `water` = reservoir depth on the upstream face (None: dry); `uplift` =
    the *UPLIFT text (keyword line and data lines) or None; `friction` = the *FRICTION
    lines of the joint (then the base is not held horizontally: the friction carries the
    thrust); `after` = the text of further steps."""
    p = np.asarray(poly, float)
    nodes, elems = [], []

    def nid(i, j):
        return 1 + j * (nx + 1) + i

    for j in range(ny + 1):
        for i in range(nx + 1):
            a, b = i / nx, j / ny
            x = (1 - a) * (1 - b) * p[0] + a * (1 - b) * p[1] + a * b * p[2] + (1 - a) * b * p[3]
            nodes.append((nid(i, j), x[0], x[1]))
    for j in range(ny):
        for i in range(nx):
            elems.append((1 + j * nx + i, nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
    base0 = (nx + 1) * (ny + 1)
    h = 0.25
    for i in range(nx + 1):
        x = p[0] + (p[1] - p[0]) * i / nx
        nodes.append((base0 + 1 + i, x[0], -h))
        nodes.append((base0 + nx + 2 + i, x[0], 0.0))
    e0 = nx * ny
    for i in range(nx):
        elems.append((e0 + 1 + i, base0 + 1 + i, base0 + 2 + i, base0 + nx + 3 + i, base0 + nx + 2 + i))
    L = ["*HEADING", "block on a rigid base with water in the joint", "*NODE"]
    L += [f"{n}, {float(x)!r}, {float(y)!r}" for n, x, y in nodes]
    L += [f"*ELEMENT, TYPE={etype}, ELSET=BLOCK"] + [", ".join(map(str, e)) for e in elems[:e0]]
    L += [f"*ELEMENT, TYPE={etype}, ELSET=BASE"] + [", ".join(map(str, e)) for e in elems[e0:]]
    L += ["*NSET, NSET=BASENODES"] + [str(base0 + 1 + k) for k in range(2 * nx + 2)]
    L += ["*NSET, NSET=FOOT"] + [str(nid(i, 0)) for i in range(nx + 1)]
    L += ["*SURFACE, NAME=SLAVE, TYPE=ELEMENT"] + [f"{1 + i}, S1" for i in range(nx)]
    L += ["*SURFACE, NAME=MASTER, TYPE=ELEMENT"] + [f"{e0 + 1 + i}, S3" for i in range(nx)]
    if water is not None:
        rows = [j for j in range(ny) if (j + 1) * (p[3][1] / ny) <= water + 1e-9]
        L += ["*SURFACE, NAME=UPSTREAM, TYPE=ELEMENT"] + [f"{1 + j * nx}, S4" for j in rows]
    L += ["*MATERIAL, NAME=CONCRETE", "*ELASTIC", f"{float(young)!r}, 0.2", "*DENSITY", f"{float(RHO)!r}",
          "*SOLID SECTION, ELSET=BLOCK, MATERIAL=CONCRETE", "1.0",
          "*SOLID SECTION, ELSET=BASE, MATERIAL=CONCRETE", "1.0",
          "*SURFACE INTERACTION, NAME=JOINT"]
    if hard:
        L += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"]
    else:
        L += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{float(penalty)!r}"]
    if friction is not None:
        L += [friction]
    L += [f"*CONTACT PAIR, INTERACTION=JOINT, TYPE={pair}", "SLAVE, MASTER",
          "*BOUNDARY", "BASENODES, 1, 2"] + (["FOOT, 1"] if friction is None else [])
    step = ["*STEP", "*STATIC", "*DLOAD", f"BLOCK, GRAV, {float(G)!r}, 0., -1."]
    if two_steps:
        L += step + ["*END STEP"]
        step = ["*STEP", "*STATIC"]
    if water is not None:
        step += ["*DSLOAD", f"UPSTREAM, HP, {float(GW * water)!r}, {float(water)!r}, 0."]
    if uplift is not None:
        step += [uplift]
    if extra is not None:
        step += [extra]
    L += step + ["*END STEP"]
    if after is not None:
        L += [after]
    path.write_text("\n".join(L) + "\n")
    return path


def run(exe, deck, out):
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr + r.stdout
    return out / (os.path.basename(str(deck))[:-4] + ".h5"), out / (os.path.basename(str(deck))[:-4] + ".log")


def pair(h5, step="0001"):
    with h5py.File(h5) as f:
        g = f[f"steps/{step}/contact/pair_1"]
        d = {k: g[k][:] for k in g}
    order = np.argsort(d["coordinates"][:, 0] if d["coordinates"].shape[-1] == 2 else d["coordinates"][0])
    x = d["coordinates"]
    x = x if x.shape[-1] == 2 else x.T
    return {k: (v[order] if k != "coordinates" else x[order]) for k, v in d.items()}


RECT = [(0, 0), (5, 0), (5, 4), (0, 4)]
W_RECT = RHO * G * 20.0


@pytest.mark.parametrize("etype,kind", [("CPE4", "NODE TO SURFACE, SMALL SLIDING"),
                                       ("CPE4", "NODE TO SURFACE"),
                                       ("VPE", "SURFACE TO SURFACE")])
def test_linear_uplift_balance(exe, tmp_path, etype, kind):
    """Linear uplift from a head 2 above the joint at the heel to 0.5 at the toe on a
    5 x 4 block: U = gamma_w B (2 + 0.5)/2 = 61 312.5 N/m; the base stays closed.  FEM
    and VEM, node to segment with fixed and finite-sliding pairing, surface to surface."""
    up = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 2.\n5., 0., 0.5"
    for hard in (False, True):
        h5, _ = run(exe, block_deck(tmp_path / f"lin{int(hard)}.inp", RECT, 20, 8, hard=hard, uplift=up,
                                    etype=etype, pair=kind), tmp_path)
        c = pair(h5)
        x = c["coordinates"][:, 0]
        # the formula at every slave node: round-off only
        assert np.allclose(c["CFLUIDP"], GW * (2.0 + (0.5 - 2.0) * x / 5.0), rtol=1e-13, atol=0)
        U = np.sum(c["CFLUIDP"] * c["CNAREA"])
        assert U == pytest.approx(GW * 5.0 * 1.25, rel=1e-13)
        assert (c["STATUS"] == 1).all()
        # equilibrium of the block, to the contact iteration's residual (1e-10) and the
        # round-off of the stiff block (E = 1e13 against forces of 1e5): measured 6e-11
        # (LINEAR) and 1e-15 (HARD); 1e-8
        assert np.sum(c["CPRESS"] * c["CNAREA"]) == pytest.approx(W_RECT - U, rel=1e-8)
        m_total = np.sum((c["CPRESS"] + c["CFLUIDP"]) * c["CNAREA"] * x)
        assert m_total == pytest.approx(W_RECT * 2.5, rel=1e-8)


@pytest.mark.parametrize("E", [None, 0.5])
def test_drained_uplift(exe, tmp_path, E):
    """A drain line at x = 1 (a node): USBR's rule (E omitted: 2/3) and E = 0.5, heads 3
    at the heel and 0 at the toe: the head at the drain is (1 - E) 3."""
    line3 = "1., 0." if E is None else f"1., 0., {E}"
    e = 2.0 / 3.0 if E is None else E
    up = f"*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 3.\n5., 0., 0.\n{line3}"
    h5, _ = run(exe, block_deck(tmp_path / "drain.inp", RECT, 20, 8, uplift=up), tmp_path)
    c = pair(h5)
    x = c["coordinates"][:, 0]
    hd = (1 - e) * 3.0
    head = np.where(x <= 1.0, 3.0 + (hd - 3.0) * x, hd * (5.0 - x) / 4.0)
    assert np.allclose(c["CFLUIDP"], GW * head, rtol=1e-13, atol=1e-9)
    U = GW * (0.5 * (3.0 + hd) * 1.0 + 0.5 * hd * 4.0)
    assert np.sum(c["CFLUIDP"] * c["CNAREA"]) == pytest.approx(U, rel=1e-13)
    assert np.sum(c["CPRESS"] * c["CNAREA"]) == pytest.approx(W_RECT - U, rel=1e-8)


def test_uplift_acts_on_both_faces(exe, tmp_path):
    """HARD contact, an elastic block (E = 2e10): while the joint stays closed its faces
    cannot separate, so an uplift that pushes both faces apart equally changes the
    contact force node by node by exactly the uplift and nothing else moves.  Dry and wet
    from the same deck; the wet one adds the uplift in a second step."""
    up = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 4.\n5., 0., 1.\n2., 0., 0.5"
    h5, _ = run(exe, block_deck(tmp_path / "faces.inp", RECT, 20, 8, hard=True, young=2.0e10, uplift=up,
                                two_steps=True), tmp_path)
    dry, wet = pair(h5, "0001"), pair(h5, "0002")
    assert "CFLUIDP" not in dry
    assert (wet["STATUS"] == 1).all()
    scale = np.max(np.abs(dry["CPRESS"]))
    # HARD stops at an overclosure of 1e-10 of the element size and a residual of 1e-10;
    # measured 1.7e-14 of the largest pressure (the faces do not move at all): 1e-10
    assert np.max(np.abs(wet["CPRESS"] + wet["CFLUIDP"] - dry["CPRESS"])) < 1e-10 * scale


def gravity_method_crack(poly, hw, B):
    """No-tension gravity method (CADAM/USACE): rigid dam, base pressure linear over the
    closed length, zero at the crack tip; full head in the crack, then linear to zero at
    the toe.  Returns the crack length a (bisection on the resultant's position)."""
    P = np.asarray(poly, float)
    x, y = P[:, 0], P[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    A = 0.5 * cr.sum()
    xc = ((x + x1) * cr).sum() / (6 * A)
    W = RHO * G * A
    H = 0.5 * GW * hw**2
    ph = GW * hw

    def resid(a):
        U = ph * a + 0.5 * ph * (B - a)
        MU = ph * a**2 / 2 + 0.5 * ph * (B - a) * (a + (B - a) / 3)
        N = W - U
        xR = (W * xc - MU + H * hw / 3) / N       # moments about the heel
        return xR - (B - (B - a) / 3)             # > 0: resultant beyond the triangle's

    lo, hi = 0.0, 0.999 * B
    assert resid(lo) > 0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if resid(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


SSNP142 = [(0, 0), (5, 0), (1.5, 10), (0, 10)]


def test_gravity_method_reference():
    """The bisection reproduces the research note's value for ssnp142 (3.4545 m,
    friction_anchors_calc/uplift_ssr.py)."""
    assert gravity_method_crack(SSNP142, 9.0, 5.0) == pytest.approx(3.4545, abs=1e-4)


@pytest.mark.parametrize("nx", [20, 40])
def test_pressure_penetration_matches_gravity_method(exe, tmp_path, nx):
    """ssnp142 dam, 9 m of water, heads 9 (heel) and 0 (toe) on the joint: the base
    cracks from the heel.  Rigid dam on penalty springs (E = 1e13, K = 1e8: the springs
    carry 1e-4 of the compliance), so the base pressure is the gravity method's linear
    one; the crack length must agree within a mesh cell h = 5/nx."""
    up = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810, PENETRATION\n0., 0., 9.\n5., 0., 0."
    h5, _ = run(exe, block_deck(tmp_path / "pp.inp", SSNP142, nx, 20, water=9.0, uplift=up), tmp_path)
    c = pair(h5)
    x = c["coordinates"][:, 0]
    closed = c["STATUS"] == 1
    k = np.argmax(closed)            # the first closed node from the heel
    assert k > 0 and closed[k:].all(), "one crack from the heel, closed beyond it"
    a_fe = x[k - 1]                  # the water filled up to the last open node
    a_gm = gravity_method_crack(SSNP142, 9.0, 5.0)
    h = 5.0 / nx
    # measured a_fe = 3.25, 3.375, 3.4375 for nx = 20, 40, 80 against 3.4545 (the last
    # open node lies before the continuous tip, within one cell)
    assert abs(a_fe - a_gm) <= h, (a_fe, a_gm)
    # full head over the open part, the distribution restarted at the crack tip beyond
    assert np.allclose(c["CFLUIDP"][:k], GW * 9.0, rtol=1e-13)
    assert np.allclose(c["CFLUIDP"][k:], GW * 9.0 * (5.0 - x[k:]) / (5.0 - a_fe), rtol=1e-12, atol=1e-9)
    # how far the water entered, along the flat joint from the heel (x = 0)
    with h5py.File(h5) as f:
        assert f["steps/0001/contact/pair_1"].attrs["water_entered"] == pytest.approx(a_fe, rel=1e-12)
    # the prescribed distribution alone leaves a shorter crack: penetration changed it
    up0 = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 9.\n5., 0., 0."
    h50, _ = run(exe, block_deck(tmp_path / "lin.inp", SSNP142, nx, 20, water=9.0, uplift=up0), tmp_path)
    c0 = pair(h50)
    assert np.argmax(c0["STATUS"] == 1) < k


MOHR_COULOMB = "*FRICTION, COHESION=100000.\n1.0"     # phi = 45 deg, c = 100 kPa


def penetration_on_friction(exe, tmp_path, nx, after=None):
    """ssnp142 with pressure penetration on a Mohr-Coulomb joint (phi = 45 deg, c = 100 kPa)
    instead of the horizontal hold: the friction carries the reservoir's thrust."""
    up = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810, PENETRATION\n0., 0., 9.\n5., 0., 0."
    deck = block_deck(tmp_path / "ppf.inp", SSNP142, nx, 20, water=9.0, uplift=up, friction=MOHR_COULOMB,
                      after=after)
    return run(exe, deck, tmp_path)


@pytest.mark.parametrize("nx", [20, 40])
def test_pressure_penetration_on_a_frictional_joint(exe, tmp_path, nx):
    """The same crack as with the hold (within a mesh cell of the gravity method) when a
    Mohr-Coulomb joint carries the thrust: the shear acts at base level, so the moment
    balance, and with it the no-tension crack, are the gravity method's.  The joint's shear
    resultant is the reservoir's thrust, and the water is the full head over the open part
    and the distribution restarted at the tip beyond."""
    h5, log = penetration_on_friction(exe, tmp_path, nx)
    c = pair(h5)
    x = c["coordinates"][:, 0]
    closed = c["STATUS"] != 0
    k = np.argmax(closed)
    assert k > 0 and closed[k:].all(), "one crack from the heel, closed beyond it"
    assert set(np.unique(c["STATUS"][k:])) <= {3, 4}, "closed nodes stick or slip"
    a_fe = x[k - 1]
    assert abs(a_fe - gravity_method_crack(SSNP142, 9.0, 5.0)) <= 5.0 / nx, a_fe
    assert np.allclose(c["CFLUIDP"][:k], GW * 9.0, rtol=1e-13)
    assert np.allclose(c["CFLUIDP"][k:], GW * 9.0 * (5.0 - x[k:]) / (5.0 - a_fe), rtol=1e-12, atol=1e-9)
    # horizontal equilibrium of the block: the shear resultant is the thrust H, to the
    # round-off of the elastic forces.  The bodies are near-rigid (E = 1e13 Pa) and move
    # by 0.03 m on the penalty springs: the residual's round-off, 1e-16 of (K_max |u|
    # ~ 3e12 N), is 3e-4 N in norm, and its sum over the block's ~900 dofs up to 1e-2 N,
    # 2.5e-8 of H (the supports' RF shows the same imbalance against the applied loads).
    # Measured 5.6e-9, 1.5e-8 and 2.4e-8 on three solution paths that end in the same
    # stick/slip states (GMRES and Uzawa; the condensed solve with Uzawa; with the
    # Newton step); 1e-7
    thrust = 0.5 * GW * 9.0**2
    assert abs(np.sum(c["CSHEAR"] * c["CNAREA"])) == pytest.approx(thrust, rel=1e-7)
    # nodes within the strength: |CSHEAR| <= c + mu CPRESS.  CSHEAR is the force the
    # balance leaves at the node, which meets the law's bound to the iteration's
    # tolerance: measured 4.9e-7 above it at the crack-tip node (nx = 40); 1e-6
    assert (np.abs(c["CSHEAR"][k:]) <= (1.0e5 + c["CPRESS"][k:]) * (1 + 1e-6)).all()


@pytest.mark.parametrize("nx", [20, 40])
def test_strength_reduction_on_a_cracked_base(exe, tmp_path, nx):
    """Strength reduction on the cracked ssnp142 base (phi = 45 deg, c = 100 kPa): the
    cohesion acts on the closed length only, so the factor is (c L_closed + N' tan phi)/H
    with the run's own crack (L_closed = sum CNAREA of the closed nodes, N' = sum CPRESS
    CNAREA, both at F = 1): measured -0.04 % (nx = 20 and 40); the bisection's
    tolerance is 1e-3, so 2e-3.  The crack does not change during the reduction (the base
    pressure of a rigid dam is fixed by statics).  Against the no-tension gravity method
    (computed here, 1.3755) the factor differs by what one mesh cell of crack changes:
    (c + gamma_w h_w tan phi / 2) h / H; uncracked, the base would give 2.6288."""
    h5, _ = penetration_on_friction(exe, tmp_path, nx, after="*STEP\n*STRENGTH REDUCTION\n*END STEP")
    c1, c2 = pair(h5, "0001"), pair(h5, "0002")
    area, closed = c1["CNAREA"], c1["STATUS"] != 0
    assert np.array_equal(c2["STATUS"] != 0, closed)
    thrust = 0.5 * GW * 9.0**2
    n_eff = np.sum(c1["CPRESS"] * area)
    with h5py.File(h5) as f:
        F = float(f["steps/0002"].attrs["factor_of_safety"])
    assert F == pytest.approx((1.0e5 * area[closed].sum() + n_eff * 1.0) / thrust, rel=2e-3)
    # the gravity method: crack a, uplift full head over it then linear, N' = W - U
    a = gravity_method_crack(SSNP142, 9.0, 5.0)
    P = np.asarray(SSNP142, float)
    W = RHO * G * 0.5 * abs(np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1]))
    U = GW * 9.0 * (a + 0.5 * (5.0 - a))
    fs_gm = (1.0e5 * (5.0 - a) + (W - U) * 1.0) / thrust
    assert fs_gm == pytest.approx(1.3755, abs=1e-4)
    h = 5.0 / nx
    assert abs(F - fs_gm) <= (1.0e5 + 0.5 * GW * 9.0) * h / thrust
    uncracked = (1.0e5 * 5.0 + (W - 0.5 * GW * 9.0 * 5.0)) / thrust
    assert uncracked == pytest.approx(2.6288, abs=1e-4) and F < 0.6 * uncracked


def test_crack_past_the_drains(exe, tmp_path):
    """ssnp142 with a drain line 1 m from the heel (USBR): the first pass, with the drained
    diagram, cracks less, but the crack then grows past the drain line, the drains lose
    their effect (USACE, CADAM) and the joint ends as without drains: the same crack and
    the same uplift node by node."""
    nx = 20
    runs = {}
    for tag, drain in (("plain", ""), ("drained", "\n1., 0.")):
        up = f"*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810, PENETRATION\n0., 0., 9.\n5., 0., 0.{drain}"
        h5, log = run(exe, block_deck(tmp_path / f"{tag}.inp", SSNP142, nx, 20, water=9.0, uplift=up), tmp_path)
        runs[tag] = (pair(h5), log.read_text())
    a, b = runs["plain"][0], runs["drained"][0]
    assert (a["STATUS"] == b["STATUS"]).all()
    assert np.array_equal(a["CFLUIDP"], b["CFLUIDP"])
    k = np.argmax(b["STATUS"] == 1)
    assert b["coordinates"][k - 1, 0] > 1.0, "the crack passed the drain line"
    # the drained run took a shorter first step: it logged a crack short of the plain one's
    first = [line for line in runs["drained"][1].splitlines() if "pass 1:" in line]
    first_plain = [line for line in runs["plain"][1].splitlines() if "pass 1:" in line]
    assert first and first_plain and first != first_plain


def test_cfluidp_in_every_result_file(exe, tmp_path):
    """CFLUIDP is written beside CPRESS in the contact CSV, the contact VTU and the
    PRINT CSV (*CONTACT PRINT, CSTR), with the values of the HDF5 file."""
    import meshio
    up = "*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 3.\n5., 0., 0.\n1., 0."
    h5, _ = run(exe, block_deck(tmp_path / "files.inp", RECT, 10, 4, uplift=up,
                                extra="*CONTACT FILE\nCSTR, CDIS\n*CONTACT PRINT\nCSTR"), tmp_path)
    with h5py.File(h5) as f:
        g = f["steps/0001/contact/pair_1"]
        ids, fluid = g["node_ids"][:], g["CFLUIDP"][:]
    want = dict(zip(ids.tolist(), fluid.tolist()))
    d = np.genfromtxt(tmp_path / "files_contact_pair1_0001.csv", delimiter=",", names=True, dtype=None,
                      encoding=None)
    assert {int(n): v for n, v in zip(d["node"], d["CFLUIDP"])} == want
    pts = meshio.read(tmp_path / "files_contact_0001.vtu")
    assert dict(zip(pts.point_data["NODE_ID"].tolist(), pts.point_data["CFLUIDP"].tolist())) == want
    p = np.genfromtxt(tmp_path / "files_print_0001.csv", delimiter=",", names=True, dtype=None, encoding=None)
    rows = p[p["variable"] == "CFLUIDP"]
    assert {int(n): v for n, v in zip(rows["id"], rows["value"])} == want


@pytest.mark.parametrize("line,message", [
    ("*UPLIFT, INTERACTION=JOINTS, UNIT WEIGHT=9810\n0., 0., 2.\n5., 0., 0.", "undefined surface interaction JOINTS"),
    ("*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=-1\n0., 0., 2.\n5., 0., 0.", "UNIT WEIGHT = -1 must be a positive"),
    ("*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 2.", "needs two data lines"),
    ("*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 2.\n5., 0., 0.\n7., 0.", "drain line must lie between"),
    ("*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810\n0., 0., 2.\n5., 0., 0.\n1., 0., 1.5", "must lie between 0 and 1"),
])
def test_uplift_input_errors(exe, tmp_path, line, message):
    """Bad *UPLIFT input: exit 1, one message naming file:line."""
    deck = block_deck(tmp_path / "bad.inp", RECT, 4, 2, uplift=line)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(deck)], capture_output=True, text=True)
    assert r.returncode == 1
    assert message in r.stderr
    assert "bad.inp:" in r.stderr
