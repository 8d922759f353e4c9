"""JOB.sta, CalculiX's "SUMMARY OF JOB INFORMATION": one line per converged increment
(step, increment, attempt, iterations, total, step and increment time), in CalculiX's
columns, and /steps/NNNN/increments in JOB.h5 with the same numbers.

- The format: a deck whose steps are one increment each gives the very file CalculiX
  2.20 writes for it (ccx run here when installed; a linear step is one increment in
  both codes).
- The numbers: DIRECT increments 0.25 of a period 1, then automatic ones (0.5 of a
  period 2, growing by half after two easy increments: 0.5, 0.5, 0.75, then the 0.25
  left), against the schedule computed here.
- A cut-back (the Hertz deck of test_increments.py with MAXIT=3): the increment that
  converges after one cut-back is attempt 2 and is a quarter of the first try.
- A run that stops keeps the lines of the increments it completed.
"""
import shutil
import subprocess

import h5py
import numpy as np
import pytest

from test_increments import hertz
from test_strength_reduction import dam_deck
from test_thermal import deck as thermal_deck


def bar(tmp_path, static1, static2):
    def bc(x, y):
        out = [(1, 0.0)] if x in (0.0, 3.0) else []
        return out + ([(2, 0.0)] if (x, y) == (0.0, 0.0) else [])
    text, _ = thermal_deck("CPS4", 1, bc, lambda x, y: 70.0, False)
    text = text.replace("*STATIC\n", "*STATIC" + static1 + "\n").replace("*NODE PRINT, NSET=ALL\nU\n", "")
    text += "*STEP\n*STATIC" + static2 + "\n*TEMPERATURE\nALL, 90.\n*END STEP\n"
    path = tmp_path / "bar.inp"
    path.write_text(text)
    return path


def run(exe, path, code=0):
    out = path.parent / "out"
    r = subprocess.run([exe, "-q", "-o", str(out), str(path)], capture_output=True, text=True)
    assert r.returncode == code, r.stderr
    return out / (path.stem + ".sta"), out / (path.stem + ".h5")


def read_sta(path):
    lines = path.read_text().splitlines()
    assert lines[0] == "SUMMARY OF JOB INFORMATION"
    assert lines[1] == "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME"
    rows = [line.split() for line in lines[2:]]
    return np.array([[float(v) for v in r] for r in rows]).reshape(-1, 7)


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) is not installed")
def test_same_file_as_calculix(exe, tmp_path):
    path = bar(tmp_path, "", "\n2., 2.")
    sta, _ = run(exe, path)
    subprocess.run(["ccx", "-i", "bar"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    ours = sta.read_text().splitlines()
    theirs = (tmp_path / "bar.sta").read_text().splitlines()
    assert len(theirs) == 4
    assert ours == theirs


def test_increments_and_times(exe, tmp_path):
    sta, h5 = run(exe, bar(tmp_path, ", DIRECT\n0.25, 1.", "\n0.5, 2."))
    rows = read_sta(sta)
    inc2 = [0.5, 0.5, 0.75, 0.25]
    want_inc = [0.25] * 4 + inc2
    want_step_time = list(np.cumsum([0.25] * 4)) + list(np.cumsum(inc2))
    np.testing.assert_array_equal(rows[:, 0], [1] * 4 + [2] * 4)
    np.testing.assert_array_equal(rows[:, 1], [1, 2, 3, 4] * 2)
    np.testing.assert_array_equal(rows[:, 2], 1)
    np.testing.assert_array_equal(rows[:, 3], 1)
    # the printed digits: 6 significant
    np.testing.assert_allclose(rows[:, 6], want_inc, rtol=1e-6)
    np.testing.assert_allclose(rows[:, 5], want_step_time, rtol=1e-6)
    np.testing.assert_allclose(rows[:, 4], np.array(want_step_time) + np.repeat([0.0, 1.0], 4), rtol=1e-6)
    with h5py.File(h5) as f:
        for step, sl in (("0001", slice(0, 4)), ("0002", slice(4, 8))):
            g = f[f"steps/{step}/increments"]
            np.testing.assert_allclose(g["step_time"][()], want_step_time[sl], rtol=1e-15)
            np.testing.assert_allclose(g["increment"][()], want_inc[sl], rtol=1e-15)
            np.testing.assert_array_equal(g["attempts"][()], 1)


def test_cut_back_is_another_attempt(exe, tmp_path):
    """Each cut-back quarters the increment: the first converged increment is attempt
    k with the size 0.25^(k - 1) of the first try (1); the increments add up to the
    period; no increment took more than MAXIT = 3 iterations."""
    path = tmp_path / "cut.inp"
    path.write_text(hertz(tmp_path, 3, "1., 1., 0.01"))
    sta, h5 = run(exe, path)
    rows = read_sta(sta)
    assert rows[0, 2] >= 2
    assert rows[0, 6] == pytest.approx(0.25 ** (rows[0, 2] - 1), rel=1e-6)
    assert rows[-1, 5] == pytest.approx(1.0, rel=1e-6)
    with h5py.File(h5) as f:
        g = f["steps/0001/increments"]
        np.testing.assert_array_equal(g["attempts"][()], rows[:, 2])
        np.testing.assert_array_equal(g["iterations"][()], rows[:, 3])
        assert (g["iterations"][()] <= 3).all()
        assert g["step_time"][-1] == 1.0
        assert np.sum(g["increment"][()]) == pytest.approx(1.0, rel=1e-14)


def test_stopped_run_keeps_its_increments(exe, tmp_path):
    """The dam of test_strength_reduction.py on a joint with mu = 0.2 stands under its
    weight and slides under the reservoir (exit 3): JOB.sta keeps step 1's line."""
    path = dam_deck(tmp_path / "slide.inp", mu=0.2)
    sta, _ = run(exe, path, code=3)
    rows = read_sta(sta)
    np.testing.assert_array_equal(rows[:, :2], [[1, 1]])
