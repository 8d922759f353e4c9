"""Reaction forces with contact (issue 23): RF is the force the support exerts, contact
included, at every constrained node, so that RF_total balances the applied loads
(LOAD_total) in every step of every contact deck.

Before the fix RF was K u - f_ext at the constrained dofs, which at a node that is both
constrained and in contact holds the contact force too: the block of
tests/integration/decks/rf_constrained_slave.inp, pushed down by its back face whose
bottom corner node is a contact slave, reported RF at the pushed face 77 % below the
force the base's supports take (-1.58e4 against 6.76e4) and RF_total = 5.2e4 with no
load applied."""
import os
import subprocess

import h5py
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DECKS = os.path.join(ROOT, "tests", "integration", "decks")

# the contact decks of inputs/ that run in seconds, and the suite's own
CONTACT_DECKS = [os.path.join(ROOT, "inputs", d) for d in (
    "dam_joint.inp", "hertz_389_vem.inp", "hertz_389_fem.inp", "hertz_329_vem2.inp", "hertz_329_fem2.inp",
    "interface_quad.inp", "interface_tri.inp", "interface_voronoi_50.inp")] + [
    os.path.join(DECKS, "sliding_rebuild.inp"), os.path.join(DECKS, "rf_constrained_slave.inp")]


def run(exe, deck, out):
    r = subprocess.run([os.path.abspath(exe), "-q", "-o", str(out), deck], capture_output=True, text=True, cwd=os.path.dirname(deck))
    assert r.returncode == 0, r.stderr
    return os.path.join(str(out), os.path.basename(deck)[:-4] + ".h5")


def test_rf_of_constrained_slave_node(exe, tmp_path):
    """The pushed face's RF is the force the base's supports take, opposite (no load)."""
    with h5py.File(run(exe, os.path.join(DECKS, "rf_constrained_slave.inp"), tmp_path)) as f:
        g = f["steps/0001"]
        names = [n.decode() if isinstance(n, bytes) else n for n in g["RF_sets/names"][()]]
        rf = dict(zip(names, g["RF_sets/RF"][()]))
        load = g["LOAD_total"][()]
    assert np.all(load == 0.0)
    # the contact iteration converges to a residual of 1e-10 of the forces
    assert rf["BACK"][1] == pytest.approx(-rf["FIXED"][1], rel=1e-9)
    assert rf["FIXED"][1] > 6.0e4


@pytest.mark.parametrize("deck", CONTACT_DECKS, ids=[os.path.basename(d)[:-4] for d in CONTACT_DECKS])
def test_rf_total_balances_the_loads(exe, tmp_path, deck):
    """sum RF + sum f_ext = 0 in every step: K does no work on a rigid translation and
    the contact forces are equal and opposite on the two sides."""
    with h5py.File(run(exe, deck, tmp_path)) as f:
        assert f.attrs["complete"] == 1
        for name, g in f["steps"].items():
            rf, load = g["RF_total"][()], g["LOAD_total"][()]
            scale = np.abs(g["RF"][()]).sum() + np.abs(load).sum()
            # the contact residual tolerance is 1e-10 of the forces; the sum of the
            # nodal RF adds round-off of K u over the nodes
            assert np.abs(rf + load).max() <= 1e-8 * scale, (name, rf, load)
