"""Factor of safety by strength reduction (*STRENGTH REDUCTION, docs/sliding-safety.md),
checked against limit equilibrium computed here from the run's own loads.

The model is a dam (a trapezoid) on a rigid base: a row of elements whose nodes are all
held, the dam's bottom on its top through a contact pair with Coulomb (or Mohr-Coulomb)
friction and nothing else holding the dam.  Step 1: self-weight; step 2: the reservoir on
the upstream face (and the uplift in the joint); step 3: *STRENGTH REDUCTION.

For one planar joint that stays closed the resistance is linear in 1/F, so the factor of
safety is the limit-equilibrium value exactly: F = ((W - U) tan(phi) + c B) / H, with W
the dam's weight (-LOAD_total y of step 1), H the water's thrust (LOAD_total x of step 2),
U = sum(CFLUIDP * CNAREA) of the joint, B the base length - all read from the results,
not from numbers of the deck.
"""
import csv
import math
import os
import subprocess

import h5py
import numpy as np
import pytest

G = 9.81
GW = 9810.0
RHO = 2400.0
PHI = 35.0
MU = math.tan(math.radians(PHI))
DAM = [(0.0, 0.0), (5.0, 0.0), (2.0, 6.0), (0.0, 6.0)]   # heel, toe, top right, top left
WATER = 5.0


def dam_deck(path, *, nx=6, ny=4, hard=False, pair="NODE TO SURFACE, SMALL SLIDING", uplift=False,
             cohesion=0.0, srm="*STRENGTH REDUCTION", srm_data=None, mu=MU, extra_step=None, model_extra=None):
    """The dam meshed nx x ny CPE4 on a rigid base strip, three steps (the third `srm`
    with the data line `srm_data`); `extra_step` is put inside the third step."""
    p = np.asarray(DAM, float)
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
    for i in range(nx + 1):
        x = p[0] + (p[1] - p[0]) * i / nx
        nodes.append((base0 + 1 + i, x[0], -0.5))
        nodes.append((base0 + nx + 2 + i, x[0], 0.0))
    e0 = nx * ny
    for i in range(nx):
        elems.append((e0 + 1 + i, base0 + 1 + i, base0 + 2 + i, base0 + nx + 3 + i, base0 + nx + 2 + i))
    rows = [j for j in range(ny) if (j + 1) * (p[3][1] / ny) <= WATER + 1e-9]
    L = ["*HEADING", "dam on a rigid base, frictional joint", "*NODE"]
    L += [f"{n}, {float(x)!r}, {float(y)!r}" for n, x, y in nodes]
    L += ["*ELEMENT, TYPE=CPE4, ELSET=DAM"] + [", ".join(map(str, e)) for e in elems[:e0]]
    L += ["*ELEMENT, TYPE=CPE4, ELSET=BASE"] + [", ".join(map(str, e)) for e in elems[e0:]]
    L += ["*NSET, NSET=BASENODES"] + [str(base0 + 1 + k) for k in range(2 * nx + 2)]
    L += ["*NSET, NSET=CREST"] + [str(nid(i, ny)) for i in range(nx + 1)]
    L += ["*SURFACE, NAME=SLAVE, TYPE=ELEMENT"] + [f"{1 + i}, S1" for i in range(nx)]
    L += ["*SURFACE, NAME=MASTER, TYPE=ELEMENT"] + [f"{e0 + 1 + i}, S3" for i in range(nx)]
    L += ["*SURFACE, NAME=UPSTREAM, TYPE=ELEMENT"] + [f"{1 + j * nx}, S4" for j in rows]
    L += ["*MATERIAL, NAME=CONCRETE", "*ELASTIC", "2.e10, 0.2", "*DENSITY", f"{float(RHO)!r}",
          # virtual elements: SURFACE TO SURFACE inserts nodes into the sides of both bodies
          "*SOLID SECTION, ELSET=DAM, MATERIAL=CONCRETE, FORMULATION=VEM", "1.0",
          "*SOLID SECTION, ELSET=BASE, MATERIAL=CONCRETE, FORMULATION=VEM", "1.0",
          "*SURFACE INTERACTION, NAME=JOINT"]
    if hard:
        L += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"]
    else:
        L += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e12"]
    L += [f"*FRICTION, COHESION={float(cohesion)!r}" if cohesion > 0 else "*FRICTION", f"{float(mu)!r}"]
    L += [f"*CONTACT PAIR, INTERACTION=JOINT, TYPE={pair}", "SLAVE, MASTER", "*BOUNDARY", "BASENODES, 1, 2"]
    if model_extra:
        L += [model_extra]
    L += ["*STEP, NAME=WEIGHT", "*STATIC", "*DLOAD", f"DAM, GRAV, {float(G)!r}, 0., -1.", "*END STEP"]
    L += ["*STEP, NAME=RESERVOIR", "*STATIC", "*DSLOAD", f"UPSTREAM, HP, {float(GW * WATER)!r}, {float(WATER)!r}, 0."]
    if uplift:
        L += ["*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT=9810.", f"0., 0., {float(WATER)!r}", "5., 0., 0."]
    L += ["*END STEP", "*STEP, NAME=SAFETY", srm]
    if srm_data is not None:
        L += [srm_data]
    if extra_step:
        L += [extra_step]
    L += ["*END STEP"]
    path.write_text("\n".join(L) + "\n")
    return path


