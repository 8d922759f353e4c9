"""Load increments (issue 23): CalculiX's *STATIC data line and DIRECT, loads ramped
within a step (AMPLITUDE=RAMP, the default) or applied at once (AMPLITUDE=STEP),
*AMPLITUDE curves, the results of increments on request (FREQUENCY=n), the cut-back
of an increment whose contact iteration does not converge, and the errors.

A linear model is checked against itself: its answer at the end of a step does not
depend on the increments (the last increment solves with the step's loads exactly),
and at an increment it is the step's answer times the load factor of that time."""
import os
import re
import subprocess

import h5py
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

MODEL = """*NODE, NSET=ALL
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 0., 1.
5, 1., 1.
6, 2., 1.
*ELEMENT, TYPE=CPE4, ELSET=PLATE
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*NSET, NSET=BASE
1, 2, 3
*MATERIAL, NAME=ROCK
*ELASTIC
1.0e9, 0.25
*DENSITY
2500.
*SOLID SECTION, ELSET=PLATE, MATERIAL=ROCK
1.0
*AMPLITUDE, NAME=UP
0., 0., 0.5, 1., 1., 1.
*BOUNDARY
BASE, 2
1, 1
"""

# step 1: a force, gravity and a pressure; step 2: a prescribed displacement, the
# force replaced (OP=NEW); {inc1}, {inc2}: the *STATIC lines
STEPS = """*STEP{amp}
*STATIC{inc1}
*NODE FILE{freq}
U, RF
*EL FILE{freq}
S
*CLOAD
6, 1, 1.0e3
*DLOAD
PLATE, GRAV, 9.81, 0., -1.
2, P3, 1.0e4
*END STEP
*STEP
*STATIC{inc2}
*BOUNDARY
3, 1, 1, 1.0e-5
*CLOAD, OP=NEW
5, 2, -2.0e3
*END STEP
"""


def run(exe, tmp_path, text, name="job", code=0):
    deck = tmp_path / f"{name}.inp"
    deck.write_text(text)
    out = tmp_path / f"out_{name}"
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == code, r.stderr
    return out / f"{name}.h5", r.stderr


def deck(inc1="", inc2="", amp="", freq=""):
    return MODEL + STEPS.format(inc1=inc1, inc2=inc2, amp=amp, freq=freq)


def fields(h5, group):
    with h5py.File(h5) as f:
        g = f[group]
        return {k: g[k][()] for k in ("U", "S_element", "RF", "RF_total", "LOAD_total")}


@pytest.mark.parametrize("inc1, inc2", [("\n0.3, 1.", ", DIRECT\n0.3, 2."), ("\n0.1, 1., 0.01, 0.2", "\n0.5, 1.")])
def test_linear_model_same_answer_as_one_increment(exe, tmp_path, inc1, inc2):
    one, _ = run(exe, tmp_path, deck(), "one")
    many, _ = run(exe, tmp_path, deck(inc1, inc2), "many")
    for step in ("0001", "0002"):
        a, b = fields(one, f"steps/{step}"), fields(many, f"steps/{step}")
        for k in a:
            # the last increment solves with the step's loads exactly: round-off only
            np.testing.assert_allclose(b[k], a[k], rtol=1e-12, atol=1e-12 * np.abs(a[k]).max(), err_msg=k)


def test_step_times_are_total_times(exe, tmp_path):
    """The step's time attribute is the total time at its end (the periods add up)."""
    h5, _ = run(exe, tmp_path, deck("\n0.3, 1.5", ", DIRECT\n0.3, 2."))
    with h5py.File(h5) as f:
        assert f["steps/0001"].attrs["time"] == pytest.approx(1.5, rel=1e-15)
        assert f["steps/0002"].attrs["time"] == pytest.approx(3.5, rel=1e-15)
        assert f.attrs["complete"] == 1


