"""Curved contact with a stiff penalty (docs/contact-robustness.md, "Stiff penalties: no
cycling"; docs/stability-penalty.md).

On the Hertz deck inputs/hertz_389_vem.inp with K h/E >= 1e5 (h the shortest slave
segment, E = 1e3 of the disc) a large early step moves the pairing enough to open the
nodes at the edge of the contact zone (the frozen gaps are exact to O(|du|^2/h), more
than the overclosure p/K), and the next solve closes them again.  The iteration then
returns to an earlier active set from a different, lower-energy iterate; the cycle check,
which looked at the active set alone, stopped these runs with "contact iterations cycle"
(exit 4).  It now also compares the gaps, up to round-off, and a node opened by the
pairing update alone is held closed for one more solve; the runs converge in as many
iterations as at f = 1e3.  Each case below fails with the old code (exit 4 at
f = 1e5 ... 1e9)."""
import os
import re
import subprocess

import h5py
import numpy as np

from h5results import assert_rf_balanced
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
E_DISC = 1.0e3




def hertz(exe, out, penalty=None):
    """Run inputs/hertz_389_vem.inp (optionally with another penalty slope) in `out`;
    return the log, CPRESS, STATUS and the slave x coordinates."""
    text = open(os.path.join(ROOT, "inputs", "hertz_389_vem.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    if penalty is not None:
        text, n = re.subn(r"(\*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n)[^\n]*\n",
                          rf"\g<1>{penalty!r}\n", text)
        assert n == 1
    out.mkdir(parents=True, exist_ok=True)
    deck = out / "h.inp"
    deck.write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    log = (out / "h.log").read_text()
    # RF takes the contact force N = K g of the springs, whose digits fall as K grows
    # (1.2e-8 of the load at K = 1e8 E/h): balanced to 1e-6 here
    assert_rf_balanced(out / "h.h5", rtol=1e-6)
    with h5py.File(out / "h.h5") as f:
        g = f["steps/0001/contact/pair_1"]
        return log, g["CPRESS"][:], g["STATUS"][:], g["coordinates"][:, 0]


@pytest.fixture(scope="module")
def reference(exe, tmp_path_factory):
    """h from the paper deck, and the run at K h/E = 1e3 (converges in 5 iterations)."""
    base = tmp_path_factory.mktemp("stiff")
    _, _, _, x = hertz(exe, base / "probe")
    h = float(np.min(np.diff(np.sort(x))))
    _, p, st, _ = hertz(exe, base / "f1e3", 1.0e3 * E_DISC / h)
    return h, p, st


@pytest.mark.parametrize("f, max_its, nodal_tol", [(1.0e6, 5, 5e-4), (1.0e8, 5, 3e-3)])
def test_stiff_penalty_converges(exe, tmp_path, reference, f, max_its, nodal_tol):
    """K h/E = 1e6 and 1e8 (rcond 2e-7 and 2e-9, above the stops) converge in at most 5
    iterations, as the f = 1e3 run (measured 5; without the hold, 6 and 8: the edge nodes
    opened by the pairing update came back one per iteration), with the closed nodes of
    the f = 1e3 run and its peak
    pressure within 2e-4.  Why 2e-4: the penalty error of the reference run itself, since
    the Hertz peak settles like 1/f (docs/stability-penalty.md: 6.4e-4 at f = 1e2, 6.4e-5
    between 1e3 and 1e4); measured 7.1e-5 at both f.
    Every nodal CPRESS is compared too, against the peak: at f = 1e6 within 5e-4
    (measured 1.3e-4, at the edge node, where the reference's overclosure of 1e-4 h
    still widens the zone); at f = 1e8 within 3e-3 (measured 1.3e-3): the gaps carry
    an offset of about 2.4e-13 (cause not found; the same with either ordering), which K
    turns into a pressure error growing like f (1.2e-2 at f = 1e9,
    docs/stability-penalty.md)."""
    h, p_ref, st_ref = reference
    log, p, st, _ = hertz(exe, tmp_path, f * E_DISC / h)
    its = [int(m) for m in re.findall(r"contact converged in (\d+) iterations", log)]
    print(f, its, p.max() / p_ref.max() - 1, np.abs(p - p_ref).max() / p_ref.max())
    assert len(its) == 1 and its[0] <= max_its
    assert (st == st_ref).all()
    assert abs(p.max() / p_ref.max() - 1) < 2e-4
    assert np.abs(p - p_ref).max() < nodal_tol * p_ref.max()
