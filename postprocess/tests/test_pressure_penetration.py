"""Abaqus' *PRESSURE PENETRATION (docs/sliding-safety.md, docs/deck-reference.md),
checked against computations made here without the code under test.

The model: a nearly rigid block (B x 2, nx elements along the joint) on a nearly
rigid base strip (a different number of elements: the pair does not match), a
frictionless NODE TO SURFACE pair with linear penalty springs between them, the base's
bottom held, the block held horizontally at one top node.  One vertical force N at
x_N = 3 (B = 4) makes the block rock onto its right end: on rigid bodies and
no-tension springs the joint opens over 0 <= x < a with a = 3 x_N - 2B = 1 dry.

- Fluid from the opening end (x = 0): CFLUIDP = p on the slave nodes that are open,
  contiguously from x = 0, and 0 on the closed part; the block's statics (vertical
  force and moment) hold with sum((CPRESS + CFLUIDP) CNAREA).
- Rigid block on springs with the fluid p on the open part: vertical and moment
  balance give p a^2 + (2N - 4pB) a + 4NB - 6N x_N = 0 for the opening a (the
  smaller positive root), which the wetted length matches within a mesh cell.
- Fluid offered at the closed end (x = B): nothing enters, the state is the dry one.
- A CRITICAL PRESSURE above the contact pressure of the first closed nodes lets the
  fluid further in: every wetted node carries a contact pressure at or below p_c and
  the first dry node one above it.
"""
import os
import subprocess

import h5py
import numpy as np
import pytest

B = 4.0
NX_SLAVE = 40      # slave cell h = 0.1
NX_MASTER = 27     # a different master division: a non-matching pair
N = 1.0e6          # N per unit thickness
X_N = 3.0
P_FLUID = 2.5e4    # 0.1 N / B: the joint opens part of the way only


def joint_deck(path, pp=None, *, extra_model=None, pair="NODE TO SURFACE, SMALL SLIDING", etype="CPE4",
               after=None):
    """The deck of the rocking block; `pp` = the *PRESSURE PENETRATION text or None."""
    ny, hb = 4, 2.0
    nodes, elems = [], []

    def up(i, j):
        return 1 + j * (NX_SLAVE + 1) + i

    for j in range(ny + 1):
        for i in range(NX_SLAVE + 1):
            nodes.append((up(i, j), B * i / NX_SLAVE, hb * j / ny))
    for j in range(ny):
        for i in range(NX_SLAVE):
            elems.append((1 + j * NX_SLAVE + i, up(i, j), up(i + 1, j), up(i + 1, j + 1), up(i, j + 1)))
    e0, n0 = len(elems), 1000

    def lo(i, j):
        return n0 + 1 + j * (NX_MASTER + 1) + i

    for j in range(2):
        for i in range(NX_MASTER + 1):
            nodes.append((lo(i, j), B * i / NX_MASTER, -0.5 + 0.5 * j))
    for i in range(NX_MASTER):
        elems.append((e0 + 1 + i, lo(i, 0), lo(i + 1, 0), lo(i + 1, 1), lo(i, 1)))
    load = up(round(X_N / B * NX_SLAVE), ny)
    L = ["*HEADING", "rocking block on a base: pressure penetration", "*NODE"]
    L += [f"{n}, {float(x)!r}, {float(y)!r}" for n, x, y in nodes]
    L += [f"*ELEMENT, TYPE={etype}, ELSET=BLOCK"] + [", ".join(map(str, e)) for e in elems[:e0]]
    L += [f"*ELEMENT, TYPE={etype}, ELSET=BASE"] + [", ".join(map(str, e)) for e in elems[e0:]]
    L += ["*NSET, NSET=BOTTOM"] + [str(lo(i, 0)) for i in range(NX_MASTER + 1)]
    L += ["*NSET, NSET=HEEL_S", str(up(0, 0)), "*NSET, NSET=HEEL_M", str(lo(0, 1))]
    L += ["*SURFACE, NAME=BLOCKBOT, TYPE=ELEMENT"] + [f"{1 + i}, S1" for i in range(NX_SLAVE)]
    L += ["*SURFACE, NAME=BASETOP, TYPE=ELEMENT"] + [f"{e0 + 1 + i}, S3" for i in range(NX_MASTER)]
    L += ["*MATERIAL, NAME=STIFF", "*ELASTIC", f"{float(1.0e13)!r}, 0.2",
          "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STIFF", "1.0",
          "*SOLID SECTION, ELSET=BASE, MATERIAL=STIFF", "1.0",
          "*SURFACE INTERACTION, NAME=JOINT",
          "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{float(1.0e8)!r}",
          f"*CONTACT PAIR, INTERACTION=JOINT, TYPE={pair}", "BLOCKBOT, BASETOP",
          "*BOUNDARY", "BOTTOM, 1, 2", f"{up(0, ny)}, 1"]
    if extra_model is not None:
        L += [extra_model]
    L += ["*STEP", "*STATIC", "*CLOAD", f"{load}, 2, {float(-N)!r}"]
    if pp is not None:
        L += [pp]
    L += ["*END STEP"]
    if after is not None:
        L += [after]
    path.write_text("\n".join(L) + "\n")
    return path