def test_increment_results_follow_the_ramp(exe, tmp_path):
    """FREQUENCY=1: every increment's results; from rest, a linear model's U at step
    time t is t/T times the step's U (RAMP), and RF balances the loads in force."""
    h5, _ = run(exe, tmp_path, deck(", DIRECT\n0.25, 1.", ", DIRECT\n0.5, 1.", freq=", FREQUENCY=1"))
    with h5py.File(h5) as f:
        end1 = f["steps/0001/U"][()]
        frames = f["increments/0001"]
        assert sorted(frames) == ["0001", "0002", "0003"]
        for k, name in enumerate(sorted(frames), start=1):
            g = frames[name]
            assert g.attrs["time"] == pytest.approx(0.25 * k, rel=1e-15)
            np.testing.assert_allclose(g["U"][()], 0.25 * k * end1, rtol=1e-10, atol=1e-12 * np.abs(end1).max())
            np.testing.assert_allclose(g["RF_total"][()], -g["LOAD_total"][()], atol=1e-8 * np.abs(g["LOAD_total"][()]).max())
            assert "S_element" in g
        # step 2 ramps from step 1's values to its own: halfway is the mean
        end2 = f["steps/0002/U"][()]
        np.testing.assert_allclose(f["increments/0002/0001/U"][()], 0.5 * (end1 + end2), rtol=1e-10,
                                   atol=1e-12 * np.abs(end2).max())
        assert f["increments/0002/0001"].attrs["time"] == pytest.approx(1.5, rel=1e-15)
    pvd = open(h5.with_suffix(".pvd")).read()
    entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd)
    assert [float(t) for t, _ in entries] == pytest.approx([0.25, 0.5, 0.75, 1.0, 1.5, 2.0])
    assert [f for _, f in entries] == ["job_0001_0001.vtu", "job_0001_0002.vtu", "job_0001_0003.vtu",
                                       "job_0001.vtu", "job_0002_0001.vtu", "job_0002.vtu"]
    for _, f in entries:
        assert (h5.parent / f).exists()


def test_amplitude_step_applies_at_once(exe, tmp_path):
    h5, _ = run(exe, tmp_path, deck(", DIRECT\n0.25, 1.", amp=", AMPLITUDE=STEP", freq=", FREQUENCY=2"))
    with h5py.File(h5) as f:
        assert sorted(f["increments/0001"]) == ["0002"]
        np.testing.assert_allclose(f["increments/0001/0002/U"][()], f["steps/0001/U"][()], rtol=1e-12)


def test_amplitude_curve(exe, tmp_path):
    """*CLOAD, AMPLITUDE=UP (0 at t = 0, 1 from t = 0.5): the force alone, at t = 0.25
    half of it, at t = 0.5 all of it."""
    text = MODEL + """*STEP
*STATIC, DIRECT
0.25, 1.
*NODE FILE, FREQUENCY=1
U
*CLOAD, AMPLITUDE=UP
6, 1, 1.0e3
*END STEP
"""
    h5, _ = run(exe, tmp_path, text)
    with h5py.File(h5) as f:
        end = f["steps/0001/U"][()]
        for name, factor in (("0001", 0.5), ("0002", 1.0), ("0003", 1.0)):
            np.testing.assert_allclose(f[f"increments/0001/{name}/U"][()], factor * end, rtol=1e-10,
                                       atol=1e-12 * np.abs(end).max())


