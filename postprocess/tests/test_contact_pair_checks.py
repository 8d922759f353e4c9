"""Decks that would make the contact meaningless are refused before the analysis
(src/driver/contact_checks.f90): a slave face on an element of its own master face
(the one-character slip `1, S1` for `2, S1`), and an initial overclosure beyond a
quarter of the master side (no contact starts that deep; the sagitta of a meshed
curve is h^2/(8R)).  Two unit squares, the upper one on the lower one; the files are
read as data (h5py) where the run succeeds."""
from __future__ import annotations

import subprocess

import h5py
import numpy as np
import pytest


def deck(y0: float, slave: str, behavior: str = "HARD") -> str:
    """Lower square [0,1]^2 (element 1), upper square [0,1] x [y0, y0+1] (element 2);
    slave = element surface `slave` (correct: "2, S1", the upper's bottom), master =
    the lower's top (1, S3); the upper's top pressed down by 1e-3."""
    penalty = "\n1.0e12" if behavior == "LINEAR" else ""
    return f"""*NODE, NSET=NALL
1, 0, 0
2, 1, 0
3, 1, 1
4, 0, 1
5, 0, {y0}
6, 1, {y0}
7, 1, {y0 + 1}
8, 0, {y0 + 1}
*ELEMENT, TYPE=CPE4, ELSET=LOWER
1, 1, 2, 3, 4
*ELEMENT, TYPE=CPE4, ELSET=UPPER
2, 5, 6, 7, 8
*NSET, NSET=BOTTOM
1, 2
*NSET, NSET=TOP
7, 8
*SURFACE, NAME=SLAVE, TYPE=ELEMENT
{slave}
*SURFACE, NAME=MASTER, TYPE=ELEMENT
1, S3
*MATERIAL, NAME=STEEL
*ELASTIC
1.0e9, 0.0
*SOLID SECTION, ELSET=LOWER, MATERIAL=STEEL
1.0
*SOLID SECTION, ELSET=UPPER, MATERIAL=STEEL
1.0
*SURFACE INTERACTION, NAME=I
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE={behavior}{penalty}
*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE
SLAVE, MASTER
*BOUNDARY
BOTTOM, 1, 2
TOP, 1, 1, 0.0
TOP, 2, 2, -1.0e-3
*STEP
*STATIC
*END STEP
"""


def run(exe, tmp_path, name, text):
    path = tmp_path / f"{name}.inp"
    path.write_text(text)
    p = subprocess.run([exe, "-q", "-o", str(tmp_path / name), str(path)], capture_output=True, text=True,
                       timeout=120, check=False)
    return p, tmp_path / name / f"{name}.h5"


def test_correct_pair_runs(exe, tmp_path):
    """Control: the upper square on the lower one, HARD: both compressed alike (nu = 0,
    equal moduli), so the contact pressure is E * 1e-3 / 2 (two unit heights in series)."""
    p, h5 = run(exe, tmp_path, "good", deck(1.0, "2, S1"))
    assert p.returncode == 0, p.stderr
    with h5py.File(h5) as f:
        cpress = f["steps/0001/contact/pair_1/CPRESS"][...]
    # 1e-8: HARD meets the constraint to round-off of the 2-element system
    assert np.allclose(cpress, 1.0e9 * 1.0e-3 / 2, rtol=1e-8), cpress


def test_slave_on_the_master_element_refused(exe, tmp_path):
    p, _ = run(exe, tmp_path, "slip", deck(1.0, "1, S1"))
    assert p.returncode == 1, p.stderr
    first = p.stderr.splitlines()[0]
    assert first.startswith(str(tmp_path / "slip.inp") + ":") and "element 1 has both a slave side" in first, first


@pytest.mark.parametrize("behavior", ["HARD", "LINEAR"])
def test_deep_initial_overclosure_refused(exe, tmp_path, behavior):
    """The upper square starts half a side into the lower one (0.5 > 0.25 of the side)."""
    p, _ = run(exe, tmp_path, "deep", deck(0.5, "2, S1", behavior))
    assert p.returncode == 1, p.stderr
    first = p.stderr.splitlines()[0]
    assert "deep.inp:" in first and "overclosure of  5.000E-01" in first and "from node 3 to node 4" in first, first


def test_small_initial_overclosure_accepted(exe, tmp_path):
    """0.1 of the side (below the quarter): a shrink fit, run as given."""
    p, _ = run(exe, tmp_path, "fit", deck(0.9, "2, S1", "LINEAR"))
    assert p.returncode == 0, p.stderr
