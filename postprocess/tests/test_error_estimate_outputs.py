"""The error estimate's fields follow the output requests (written with S), for models
with first- and with second-order elements."""
import subprocess

import h5py
import meshio
import numpy as np
import pytest

# a 2 x 1 cantilever of four CPE4 / CPE8 cells, clamped at x = 0, shear at x = 2
NODES4 = """1, 0, 0
2, 1, 0
3, 2, 0
4, 0, 1
5, 1, 1
6, 2, 1
"""
NODES8 = NODES4 + """7, 0.5, 0
8, 1.5, 0
9, 0.5, 1
10, 1.5, 1
11, 0, 0.5
12, 1, 0.5
13, 2, 0.5
"""


def deck(order, requests=""):
    if order == 1:
        nodes, etype, elems = NODES4, "CPE4", "1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n"
    else:
        nodes, etype, elems = NODES8, "CPE8", "1, 1, 2, 5, 4, 7, 12, 9, 11\n2, 2, 3, 6, 5, 8, 13, 10, 12\n"
    return f"""*NODE
{nodes}*ELEMENT, TYPE={etype}, ELSET=B
{elems}*MATERIAL, NAME=M
*ELASTIC
1000.0, 0.3
*SOLID SECTION, ELSET=B, MATERIAL=M
1.0
*BOUNDARY
1, 1, 2
4, 1, 2
*STEP
*STATIC
*CLOAD
3, 2, -1.0
6, 2, -1.0
{requests}*END STEP
"""


def run(exe, tmp_path, text):
    p = tmp_path / "job.inp"
    p.write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), str(p)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    with h5py.File(tmp_path / "job.h5") as f:
        g = f["steps/0001"]
        h5 = {k: g[k][...] for k in g if isinstance(g[k], h5py.Dataset)}
        attrs = dict(g.attrs)
    cells = meshio.read(tmp_path / "job_0001.vtu").cell_data
    return h5, attrs, cells


@pytest.mark.parametrize("requests, written", [("", True),
                                               ("*NODE FILE\nU\n*EL FILE\nS\n", True),
                                               ("*NODE FILE\nU\n*EL FILE\nE\n", False)])
def test_indicator_follows_the_stress_request(exe, tmp_path, requests, written):
    h5, attrs, cells = run(exe, tmp_path, deck(1, requests))
    assert ("ERROR_INDICATOR" in h5) == written
    assert ("ERROR_INDICATOR" in cells) == written
    assert ("error_estimate" in attrs) == written and ("energy_norm" in attrs) == written
    if written:
        vtu = np.concatenate(cells["ERROR_INDICATOR"])
        np.testing.assert_array_equal(vtu, h5["ERROR_INDICATOR"])   # bit-exact in both files
        # the estimate is the root of the sum of the squared indicators (round-off)
        assert attrs["error_estimate"] == pytest.approx(np.sqrt(np.sum(vtu**2)), rel=1e-12)
        assert attrs["error_estimate"] > 0


@pytest.mark.parametrize("requests, written", [("", True), ("*NODE FILE\nU\n*EL FILE\nE\n", False)])
def test_estimate_for_second_order_elements(exe, tmp_path, requests, written):
    """CPE8 cells get the second-order recovery's indicators, written like the k = 1 ones."""
    h5, attrs, cells = run(exe, tmp_path, deck(2, requests))
    assert ("ERROR_INDICATOR" in h5) == written and ("ERROR_INDICATOR" in cells) == written
    assert ("error_estimate" in attrs) == written
    if written:
        vtu = np.concatenate(cells["ERROR_INDICATOR"])
        np.testing.assert_array_equal(vtu, h5["ERROR_INDICATOR"])
        assert vtu.shape == (2,) and (vtu > 0).all()
        assert attrs["error_estimate"] == pytest.approx(np.sqrt(np.sum(vtu**2)), rel=1e-12)
        assert "S_element" in h5 and "S" in cells
