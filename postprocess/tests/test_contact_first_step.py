"""The first contact iterations of a curved contact (Hertz, docs/contact-robustness.md,
"Curved contact: the first step").

Iteration 1 starts with only the initially touching node closed: one spring holds the
whole load and the full solve sinks the disc 0.26-0.59 (the true overclosure is 8e-4).
Before the line search of solve_contact the next active set was about twice the true
contact zone and was peeled back one ring per iteration: 4 iterations on the paper decks,
7 and 8 on the refined meshes of bench/hertz_refined.toml, and at 8e4 unknowns one
rebuild of the matrix pattern.  Now the step of a solve that closes new nodes is cut on
the penalty energy (Armijo), and the counts below are what was measured after the change;
each assertion fails with the old code.  The converged answer is the same: active set
and peak pressure as in tests/reference and the analytical Hertz solution."""
import os
import re
import subprocess

import h5py
import numpy as np

from h5results import assert_rf_balanced, contact_iterations, line_search_steps, pattern_rebuilds
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
P0 = 83.60  # analytical plane-strain Hertz peak pressure of these decks




def run(exe, deck, out):
    """Run a deck; returns its results file JOB.h5."""
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert_rf_balanced(out / (os.path.basename(str(deck))[:-4] + ".h5"))
    return out / (os.path.basename(str(deck))[:-4] + ".h5")


def iterations(h5):
    return contact_iterations(h5)


def steps(h5):
    """Line search step of every contact iteration (the records in the HDF5 file)."""
    return line_search_steps(h5)


def contact(h5, step="0001"):
    with h5py.File(h5) as f:
        g = f[f"steps/{step}/contact/pair_1"]
        return g["CPRESS"][:], g["STATUS"][:]


def deck_with(src, dst, mesh=None, penalty=None, tolerance=None):
    """A copy of inputs/<src> with another mesh, penalty slope or residual tolerance."""
    text = open(os.path.join(ROOT, "inputs", src)).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    if mesh is not None:
        text = re.sub(r"INPUT=\S+\.inp", "INPUT=" + str(mesh), text, count=1)
    if penalty is not None:
        text = text.replace("PRESSURE-OVERCLOSURE=LINEAR\n1.0e5", f"PRESSURE-OVERCLOSURE=LINEAR\n{penalty!r}")
    if tolerance is not None:
        text = text.replace("*STEP", f"*CONTACT CONTROLS, TOLERANCE={tolerance!r}\n*STEP", 1)
    dst.write_text(text)
    return dst


# measured at the default residual 1e-10 (at 1e-8: 3, 3 and 4 with the line search,
# 4 on every deck without it)
PAPER = {"hertz_389_vem": 4, "hertz_389_fem": 4, "hertz_600_vem": 4, "hertz_600_fem": 4,
         "hertz_1155_vem": 5, "hertz_1155_fem": 5}


@pytest.mark.parametrize("deck", sorted(PAPER))
def test_paper_decks(exe, tmp_path, deck):
    """Iterations at most the measured count (at the 1e-8 residual of session 1: 389 and
    600: 3, were 4; at today's 1e-10 one more), the first step
    cut (the full step sinks the disc 0.26-0.35), the last one full; the same closed
    nodes as the reference and the same peak pressure within 2e-4.  Why 2e-4: both
    runs stop at the default residual 1e-8, which leaves CPRESS up to 5.5e-4 (max norm)
    from the converged solution, and the pairing hysteresis lets the two iteration
    paths converge to pairings that differ at one node near a master vertex (8e-5 in
    CPRESS for 1155); measured peak differences 1e-6 .. 3e-5."""
    h5 = run(exe, os.path.join(ROOT, "inputs", deck + ".inp"), tmp_path)
    its = iterations(h5)
    s = steps(h5)
    print(deck, its, s)
    assert len(its) == 1 and its[0] <= PAPER[deck]
    assert len(s) == its[0] and s[0] < 0.2 and s[-1] == 1.0
    p, st = contact(tmp_path / f"{deck}.h5")
    pr, str_ = contact(os.path.join(ROOT, "tests", "reference", f"{deck}.h5"))
    assert (st == str_).all()
    assert abs(p.max() / pr.max() - 1) < 2e-4