def pp_text(slave="HEEL_S", master="HEEL_M", p=P_FLUID, critical=None, field4=False):
    """The keyword; the critical pressure as the parameter or (field4) as Abaqus' fourth field."""
    head = "*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT"
    tail = ""
    if critical is not None and field4:
        tail = f", {float(critical)!r}"
    elif critical is not None:
        head += f", CRITICAL PRESSURE={float(critical)!r}"
    return f"{head}\n{slave}, {master}, {float(p)!r}{tail}"


def run(exe, deck, out):
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr + r.stdout
    return out / (os.path.basename(str(deck))[:-4] + ".h5")


def joint(h5, step="0001"):
    """The pair's slave nodes in order of x, and the pair's water_entered attribute."""
    with h5py.File(h5) as f:
        g = f[f"steps/{step}/contact/pair_1"]
        d = {k: g[k][:] for k in g}
        entered = g.attrs.get("water_entered", None)
    x = d["coordinates"]
    x = x if x.shape[-1] == 2 else x.T
    order = np.argsort(x[:, 0])
    d = {k: (v[order] if k != "coordinates" else x[order]) for k, v in d.items()}
    return d, entered


def check_statics(d, moment_rel=1e-8):
    """Vertical force and moment about x = 0 of the block: the joint's normal stress
    (CPRESS + CFLUIDP) over CNAREA against N at x_N.  The joint is straight and
    horizontal and frictionless and the block's only support is horizontal, so both
    balances are exact up to the solver's round-off: the blocks' stiffness (E = 1e13)
    over the springs' (1e8) costs about 5 of the 16 digits, hence rel 1e-8."""
    f = (d["CPRESS"] + d.get("CFLUIDP", 0.0)) * d["CNAREA"]
    assert f.sum() == pytest.approx(N, rel=1e-8)
    assert (f * d["coordinates"][:, 0]).sum() == pytest.approx(N * X_N, rel=moment_rel)


def wetted_count(fluid):
    """Number of slave nodes wetted contiguously from x = 0."""
    k = 0
    while k < len(fluid) and fluid[k] > 0.0:
        k += 1
    return k


@pytest.mark.parametrize("etype,kind", [("CPE4", "NODE TO SURFACE, SMALL SLIDING"), ("CPE4", "NODE TO SURFACE"),
                                       ("VPE", "SURFACE TO SURFACE")])
