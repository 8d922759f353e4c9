"""Every example deck under inputs/ runs to the end, and every contact step of
the paper's scenes converges within 8 active-set iterations (the issue's target)."""
import glob
import os
import re
import subprocess

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DECKS = sorted(glob.glob(os.path.join(ROOT, "inputs", "*.inp")))
# iterations per contact solve beyond the 8 of the paper's scenes, per deck, measured:
# the two-wedge penetration deck's second pass (headwater in the back joint) takes 10, its
# last 5 with the active set and the stick/slip states settled, the exact-stick Uzawa
# updates bringing the largest tangential force change from 0.34 to 1e-10 of the largest
# contact force (the water at the kink acting on its own sides moved them there; 8 + 7
# iterations when it acted along one segment's normal)
BOUND = {"dam_two_wedge_penetration.inp": 10}


@pytest.mark.parametrize("deck", DECKS, ids=[os.path.basename(d) for d in DECKS])
def test_deck_runs(deck, tmp_path):
    exe = os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build-debug", "vemcontact")
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), deck], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    job = os.path.splitext(os.path.basename(deck))[0]
    log = (tmp_path / f"{job}.log").read_text()
    its = [int(m) for m in re.findall(r"contact converged in (\d+) iterations", log)]
    # pressure penetration solves the contact once per pass and the log counts the
    # iterations of all passes: the bound holds per contact solve
    passes = max([int(m) for m in re.findall(r"contact solved (\d+) times", log)] or [1])
    assert all(i <= BOUND.get(os.path.basename(deck), 8) * passes for i in its), its
    assert (tmp_path / f"{job}.pvd").exists() and (tmp_path / f"{job}.h5").exists()


def test_interface_pressure_is_uniform_in_the_middle(tmp_path):
    """Example 3 on the 200-cell Voronoi mesh: between x = 1 and 3 the pressure
    lies between the laterally free (E' eps) and the laterally confined
    (E(1-nu)/((1+nu)(1-2nu)) eps) plane-strain values, eps = 0.1/2, and scatters
    by a few percent only (non-matching meshes)."""
    exe = os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build-debug", "vemcontact")
    subprocess.run([exe, "-q", "-o", str(tmp_path), os.path.join(ROOT, "inputs", "interface_voronoi_200.inp")],
                   check=True)
    d = np.genfromtxt(tmp_path / "interface_voronoi_200_contact_pair1_0001.csv", delimiter=",", names=True,
                      dtype=None, encoding=None)
    e, nu, eps = 1e9, 0.3, 0.05
    free, confined = e / (1 - nu**2) * eps, e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * eps
    mid = (d["x"] > 1) & (d["x"] < 3)
    p = d["CPRESS"][mid]
    assert (d["STATUS"] == "CLOSED").all()
    assert free < p.mean() < confined
    assert p.std() / p.mean() < 0.05


def test_dam_geostatic_and_joint(tmp_path):
    """Example 4: step 1 (geostatic) reports zero displacements and keeps the
    self-weight stresses (mean vertical stress at the foundation bottom about
    -rho g times the weight over the width); step 2 (reservoir) moves the dam
    downstream (+x); the joint faces carry pressure in both steps, and the slave
    node next to the joint tip (10, 4), whose tributary length includes half of
    the edge to the tip (a node of both faces, no slave), reports the pressure of
    its neighbours (about 1e5 Pa), not twice it (issue 10)."""
    import h5py
    exe = os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build-debug", "vemcontact")
    subprocess.run([exe, "-q", "-o", str(tmp_path), os.path.join(ROOT, "inputs", "dam_joint.inp")], check=True)
    with h5py.File(tmp_path / "dam_joint.h5") as f:
        u1 = f["steps/0001/U"][()]
        u2 = f["steps/0002/U"][()]
        s1 = f["steps/0001/S_element"][()]
        xy = f["mesh/coordinates"][()]
        c1 = f["steps/0001/contact/pair_1/CPRESS"][()]
        c2 = f["steps/0002/contact/pair_1/CPRESS"][()]
        cxy = f["steps/0002/contact/pair_1/coordinates"][()]
    assert np.abs(u1).max() == 0.0
    assert np.abs(s1[:, 1]).max() > 1e5            # stresses of the self-weight kept
    crest = np.argmax(xy[:, 1])
    assert u2[crest, 0] > 0                          # water pushes the crest downstream
    assert c1.max() > 0 and c2.max() > 0
    # the pressure varies by about 1 % per node near the tip (9.71e4, 9.72e4,
    # 9.84e4 Pa at the three nodes before the last): within 10 % of their mean
    near_tip = np.argsort(np.hypot(cxy[:, 0] - 10.0, cxy[:, 1] - 4.0))
    for c in (c1, c2):
        assert abs(c[near_tip[0]] / np.mean(c[near_tip[1:4]]) - 1) < 0.1