def refined_mesh(tmp_path, variant, divisions):
    toml = open(os.path.join(ROOT, "bench", "hertz_refined.toml")).read()
    toml = toml[:toml.index("[[variant]]")] + (
        f'[[variant]]\nname = "{variant}"\nset = {{ "body.0.divisions" = {divisions[0]}, '
        f'"body.1.divisions" = {divisions[1]}, "mesh.formulation" = "vem" }}\n')
    (tmp_path / "h.toml").write_text(toml)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))
    subprocess.run([os.path.join(ROOT, ".venv", "bin", "python"), "-m", "vctools.mesh", "scene",
                    str(tmp_path / "h.toml"), "-o", str(tmp_path) + "/"], check=True, env=env,
                   capture_output=True)
    return tmp_path / f"h_{variant}.inp"


@pytest.mark.parametrize("variant, divisions, max_its, closed", [
    ("h20k", ([40, 40, 24], [64, 56]), 4, 13),    # before: 7 iterations (at 1e-8)
    ("h100k", ([90, 90, 54], [144, 126]), 4, 29),  # before: 8 iterations and 1 pattern rebuild
])
def test_refined_hertz(exe, tmp_path, variant, divisions, max_its, closed):
    """The meshes of bench/hertz_refined.toml (1.7e4 and 8.3e4 unknowns): at most 4
    iterations (measured 3 at the residual 1e-8 and 4 at 1e-10, were 7 and 8 at 1e-8),
    no pattern rebuild (h100k had one: the first
    iteration's sinking, 0.59, left the candidate pairs of the undeformed state), the
    same closed nodes as before (13 and 29) and the peak pressure within 0.5% of
    Hertz (measured +0.2%, as before the change: 83.77 and 83.74)."""
    mesh = refined_mesh(tmp_path, variant, divisions)
    h5 = run(exe, deck_with("hertz_1155_vem.inp", tmp_path / "d.inp", mesh=mesh), tmp_path)
    its = iterations(h5)
    print(variant, its, steps(h5))
    assert len(its) == 1 and its[0] <= max_its
    assert pattern_rebuilds(h5) == [0]
    p, st = contact(tmp_path / "d.h5")
    assert st.sum() == closed
    assert abs(p.max() / P0 - 1) < 0.005


@pytest.mark.parametrize("penalty, max_its", [(1.0e4, 4), (3.0e3, 4)])
def test_softer_penalty(exe, tmp_path, penalty, max_its):
    """A softer penalty sinks the disc further in the first iteration (K = 1e4, 3e3 on
    the 1155 mesh at the residual 1e-8: 5 iterations before, 3 after; at 1e-10: 4 and 3).  The answer is that of a run to the
    residual 1e-12: the same closed nodes, CPRESS within 2e-3 of its maximum (the 1e-8
    stop of the default run: measured 1.3e-3 and 1.6e-3 on the refined meshes)."""
    h5 = run(exe, deck_with("hertz_1155_vem.inp", tmp_path / "k.inp", penalty=penalty), tmp_path)
    its = iterations(h5)
    print(penalty, its, steps(h5))
    assert len(its) == 1 and its[0] <= max_its
    tight = tmp_path / "tight"
    tight.mkdir()
    run(exe, deck_with("hertz_1155_vem.inp", tight / "k.inp", penalty=penalty, tolerance=1e-12), tight)
    p, st = contact(tmp_path / "k.h5")
    pt, stt = contact(tight / "k.h5")
    assert (st == stt).all()
    assert np.abs(p - pt).max() < 2e-3 * pt.max()


def test_no_cut_without_new_contact(exe, tmp_path):
    """Where no open node closes (an interface closed from the start, a joint), every
    step is a full solve and the counts are those without the line search
    (interface_quad 4 at the residual 1e-10, 3 at 1e-8; dam_joint 2 and 2)."""
    for deck, expect in (("interface_quad", [4]), ("dam_joint", [2, 2])):
        h5 = run(exe, os.path.join(ROOT, "inputs", deck + ".inp"), tmp_path)
        assert iterations(h5) == expect
        assert steps(h5) and all(s == 1.0 for s in steps(h5))