def test_fluid_fills_the_open_part(exe, tmp_path, etype, kind):
    """(a) exposed node at the opening end: CFLUIDP = p exactly on the nodes open
    contiguously from x = 0 and 0 elsewhere, statics hold, and the fluid opened the
    joint further than the dry state.  FEM and VEM, fixed and finite-sliding pairing,
    surface to surface."""
    dry, _ = joint(run(exe, joint_deck(tmp_path / "dry.inp", pair=kind, etype=etype), tmp_path))
    d, entered = joint(run(exe, joint_deck(tmp_path / "wet.inp", pp_text(), pair=kind, etype=etype), tmp_path))
    open_ = d["CPRESS"] == 0.0
    k = wetted_count(d["CFLUIDP"])
    assert k > 0 and np.all(open_[:k]) and not open_[k]
    np.testing.assert_array_equal(d["CFLUIDP"][:k], P_FLUID)
    np.testing.assert_array_equal(d["CFLUIDP"][k:], 0.0)
    check_statics(d, 5e-4 if kind == "SURFACE TO SURFACE" else 1e-8)
    assert k > np.count_nonzero(dry["CPRESS"] == 0.0)
    # water_entered: the distance from the exposed node to the last wetted node
    assert entered == pytest.approx(d["coordinates"][k - 1, 0], rel=1e-12)