def hertz(tmp_path, maxit, static):
    text = open(os.path.join(ROOT, "inputs", "hertz_389_vem.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    text = text.replace("*STEP\n", f"*CONTACT CONTROLS, MAXIT={maxit}\n*STEP\n", 1)
    return text.replace("*STATIC\n", "*STATIC\n" + static + "\n", 1)


def test_cut_back_reaches_the_answer(exe, tmp_path):
    """With MAXIT=3 the Hertz load in one increment does not converge (it takes 4
    iterations): the increment is cut back and the step reaches the same contact
    pressures as the default run (whose iterations converge to 1e-10)."""
    ref, _ = run(exe, tmp_path, hertz(tmp_path, 50, "1., 1."), "ref")
    h5, _ = run(exe, tmp_path, hertz(tmp_path, 3, "1., 1., 0.01"), "cut")
    with h5py.File(ref) as a, h5py.File(h5) as b:
        pa, pb = a["steps/0001/contact/pair_1/CPRESS"][()], b["steps/0001/contact/pair_1/CPRESS"][()]
        np.testing.assert_allclose(pb, pa, rtol=1e-6, atol=1e-6 * pa.max())
        np.testing.assert_allclose(b["steps/0001/U"][()], a["steps/0001/U"][()], rtol=1e-6,
                                   atol=1e-8 * np.abs(a["steps/0001/U"][()]).max())


def test_minimum_increment_reached(exe, tmp_path):
    """MAXIT=2 never converges: cut back to the minimum 0.5, then one message naming the
    step and the time reached, exit status 4, JOB.h5 kept with complete = 0."""
    h5, err = run(exe, tmp_path, hertz(tmp_path, 2, "1., 1., 0.5"), "fail", code=4)
    assert "error: step Step-1 did not converge at step time  0.00000E+00 of  1.00000E+00" in err
    assert "the increment reached its minimum" in err
    assert "Traceback" not in err and "backtrace" not in err.lower()
    with h5py.File(h5) as f:
        assert f.attrs["complete"] == 0
        assert len(f["steps"]) == 0


@pytest.mark.parametrize("line, message", [
    ("*STATIC\n-0.1, 1.", "the initial time increment must be positive, not -0.1"),
    ("*STATIC\n0.1, 1., 0.2", "the minimum time increment 0.2 is larger than the initial increment 0.1"),
    ("*STATIC\n0.1, 1., 0.01, 0.05", "the maximum time increment 0.05 is smaller than the initial increment 0.1"),
    ("*STATIC\n*CLOAD, AMPLITUDE=DOWN", "unknown amplitude DOWN on *CLOAD"),
])
def test_bad_increments_named_at_their_line(exe, tmp_path, line, message):
    text = MODEL + "*STEP\n" + line + "\n6, 1, 1.0e3\n*END STEP\n"
    if "CLOAD" not in line:
        text = MODEL + "*STEP\n" + line + "\n*CLOAD\n6, 1, 1.0e3\n*END STEP\n"
    lineno = text.splitlines().index(line.splitlines()[-1]) + 1
    _, err = run(exe, tmp_path, text, code=1)
    assert f"job.inp:{lineno}: error: {message}" in err


def test_direct_not_dividing_is_warned(exe, tmp_path):
    """CalculiX ends the step with a shorter increment; vemcontact warns at the line."""
    text = deck(", DIRECT\n0.3, 1.")
    deckfile = tmp_path / "w.inp"
    deckfile.write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path / "w"), str(deckfile)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "warning: the fixed increment 0.3 does not divide the step time 1.: the last increment is shorter" \
        in r.stdout + r.stderr


def test_failed_run_pvd_lists_every_completed_step(exe, tmp_path):
    """The .pvd is rewritten after steps 1, 2, 4, ...; a run that fails in step 4 still
    leaves a .pvd of steps 1-3 (written when it stops), and JOB.h5 the same steps."""
    text = open(os.path.join(ROOT, "tests", "integration", "decks", "fails_in_step2.inp")).read()
    head, _, rest = text.partition("*STEP")
    good, _, bad = ("*STEP" + rest).partition("*END STEP\n")
    good += "*END STEP\n"
    h5, _ = run(exe, tmp_path, head + good * 3 + bad, code=3)
    pvd = open(h5.with_suffix(".pvd")).read()
    assert re.findall(r'file="([^"]+)"', pvd) == ["job_0001.vtu", "job_0002.vtu", "job_0003.vtu"]
    with h5py.File(h5) as f:
        assert f.attrs["complete"] == 0
        assert sorted(f["steps"]) == ["0001", "0002", "0003"]


def test_rerun_removes_increment_files(exe, tmp_path):
    """A rerun starts clean: the increments' .vtu of the previous run are removed."""
    run(exe, tmp_path, deck(", DIRECT\n0.25, 1.", freq=", FREQUENCY=1"))
    out = tmp_path / "out_job"
    assert (out / "job_0001_0002.vtu").exists()
    run(exe, tmp_path, deck())
    assert not list(out.glob("job_*_*.vtu"))
    assert (out / "job_0001.vtu").exists() and (out / "job_0002.vtu").exists()
