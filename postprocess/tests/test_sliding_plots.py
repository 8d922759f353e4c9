"""The sliding-safety pictures (vctools.plot.sliding; `vc-curves srm` and `vc-curves joint`,
Result.plot_srm and Result.plot_joint): the picture is written and the arrays drawn are
checked against what the run must hold, computed here.

The run is inputs/rock_block_crack3.inp (docs/sliding-safety.md): step 2 puts 3 m of water
into the tension crack and a triangular uplift on the 28 m joint, from gamma_w z_w at the
crack bottom (the heel, the joint's higher end) to 0 at the daylight point; step 3 is the
strength reduction.
"""
import math
import os
import re
import shutil
import subprocess

import h5py
import numpy as np
import pytest

import vctools
import vctools.plot.sliding
from vctools.plot import curves
from vctools.plot.results import ResultError
from vctools.plot.sliding import chain_order, joint_data, srm_data

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GW, ZW, LJ = 9810.0, 3.0, 28.0
C, MU = 20000.0, math.tan(math.radians(35.0))


@pytest.fixture(scope="module")
def rock_block(exe, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("rb")
    text = open(os.path.join(ROOT, "inputs", "rock_block_crack3.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    (tmp / "rb.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp), str(tmp / "rb.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return tmp / "rb.h5"


def test_chain_order_starts_at_the_higher_end():
    """Nodes of a kinked joint given shuffled come back in order from the higher end (a
    horizontal joint: from the smaller x)."""
    pts = np.array([(4.0, 10.0), (4.5, 9.0), (5.0, 8.0), (6.0, 7.8), (7.5, 7.5), (9.5, 7.1)])
    perm = np.array([3, 0, 5, 1, 4, 2])
    assert np.array_equal(perm[chain_order(pts[perm])], np.arange(6))
    flat = np.array([(9.0, 0.0), (4.0, 0.0), (6.0, 0.0), (5.0, 0.0)])
    assert list(chain_order(flat)) == [1, 3, 2, 0]


def test_joint_picture(rock_block, tmp_path):
    out = tmp_path / "joint.png"
    d = vctools.open(str(rock_block)).plot_joint(str(out), step=2, mu=MU, cohesion=C)
    assert out.stat().st_size > 0
    s = d["s"]
    # from the crack bottom (24.25, 14) down to the daylight point (0, 0), 28 m of
    # collinear nodes: the arc length is the distance from the heel (round-off)
    assert (d["x"][0], d["y"][0]) == pytest.approx((14 * math.sqrt(3), 14.0), abs=1e-9)
    assert s[-1] == pytest.approx(LJ, rel=1e-12)
    assert np.all(np.diff(s) > 0)
    # the triangular uplift, gamma_w z_w (1 - s/L): round-off
    assert d["has_uplift"]
    assert np.allclose(d["CFLUIDP"], GW * ZW * (1.0 - s / LJ), rtol=1e-12, atol=1e-6)
    closed = d["STATUS"] != 0
    assert np.allclose(d["strength"][closed], C + MU * d["CPRESS"][closed], rtol=1e-14)
    assert np.all(d["strength"][~closed] == 0.0)
    # the shear stays within the strength (CSHEAR is the balance's force: the law's bound
    # to the iteration's tolerance, 1e-6 as in test_uplift)
    assert np.all(d["shear"] <= d["strength"] * (1 + 1e-6) + 1e-9)
    assert set(np.unique(d["STATUS"])) <= {0, 3, 4}


def test_joint_command_line(rock_block, tmp_path):
    out = tmp_path / "j.png"
    rc = curves.main(["joint", str(rock_block), "--step", "2", "--mu", repr(MU), "--cohesion", repr(C),
                      "-o", str(out)])
    assert rc == 0 and out.exists()


def test_joint_units_convert(rock_block, tmp_path):
    """--units converts (vc-plot's factors), not only relabels: the SI run drawn in mm and
    kPa has arc lengths x 1e3 and stresses x 1e-3 of the same run drawn in its own units."""
    si = joint_data(str(rock_block), 2, mu=MU, cohesion=C)
    d = vctools.plot.sliding.plot_joint(str(rock_block), str(tmp_path / "u.png"), step=2, mu=MU,
                                        cohesion=C, units="mm,kPa")
    assert np.allclose(d["s"], 1e3 * si["s"], rtol=1e-14)
    for k in ("CPRESS", "CFLUIDP", "shear", "strength"):
        assert np.allclose(d[k], 1e-3 * np.asarray(si[k]), rtol=1e-14, atol=0.0)
    assert d["cohesion"] == pytest.approx(1e-3 * C, rel=1e-14)
    rc = curves.main(["joint", str(rock_block), "--step", "2", "--mu", repr(MU), "--cohesion", repr(C),
                      "--units", "mm,kPa", "-o", str(tmp_path / "v.png")])
    assert rc == 0


def test_joint_needs_the_strength(rock_block, tmp_path, capsys):
    """A file whose pair has no friction attributes: a clear error unless --mu is given."""
    bare = tmp_path / "bare.h5"
    shutil.copy(rock_block, bare)
    with h5py.File(bare, "r+") as f:
        for k in f["steps"]:
            for name, g in f["steps"][k].get("contact", {}).items():
                if name.startswith("pair_"):
                    for a in ("friction_coefficient", "cohesion"):
                        if a in g.attrs:
                            del g.attrs[a]
    with pytest.raises(ResultError, match="friction_coefficient: give --mu"):
        joint_data(str(bare), 2)
    assert curves.main(["joint", str(bare), "--step", "2", "-o", str(tmp_path / "x.png")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "give --mu" in err
    d = joint_data(str(bare), 2, mu=MU)
    assert d["cohesion"] == 0.0


def test_pair_attributes_are_the_step_values(rock_block):
    """The pair's attributes hold the deck's strength in the steps before the reduction."""
    d = joint_data(str(rock_block), 2)
    assert d["mu"] == pytest.approx(MU, rel=1e-15)
    assert d["cohesion"] == pytest.approx(C, rel=1e-15)


def test_srm_picture(rock_block, tmp_path):
    out = tmp_path / "fs.png"
    res = vctools.open(str(rock_block))
    d = res.plot_srm(str(out))
    assert out.stat().st_size > 0
    fs = d["factor_of_safety"]
    ok = d["converged"]
    # every converged trial lies at or below the factor, every failed one above it, and the
    # bracket [F_lower, F_upper] holds the factor to the tolerance
    assert ok.any() and (~ok).any()
    assert np.all(d["F"][ok] <= fs * (1 + 1e-12))
    assert np.all(d["F"][~ok] > fs)
    assert d["F_lower"] <= fs <= d["F_upper"]
    assert (d["F_upper"] - d["F_lower"]) <= 2 * d["tolerance"] * d["F_upper"]
    # u_char grows with F over the converged trials (the block moves more as the strength drops)
    order = np.argsort(d["F"][ok])
    assert np.all(np.diff(d["u_char"][ok][order]) >= 0)
    # the same arrays through the API's Step
    step = res.step(d["step"])
    assert step.strength_reduction is not None
    assert np.array_equal(step.strength_reduction["F"], d["F"])
    assert step.attrs["factor_of_safety"] == pytest.approx(fs, rel=0)


def test_srm_command_line(rock_block, tmp_path, capsys):
    out = tmp_path / "fs.png"
    assert curves.main(["srm", str(rock_block), "-o", str(out)]) == 0 and out.exists()
    fs = srm_data(str(rock_block))["factor_of_safety"]
    assert re.search(r"factor of safety ([0-9.]+)", capsys.readouterr().out).group(1) == f"{fs:.6g}"
    # a step that is not a strength reduction: one line, exit 1
    assert curves.main(["srm", str(rock_block), "--step", "1", "-o", str(tmp_path / "x.png")]) == 1
    assert "not a strength-reduction step" in capsys.readouterr().err