def run(exe, deck, out, code=0):
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == code, r.stderr + r.stdout
    return out / (os.path.basename(str(deck))[:-4] + ".h5"), r


def limit_equilibrium(h5, cohesion=0.0):
    """(W - U) tan(phi)/H + c B/H from the run's own results, and the step-3 attributes."""
    with h5py.File(h5) as f:
        W = -f["steps/0001/LOAD_total"][1]
        H = f["steps/0002/LOAD_total"][0]
        c = f["steps/0002/contact/pair_1"]
        U = float(np.sum(c["CFLUIDP"][:] * c["CNAREA"][:])) if "CFLUIDP" in c else 0.0
        B = float(np.sum(c["CNAREA"][:]))
        closed = bool(np.isin(c["STATUS"][:], (1, 3, 4)).all())   # closed, stick, slip
        fs = f["steps/0003"].attrs["factor_of_safety"]
        g = f["steps/0003/strength_reduction"]
        srm = {k: g[k][:] for k in g} | {k: g.attrs[k] for k in g.attrs}
    return ((W - U) * MU + cohesion * B) / H, fs, srm, closed


@pytest.mark.parametrize("pair", ["NODE TO SURFACE, SMALL SLIDING", "NODE TO SURFACE", "SURFACE TO SURFACE"])
@pytest.mark.parametrize("hard", [False, True], ids=["LINEAR", "HARD"])
@pytest.mark.parametrize("uplift", [False, True], ids=["dry", "uplift"])
def test_factor_matches_limit_equilibrium(exe, tmp_path, pair, hard, uplift):
    """c = 0: F = (W - U) tan(phi)/H within 0.5 % (the bracket is 1e-3 wide), by the
    probes around the estimate of the trial at F = 1 (the default) and by the doubling
    bracket and bisection from a first trial of 1.5 (the data line), which never uses
    the estimate."""
    for tag, data in (("probe", None), ("bisect", "1.5, 100.")):
        (tmp_path / tag).mkdir()
        h5, _ = run(exe, dam_deck(tmp_path / tag / "dam.inp", pair=pair, hard=hard, uplift=uplift, srm_data=data),
                    tmp_path / tag)
        want, fs, srm, closed = limit_equilibrium(h5)
        assert closed, "the base stays closed (the limit-equilibrium formula applies)"
        assert abs(fs / want - 1) <= 5e-3, (tag, fs, want)
        # the factor is the last converged trial, the next failed one within the tolerance
        assert srm["F_lower"] == fs and srm["F_upper"] > fs
        assert (srm["F_upper"] - srm["F_lower"]) <= srm["tolerance"] * srm["F_lower"]
        assert srm["converged"][0] == 1 and srm["F"][0] == 1.0
        if data is not None:
            assert srm["F"][1] == 1.5


def test_cohesion_uncracked(exe, tmp_path):
    """c > 0, base uncracked: F = (W - U) tan(phi)/H + c B/H within 1 %."""
    c = 2.0e4
    h5, _ = run(exe, dam_deck(tmp_path / "coh.inp", uplift=True, cohesion=c), tmp_path)
    want, fs, _, closed = limit_equilibrium(h5, cohesion=c)
    assert closed
    assert abs(fs / want - 1) <= 1e-2, (fs, want)
    # the pair attributes: the strength in force, unreduced in step 2, divided by F in step 3
    with h5py.File(h5) as f:
        a2 = f["steps/0002/contact/pair_1"].attrs
        a3 = f["steps/0003/contact/pair_1"].attrs
        assert a2["friction_coefficient"] == pytest.approx(MU, rel=1e-15)
        assert a2["cohesion"] == pytest.approx(c, rel=1e-15)
        assert a3["friction_coefficient"] == pytest.approx(MU / fs, rel=1e-14)
        assert a3["cohesion"] == pytest.approx(c / fs, rel=1e-14)