def test_rigid_block_closed_form(exe, tmp_path):
    """(d) the opening a of the rigid block with the fluid p on it (module docstring):
    the wetted length is within one slave cell of it (the discrete tip lies between
    the last open and the first closed node; the blocks' own strain is k B / E = 4e-5
    of the springs')."""
    h = B / NX_SLAVE
    a_dry = 3.0 * X_N - 2.0 * B
    qa, qb, qc = P_FLUID, 2.0 * N - 4.0 * P_FLUID * B, 4.0 * N * B - 6.0 * N * X_N
    a = (-qb + np.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
    assert a > a_dry + 2.0 * h        # the fluid makes a difference the test can see
    d, entered = joint(run(exe, joint_deck(tmp_path / "wet.inp", pp_text()), tmp_path))
    assert abs(entered - a) <= h
    # the fluid force is p over the wetted tributary lengths: p (entered + h/2)
    assert (d["CFLUIDP"] * d["CNAREA"]).sum() == pytest.approx(P_FLUID * (entered + 0.5 * h), rel=1e-12)


def test_exposed_at_closed_end(exe, tmp_path):
    """(b) fluid offered at x = B, where the block bears: nothing enters, the result is
    the dry one, water_entered = 0."""
    dry, _ = joint(run(exe, joint_deck(tmp_path / "dry.inp"), tmp_path))
    toe = ("*NSET, NSET=TOE_S\n41\n*NSET, NSET=TOE_M\n1056")
    d, entered = joint(run(exe, joint_deck(tmp_path / "toe.inp", pp_text("TOE_S", "TOE_M"), extra_model=toe),
                           tmp_path))
    np.testing.assert_array_equal(d["CFLUIDP"], 0.0)
    np.testing.assert_array_equal(d["CPRESS"], dry["CPRESS"])
    assert entered == 0.0


@pytest.mark.parametrize("field4", [False, True])
def test_critical_pressure_lets_fluid_further(exe, tmp_path, field4):
    """(c) p_c = 1.5 times the contact pressure of the first closed node of (a): the
    fluid enters further; each wetted node's contact pressure is at or below p_c, the
    first dry one's above it, and the statics hold.  p_c as CRITICAL PRESSURE= and as
    the data line's fourth field (Abaqus' place for it)."""
    d0, _ = joint(run(exe, joint_deck(tmp_path / "wet.inp", pp_text()), tmp_path))
    k0 = wetted_count(d0["CFLUIDP"])
    pc = 1.5 * d0["CPRESS"][k0]
    d, _ = joint(run(exe, joint_deck(tmp_path / "crit.inp", pp_text(critical=pc, field4=field4)), tmp_path))
    k = wetted_count(d["CFLUIDP"])
    assert k > k0
    assert np.all(d["CPRESS"][:k] <= pc) and d["CPRESS"][k] > pc
    np.testing.assert_array_equal(d["CFLUIDP"][:k], P_FLUID)
    np.testing.assert_array_equal(d["CFLUIDP"][k:], 0.0)
    check_statics(d)


def test_penetration_time_has_no_effect(exe, tmp_path):
    """PENETRATION TIME is accepted; a static step applies the pressure at once, so the
    results are those without it, value for value."""
    d0, e0 = joint(run(exe, joint_deck(tmp_path / "a.inp", pp_text()), tmp_path))
    text = pp_text().replace("SLAVE=BLOCKBOT", "SLAVE=BLOCKBOT, PENETRATION TIME=0.01")
    d1, e1 = joint(run(exe, joint_deck(tmp_path / "b.inp", text), tmp_path))
    assert e1 == e0
    for k in ("CPRESS", "CFLUIDP"):
        np.testing.assert_array_equal(d1[k], d0[k])


def test_later_steps(exe, tmp_path):
    """The penetration holds in a later step that does not repeat it (the same state),
    and a later *PRESSURE PENETRATION of the same pair replaces it: p = 0 leaves the
    dry state."""
    dry, _ = joint(run(exe, joint_deck(tmp_path / "dry.inp"), tmp_path))
    nothing = "*STEP\n*STATIC\n*END STEP"
    zero = "*STEP\n*STATIC\n" + pp_text(p=0.0) + "\n*END STEP"
    h5 = run(exe, joint_deck(tmp_path / "steps.inp", pp_text(), after=nothing + "\n" + zero), tmp_path)
    d1, e1 = joint(h5, "0001")
    d2, e2 = joint(h5, "0002")
    d3, _ = joint(h5, "0003")
    np.testing.assert_array_equal(d2["CFLUIDP"], d1["CFLUIDP"])
    assert e2 == e1 and e1 > 0.0
    # rel 1e-9 of the largest pressure: the same system solved from another start
    np.testing.assert_allclose(d2["CPRESS"], d1["CPRESS"], rtol=0, atol=1e-9 * d1["CPRESS"].max())
    np.testing.assert_array_equal(d3["CFLUIDP"], 0.0)
    np.testing.assert_allclose(d3["CPRESS"], dry["CPRESS"], rtol=0, atol=1e-9 * dry["CPRESS"].max())


@pytest.mark.parametrize("text,message,extra", [
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=NOSUCH\nHEEL_S, HEEL_M, 1.",
     "no *CONTACT PAIR has the slave surface NOSUCH", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nHEEL_S, HEEL_M",
     "missing fields on the *PRESSURE PENETRATION data line", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nHEEL_S, HEEL_M, 1., 2., 3.",
     "too many fields on the *PRESSURE PENETRATION data line", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT, CRITICAL PRESSURE=1\nHEEL_S, HEEL_M, 1., 2.",
     "the critical contact pressure is given twice", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nHEEL_S, HEEL_M, 1., -2.",
     "critical contact pressure -2. must be", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nHEEL_S, HEEL_M, 1.\nHEEL_S, HEEL_M, 2.",
     "more than one *PRESSURE PENETRATION data line", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nBOTTOM, HEEL_M, 1.",
     "the exposed slave node set BOTTOM has 28 nodes", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT, AMPLITUDE=A\nHEEL_S, HEEL_M, 1.",
     "AMPLITUDE= is not supported", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT, CRITICAL PRESSURE=-1\nHEEL_S, HEEL_M, 1.",
     "CRITICAL PRESSURE = -1 must be", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\n42, HEEL_M, 1.",
     "the exposed slave node 42 is not a node of the contact pair's slave surface", None),
    ("*PRESSURE PENETRATION, MASTER=BASETOP, SLAVE=BLOCKBOT\nHEEL_S, 1, 1.",
     "the exposed master node 1 is not a node of the contact pair's master surface", None),
])
def test_input_errors(exe, tmp_path, text, message, extra):
    """Bad *PRESSURE PENETRATION input: exit 1, one message naming file:line of the
    keyword or of its offending data line."""
    deck = joint_deck(tmp_path / "bad.inp", text, extra_model=extra)
    line = deck.read_text().splitlines().index(text.splitlines()[0]) + 1
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(deck)], capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert message in r.stderr
    assert "Traceback" not in r.stderr and "NaN" not in r.stderr
    # the keyword line or the offending data line
    assert any(f"bad.inp:{n}:" in r.stderr for n in range(line, line + len(text.splitlines()))), r.stderr