def test_repeatable_and_csv(exe, tmp_path):
    """Two first trials / largest factors give the same factor within the tolerance;
    halving the tolerance halves the final bracket; the CSV holds the HDF5's trials."""
    res = {}
    for tag, srm, data in (("a", "*STRENGTH REDUCTION", None), ("b", "*STRENGTH REDUCTION", "2.7, 40."),
                           ("c", "*STRENGTH REDUCTION, TOLERANCE=5e-4", None)):
        (tmp_path / tag).mkdir()
        h5, _ = run(exe, dam_deck(tmp_path / tag / "dam.inp", srm=srm, srm_data=data), tmp_path / tag)
        res[tag] = limit_equilibrium(h5)[2]
    a, b, c = res["a"], res["b"], res["c"]
    assert abs(a["F_lower"] - b["F_lower"]) <= 1e-3 * a["F_lower"]
    assert b["F"][1] == 2.7
    wa, wc = a["F_upper"] - a["F_lower"], c["F_upper"] - c["F_lower"]
    # the probes around the estimate lie 0.8 tolerance F_est apart: half as far with
    # half the tolerance (relative 1e-9: the estimate is the same in both runs up to
    # the round-off of the contact forces)
    assert wc == pytest.approx(0.5 * wa, rel=1e-9)
    assert wa <= 1e-3 * a["F_lower"] and wc <= 5e-4 * c["F_lower"]
    # the doubling bracket and bisection from a given first trial: halved tolerance,
    # one bisection more, exactly half the bracket
    (tmp_path / "d").mkdir()
    h5, _ = run(exe, dam_deck(tmp_path / "d" / "dam.inp", srm="*STRENGTH REDUCTION, TOLERANCE=5e-4",
                              srm_data="2.7, 40."), tmp_path / "d")
    d = limit_equilibrium(h5)[2]
    assert d["F_upper"] - d["F_lower"] == pytest.approx(0.5 * (b["F_upper"] - b["F_lower"]), rel=1e-12)
    assert len(d["F"]) == len(b["F"]) + 1
    # the log's factor, the CSV and the HDF5 datasets agree
    with open(tmp_path / "a" / "dam_srm_0003.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == ["trial", "F", "converged", "u_char", "iterations", "reason"]
    assert [float(r["F"]) for r in rows] == a["F"].tolist()
    assert [int(r["converged"]) for r in rows] == a["converged"].tolist()
    assert [float(r["u_char"]) for r in rows] == a["u_char"].tolist()
    assert [int(r["iterations"]) for r in rows] == a["iterations"].tolist()
    assert all(r["reason"].startswith("converged") == (r["converged"] == "1") for r in rows)
    # the F-displacement curve rises: a weaker joint lets the dam move more
    ok = a["converged"] == 1
    order = np.argsort(a["F"][ok])
    assert np.all(np.diff(a["u_char"][ok][order]) >= 0)


def test_nset_characteristic_displacement(exe, tmp_path):
    """NSET=CREST: u_char is the largest |U - U_start| of the crest nodes, which is at
    most that of every node, and the factor does not change."""
    (tmp_path / "all").mkdir()
    (tmp_path / "crest").mkdir()
    h_all, _ = run(exe, dam_deck(tmp_path / "all" / "d.inp"), tmp_path / "all")
    h_cr, _ = run(exe, dam_deck(tmp_path / "crest" / "d.inp", srm="*STRENGTH REDUCTION, NSET=CREST"),
                  tmp_path / "crest")
    s_all, s_cr = limit_equilibrium(h_all)[2], limit_equilibrium(h_cr)[2]
    assert s_all["F_lower"] == s_cr["F_lower"]
    assert np.all(s_cr["u_char"] <= s_all["u_char"] * (1 + 1e-12))
    # the crest's displacement of the last trial, from U of steps 2 and 3 (U is relative to
    # no geostatic step here, so U - U_start = U(3) - U(2))
    with h5py.File(h_cr) as f:
        du = f["steps/0003/U"][:] - f["steps/0002/U"][:]
        du = du if du.shape[-1] == 2 else du.T
    ok = np.flatnonzero(s_cr["converged"] == 1)
    crest_ids = np.arange(1, 8) + 4 * 7 - 1          # nid(i, ny) - 1 for nx = 6, ny = 4
    assert s_cr["u_char"][ok[-1]] == pytest.approx(np.max(np.linalg.norm(du[crest_ids], axis=1)), rel=1e-12)


def test_unbounded(exe, tmp_path):
    """A joint that holds up to the largest factor: the search ends there, F_upper = +Inf."""
    h5, r = run(exe, dam_deck(tmp_path / "u.inp", srm_data="1.2, 1.5"), tmp_path)
    _, fs, srm, _ = limit_equilibrium(h5)
    assert fs == 1.5 and math.isinf(srm["F_upper"])


@pytest.mark.parametrize("srm,data,extra,message", [
    ("*STRENGTH REDUCTION, INTERACTION=JOINTS", None, None, "undefined surface interaction JOINTS"),
    ("*STRENGTH REDUCTION, TOLERANCE=0.5", None, None, "TOLERANCE=0.5 must lie between 0 and 0.5"),
    ("*STRENGTH REDUCTION, TOLERANCE=0", None, None, "TOLERANCE=0 must lie between 0 and 0.5"),
    ("*STRENGTH REDUCTION", "1.0, 10.", None, "first trial factor 1.0 must be larger than 1"),
    ("*STRENGTH REDUCTION", "3., 2.", None, "is larger than the largest factor"),
    ("*STRENGTH REDUCTION", "2., 3., 4.", None, "too many fields"),
    ("*STRENGTH REDUCTION, NSET=NOPE", None, None, "undefined node set NOPE"),
    ("*STRENGTH REDUCTION", None, "*CLOAD\n5, 1, 1.", "*CLOAD in a *STRENGTH REDUCTION step"),
    ("*STRENGTH REDUCTION", None, "*STATIC", "already has *STRENGTH REDUCTION"),
    ("*STATIC\n*STRENGTH REDUCTION", None, None, "already has a procedure"),
])
def test_input_errors(exe, tmp_path, srm, data, extra, message):
    """Bad input: exit 1, the message with file:line, no backtrace."""
    deck = dam_deck(tmp_path / "bad.inp", srm=srm, srm_data=data, extra_step=extra)
    _, r = run(exe, deck, tmp_path, code=1)
    assert message in r.stderr, r.stderr
    assert "bad.inp:" in r.stderr and "Backtrace" not in r.stderr


def test_interaction_without_friction(exe, tmp_path):
    """INTERACTION= naming an interaction without friction to reduce: exit 1, file:line."""
    deck = dam_deck(tmp_path / "smooth.inp", srm="*STRENGTH REDUCTION, INTERACTION=SMOOTH",
                    model_extra="*SURFACE INTERACTION, NAME=SMOOTH\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD")
    _, r = run(exe, deck, tmp_path, code=1)
    assert "smooth.inp:" in r.stderr and "surface interaction SMOOTH has no friction to reduce" in r.stderr, r.stderr


def test_interaction_of_no_pair(exe, tmp_path):
    """A frictional interaction that no contact pair uses: named, or the only one, exit 1."""
    extra = "*SURFACE INTERACTION, NAME=LOOSE\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n*FRICTION\n0.5"
    deck = dam_deck(tmp_path / "loose.inp", srm="*STRENGTH REDUCTION, INTERACTION=LOOSE", model_extra=extra)
    _, r = run(exe, deck, tmp_path, code=1)
    assert "loose.inp:" in r.stderr and "no *CONTACT PAIR uses the surface interaction LOOSE" in r.stderr, r.stderr


def test_first_step_and_no_friction(exe, tmp_path):
    """In the first step (no state to reduce), outside a step, without friction: exit 1."""
    deck = tmp_path / "first.inp"
    text = dam_deck(tmp_path / "tmp.inp").read_text()
    deck.write_text(text.replace("*STEP, NAME=WEIGHT\n*STATIC", "*STEP, NAME=WEIGHT\n*STRENGTH REDUCTION"))
    _, r = run(exe, deck, tmp_path, code=1)
    assert "first.inp:" in r.stderr and "in the first step" in r.stderr
    deck = tmp_path / "outside.inp"
    deck.write_text(text.replace("*STEP, NAME=WEIGHT", "*STRENGTH REDUCTION\n*STEP, NAME=WEIGHT"))
    _, r = run(exe, deck, tmp_path, code=1)
    assert "outside.inp:" in r.stderr and "only allowed inside a *STEP" in r.stderr
    deck = tmp_path / "frictionless.inp"
    deck.write_text(text.replace("*FRICTION\n", "").replace(f"{float(MU)!r}\n*CONTACT", "*CONTACT")
                    .replace("BASENODES, 1, 2", "BASENODES, 1, 2\n1, 1"))
    _, r = run(exe, deck, tmp_path, code=1)
    assert "frictionless.inp:" in r.stderr and "no surface interaction of a contact pair has friction" in r.stderr


def test_rerun_removes_stale_tables(exe, tmp_path):
    """JOB_srm_NNNN.csv is one of the job's results: a rerun removes an earlier run's
    (a step that no longer exists) and its leftover temporaries, and writes its own."""
    deck = dam_deck(tmp_path / "dam.inp")
    (tmp_path / "dam_srm_0007.csv").write_text("left by an earlier run")
    (tmp_path / ".dam_srm_0003.csv.AAAAAAAAAAAA.tmp").write_text("left by a killed run")
    (tmp_path / "dam_srm_notes.csv").write_text("not a result name: kept")
    run(exe, deck, tmp_path)
    names = os.listdir(tmp_path)
    assert "dam_srm_0007.csv" not in names and ".dam_srm_0003.csv.AAAAAAAAAAAA.tmp" not in names
    assert "dam_srm_notes.csv" in names and "dam_srm_0003.csv" in names


def test_cut_back_inside_a_trial(exe, tmp_path):
    """inputs/dam_base_dry.inp with MAXIT=4 and the doubling bracket: the jumps from
    F = 1 to 1.5 and from 1.5 to 2.25 need 5-6 contact iterations (7-8 before the
    multipliers' Newton step on the contact compliance, when this test used MAXIT=6), so
    those trials run out of iterations and are tried again in four steps from the last
    converged trial
    (reason "converged (cut back)" in the CSV); the factor stays within 0.5 % of
    (W - U) tan(phi)/H, W and H from the run's LOAD_total (U = 0, dry)."""
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    text = open(os.path.join(root, "inputs", "dam_base_dry.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(root, "inputs", "meshes") + "/")
    text = text.replace("*STRENGTH REDUCTION\n", "*STRENGTH REDUCTION\n1.5, 100.\n")
    text = text.replace("*BOUNDARY\n", "*CONTACT CONTROLS, MAXIT=4\n*BOUNDARY\n", 1)
    deck = tmp_path / "dry.inp"
    deck.write_text(text)
    h5, _ = run(exe, deck, tmp_path)
    with h5py.File(h5) as f:
        # LOAD_total of the geostatic step mixes the dam's weight with the foundation's:
        # W is the normal force the dry joint transmits (vertical equilibrium of the dam)
        c = f["steps/0002/contact/pair_1"]
        W = float(np.sum(c["CPRESS"][:] * c["CNAREA"][:]))
        H = f["steps/0002/LOAD_total"][0] - f["steps/0001/LOAD_total"][0]
        fs = f["steps/0003"].attrs["factor_of_safety"]
    with open(tmp_path / "dry_srm_0003.csv", newline="") as fh:
        reasons = [r["reason"] for r in csv.DictReader(fh)]
    assert "converged (cut back)" in reasons, reasons
    want = W * MU / H
    assert abs(fs / want - 1) <= 5e-3, (fs, want)


def test_two_processes(exe, tmp_path):
    """Under MPI (2 processes, the distributed solver: CG + GAMG) the trials end as the
    serial ones (same outcomes) and the factor agrees within the tolerance; skipped
    without mpiexec or a build with PETSc."""
    import shutil
    launcher = shutil.which("mpiexec")
    if launcher is None:
        pytest.skip("no mpiexec")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    res = {}
    for tag, cmd in (("serial", [exe]), ("np2", [launcher, "-n", "2", exe])):
        (tmp_path / tag).mkdir()
        deck = dam_deck(tmp_path / tag / "dam.inp", uplift=True)
        r = subprocess.run(cmd + ["-q", "-o", str(tmp_path / tag), str(deck)], capture_output=True, text=True,
                           env=env, timeout=300)
        if tag == "np2" and r.returncode != 0 and ("PETSc" in r.stderr or "MPI" in r.stderr):
            pytest.skip("no distributed solver: " + r.stderr.splitlines()[0])
        assert r.returncode == 0, r.stderr
        res[tag] = limit_equilibrium(tmp_path / tag / "dam.h5")[2]
    a, b = res["serial"], res["np2"]
    assert a["converged"].tolist() == b["converged"].tolist()
    assert abs(a["F_lower"] - b["F_lower"]) <= a["tolerance"] * a["F_lower"]


def test_runaway_detected(exe, tmp_path):
    """A soft fill (E = 1e5 Pa, one element between the dam's upstream crest and a held
    wall) adds a little resistance: past the joint's limit the dam slides until the fill
    holds it, centimetres instead of microns.  Trials whose converged displacement
    exceeds 1000 times the base state's largest |U| fail as "displacement grows without
    bound"; the factor is at least the joint's alone, and every converged trial stayed
    within that bound."""
    deck = dam_deck(tmp_path / "fill.inp", srm_data="1.5, 100.")
    text = deck.read_text()
    # nx = 6, ny = 4: the dam's upstream nodes at y = 4.5 and 6 are 22 and 29
    text = text.replace("*ELEMENT, TYPE=CPE4, ELSET=DAM", "9001, -1., 4.5\n9002, -1., 6.\n*ELEMENT, TYPE=CPE4, ELSET=DAM", 1)
    text = text.replace("*ELEMENT, TYPE=CPE4, ELSET=BASE",
                        "*ELEMENT, TYPE=CPE4, ELSET=FILL\n9001, 9001, 22, 29, 9002\n*ELEMENT, TYPE=CPE4, ELSET=BASE", 1)
    text = text.replace("*SURFACE INTERACTION, NAME=JOINT", "*MATERIAL, NAME=FILL\n*ELASTIC\n1.e5, 0.2\n"
                        "*SOLID SECTION, ELSET=FILL, MATERIAL=FILL, FORMULATION=VEM\n1.0\n"
                        "*SURFACE INTERACTION, NAME=JOINT", 1)
    text = text.replace("BASENODES, 1, 2\n", "BASENODES, 1, 2\n9001, 1, 2\n9002, 1, 2\n", 1)
    deck.write_text(text)
    h5, _ = run(exe, deck, tmp_path)
    want, fs, srm, _ = limit_equilibrium(h5)
    with open(tmp_path / "fill_srm_0003.csv", newline="") as fh:
        reasons = [r["reason"] for r in csv.DictReader(fh)]
    assert "displacement grows without bound" in reasons, reasons
    assert fs >= want * (1 - 5e-3), (fs, want)
    with h5py.File(h5) as f:
        base = np.max(np.abs(f["steps/0002/U"][:]))      # no geostatic step: U is absolute
    ok = srm["converged"] == 1
    # u_char is a node's |U - U_start|, the bound is on each component: sqrt(2)
    assert np.all(srm["u_char"][ok] <= 1e3 * np.sqrt(2.0) * base * (1 + 1e-12))


@pytest.mark.parametrize("margin", [0.9, 1.1])
def test_static_step_beyond_the_joint_strength(exe, tmp_path, margin):
    """A plain frictional *STATIC step whose load needs more shear than the joint carries
    (mu below H / W, the limit equilibrium of the dry dam, by 10 %) ends with one message
    that names the sliding, exit 3: no solver, cut-back or support message alone.  10 %
    above that mu the same step holds (the threshold is the joint's, not a numerical
    accident).  W and H are the deck's: the dam's weight rho g A and the thrust
    gw WATER^2 / 2."""
    area = 0.5 * (DAM[1][0] - DAM[0][0] + DAM[2][0] - DAM[3][0]) * DAM[3][1]
    mu_crit = (0.5 * GW * WATER ** 2) / (RHO * G * area)
    deck = dam_deck(tmp_path / "dam.inp", mu=margin * mu_crit, srm="*STATIC")
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(deck)], capture_output=True, text=True)
    if margin > 1:
        assert r.returncode == 0, r.stderr
        return
    assert r.returncode == 3, r.stderr + r.stdout
    errors = [line for line in r.stderr.splitlines() if line.startswith("error")]
    assert len(errors) == 1, r.stderr
    assert "no equilibrium" in errors[0] and "slide" in errors[0], errors
    assert "Traceback" not in r.stderr and "NaN" not in r.stderr and "cut back" not in r.stderr
