"""vc-adapt (postprocess/vctools/adapt.py) on the L-shaped domain, whose re-entrant corner
makes the stress singular (r^(lambda - 1), lambda = 0.5445 for the 270-degree corner): the
energy error of uniform refinement falls like N^(-lambda/2) = N^-0.27 asymptotically, that of
bulk-marked adaptive refinement like N^-1/2 (optimal for k = 1).  vc-adapt splits the marked
cells (the default for VEM); remeshing with a size field is checked on two cycles."""
import math

import h5py
import numpy as np
import pytest

from vctools import adapt

SCENE = """[mesh]
title = "L-shaped domain"
seed = 3
lloyd = 20
plane = "strain"

[[body]]
name = "L"
polygon = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]
cells = 60

[[selection]]
name = "BOTTOM"
y = 0.0

[[selection]]
name = "TOP"
y = 2.0
"""

DECK = """*HEADING
L-shaped domain: bottom clamped, top edge moved sideways (re-entrant corner at (1, 1))
*INCLUDE, INPUT=lshape_mesh.inp
*MATERIAL, NAME=M
*ELASTIC
1000.0, 0.3
*SOLID SECTION, ELSET=L, MATERIAL=M
1.0
*BOUNDARY
BOTTOM, 1, 2
*STEP
*STATIC
*BOUNDARY
TOP, 1, 1, 0.01
TOP, 2, 2, 0.0
*END STEP
"""


def rate(rows, first=0):
    """Slope of -log(estimate) against log(unknowns) from row `first` to the last."""
    n = [r["unknowns"] for r in rows[first:]]
    e = [r["estimate"] for r in rows[first:]]
    return -np.polyfit(np.log(n), np.log(e), 1)[0]


@pytest.fixture
def lshape(tmp_path):
    (tmp_path / "lshape.toml").write_text(SCENE)
    (tmp_path / "lshape.inp").write_text(DECK)
    return tmp_path


def test_adaptive_rate_on_lshape(lshape, exe):
    lines = []
    rows = adapt.adapt(lshape / "lshape.inp", lshape / "lshape.toml", 1e-3, lshape / "ad", max_unknowns=5000,
                       exe=exe, echo=lines.append)
    assert len(rows) >= 5, lines
    assert "beyond the budget" in lines[-1]
    # every cycle kept: mesh, size field, deck and results; the HDF5 agrees with the table
    for r in rows:
        c = lshape / "ad" / f"cycle_{r['cycle']:02d}"
        assert (c / "mesh.inp").is_file() and (c / "lshape.inp").is_file()
        with h5py.File(c / "lshape.h5") as f:
            assert 2 * len(f["mesh/coordinates"]) == r["unknowns"]
            assert f["steps/0001"].attrs["error_estimate"] == r["estimate"]
        # the named selections survive remeshing: the deck's BOTTOM and TOP sets are there
        text = (c / "mesh.inp").read_text().upper()
        assert "NSET=BOTTOM" in text and "NSET=TOP" in text
    # splitting: the scene is meshed once, every later mesh is the previous one split
    assert not any((lshape / "ad" / f"cycle_{k:02d}" / "size.npz").exists() for k in range(len(rows)))
    assert "split" in (lshape / "ad" / "cycle_01" / "mesh.inp").read_text().splitlines()[2]
    assert all(b["estimate"] < a["estimate"] for a, b in zip(rows, rows[1:]))
    # the marked cells gather at the corner: the smallest cells of the last mesh are there
    x = adapt.read_estimate(lshape / "ad" / f"cycle_{rows[-1]['cycle']:02d}" / "lshape.h5")
    cen, area = adapt.cell_geometry(*x[1:])
    small = cen[np.argsort(area)[:10]]
    assert np.hypot(small[:, 0] - 1, small[:, 1] - 1).max() < 0.1
    r_ad = rate(rows, 2)
    # optimal 0.5; 0.42 leaves room for the pre-asymptotic cycles and the random seeds
    assert r_ad > 0.42, rows

    uni = adapt.adapt(lshape / "lshape.inp", lshape / "lshape.toml", 1e-3, lshape / "un", max_unknowns=5000,
                      uniform=True, exe=exe, echo=lines.append)
    assert len(uni) == 3
    r_un = rate(uni)
    # singular: uniform refinement is slower (0.27 asymptotically, 0.335 measured here)
    assert r_un < 0.4 and r_un < r_ad - 0.08, (r_un, r_ad)
    # the same estimated error with fewer unknowns (2828 against 3848 here; the gap widens
    # with refinement, docs/error-estimate.md)
    target = uni[-1]["estimate"]
    n_ad = min(r["unknowns"] for r in rows if r["estimate"] <= target)
    assert n_ad < 0.8 * uni[-1]["unknowns"], (n_ad, uni[-1]["unknowns"])


def test_target_reached_and_errors(lshape, exe):
    lines = []
    rows = adapt.adapt(lshape / "lshape.inp", lshape / "lshape.toml", 0.16, lshape / "t", exe=exe, echo=lines.append)
    assert rows[-1]["relative_error"] <= 0.16 < rows[-2]["relative_error"]
    assert "reached" in lines[-1]
    assert adapt.parse_fraction("1%") == pytest.approx(0.01)
    assert adapt.parse_fraction("0.02") == pytest.approx(0.02)
    for bad in ("abc", "0", "150%"):
        with pytest.raises(adapt.AdaptError):
            adapt.parse_fraction(bad)
    assert adapt.main([str(lshape / "missing.inp"), "--scene", str(lshape / "lshape.toml"), "--exe", exe]) == 2


def test_doerfler():
    eta = np.array([1.0, 3.0, 2.0, 0.5])
    # squares 1, 9, 4, 0.25: 9 alone holds 63 % of 14.25; 9 + 4 hold 91 %
    assert adapt.doerfler(eta, 0.5).tolist() == [False, True, False, False]
    assert adapt.doerfler(eta, 0.7).tolist() == [False, True, True, False]
    assert adapt.doerfler(eta, 1.0).all()
    assert math.isclose(adapt.doerfler(np.zeros(3), 0.5).sum(), 3)


def test_size_field_grading(tmp_path):
    from vctools.mesh.errors import MeshError
    from vctools.mesh.sizing import Grading
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    np.savez(tmp_path / "f.npz", points=pts, size=np.array([0.1, 0.2, 0.2, 0.4]))
    g = Grading([{"field": str(tmp_path / "f.npz")}], "body 'B'")
    v = g.relative_size(np.vstack([pts, [[0.5, 0.5]]]))
    # at the points: their sizes over the largest; at the centre, equidistant from all
    # four: the geometric mean (0.1 * 0.2 * 0.2 * 0.4)^(1/4) / 0.4
    np.testing.assert_allclose(v, [0.25, 0.5, 0.5, 1.0, 0.2 / 0.4], rtol=1e-12)
    # gradation limit: a small size spreads to its neighbours by at most 0.3 per unit length
    s = adapt.graded_sizes(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), np.array([0.01, 1.0, 1.0]))
    np.testing.assert_allclose(s, [0.01, 0.31, 0.61])
    np.savez(tmp_path / "bad.npz", points=pts, size=np.array([0.1, 0.0, 0.2, 0.4]))
    for bad in ("missing.npz", "bad.npz"):
        with pytest.raises(MeshError, match="grading field"):
            Grading([{"field": str(tmp_path / bad)}], "body 'B'")


def test_remesh_option_and_fem_refused(lshape, exe):
    lines = []
    rows = adapt.adapt(lshape / "lshape.inp", lshape / "lshape.toml", 1e-3, lshape / "r", max_cycles=1,
                       exe=exe, refine="remesh", echo=lines.append)
    assert len(rows) == 2 and "after 1 cycles" in lines[-1]
    # remeshing: the size field of cycle 0 made cycle 1's mesh, more cells where marked
    assert (lshape / "r" / "cycle_00" / "size.npz").is_file()
    assert rows[1]["cells"] > rows[0]["cells"] and rows[1]["estimate"] < rows[0]["estimate"]
    # splitting FEM cells is refused with a message naming the FEM body (remesh instead)
    (lshape / "fem.toml").write_text(SCENE.replace('plane = "strain"', 'plane = "strain"\nformulation = "fem"')
                                     .replace('polygon = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], '
                                              '[1.0, 2.0], [0.0, 2.0]]\ncells = 60',
                                              'rectangle = [0.0, 0.0, 2.0, 2.0]\nmesher = "quad"'))
    with pytest.raises(adapt.AdaptError, match="FEM: L"):
        adapt.adapt(lshape / "lshape.inp", lshape / "fem.toml", 1e-3, lshape / "f", exe=exe, refine="split",
                    echo=lines.append)


HERTZ_SCENE = """[mesh]
formulation = "vem"
[[body]]
name = "DISC"
half_disc = { center = [0.0, 20.0], radius = 10.0, core = 0.5 }
mesher = "quad"
divisions = [4, 4, 2]
grading = { ratio = 0.3, radial_ratio = 0.4 }
[[body]]
name = "BLOCK"
rectangle = [0.0, 0.0, 10.0, 10.0]
mesher = "quad"
divisions = [6, 5]
grading = { point = [0.0, 10.0], ratio = 0.3 }
[[selection]]
name = "SYMMETRY"
x = 0.0
[[selection]]
name = "BLOCK_BOTTOM"
y = 0.0
[[selection]]
name = "ARC"
circle = { center = [0.0, 20.0], radius = 10.0 }
ymin = 20.0
body = "DISC"
[[contact]]
name = "HERTZ"
slave = "DISC"
master = "BLOCK"
slave_where = { circle = { center = [0.0, 20.0], radius = 10.0 }, ymax = 20.0 }
master_where = { y = 10.0 }
"""

HERTZ_DECK = """*HEADING
Hertz contact, small, the load spread over the upper arc
*INCLUDE, INPUT=hz_mesh.inp
*MATERIAL, NAME=DISC_MATERIAL
*ELASTIC
1.0e3, 0.3
*MATERIAL, NAME=BLOCK_MATERIAL
*ELASTIC
1.0e6, 0.3
*SOLID SECTION, ELSET=DISC, MATERIAL=DISC_MATERIAL
1.0
*SOLID SECTION, ELSET=BLOCK, MATERIAL=BLOCK_MATERIAL
1.0
*SURFACE INTERACTION, NAME=DISC_ON_BLOCK
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
1.0e5
*CONTACT PAIR, INTERACTION=DISC_ON_BLOCK, TYPE=NODE TO SURFACE
HERTZ_SLAVE, HERTZ_MASTER
*BOUNDARY
SYMMETRY, 1
BLOCK_BOTTOM, 1, 2
*STEP
*STATIC
*DSLOAD
ARC, P, 10.0
*NODE FILE
U, RF
*EL FILE
S
*CONTACT FILE
CSTR
*END STEP
"""


def test_split_keeps_contact_working(tmp_path, exe):
    """Three cycles of splitting on a contact model: the surfaces written from the split
    mesh carry the load through the contact in every cycle (the disc is held vertically by
    the contact alone, so the block's support takes the whole load: the pressure 10 on the
    quarter arc's chords has the vertical resultant 10 times their horizontal span), and the
    contact zone gains slave nodes."""
    (tmp_path / "hz.toml").write_text(HERTZ_SCENE)
    (tmp_path / "hz.inp").write_text(HERTZ_DECK)
    rows = adapt.adapt(tmp_path / "hz.inp", tmp_path / "hz.toml", 1e-4, tmp_path / "a", max_cycles=2, exe=exe,
                       echo=lambda s: None)
    assert len(rows) == 3 and rows[2]["estimate"] < rows[0]["estimate"]
    slaves = []
    for r in rows:
        with h5py.File(tmp_path / "a" / f"cycle_{r['cycle']:02d}" / "hz.h5") as f:
            st = f["steps/0001"]
            names = [n.decode() if isinstance(n, bytes) else str(n) for n in st["RF_sets/names"][...]]
            rf = st["RF_sets/RF"][...][names.index("BLOCK_BOTTOM")]
            # the loaded chords run from (0, 30) to the arc's last node at y >= 20 (the graded
            # arc has none at (10, 20)): vertical resultant 10 times that node's x
            x = f["mesh/coordinates"][...]
            ids = list(f["mesh/node_ids"][...])
            text = (tmp_path / "a" / f"cycle_{r['cycle']:02d}" / "mesh.inp").read_text()
            arc = [int(v) for v in text.split("*NSET, NSET=ARC\n")[1].split("*")[0].replace(",", " ").split()]
            span = max(x[ids.index(v), 0] for v in arc)
            # equilibrium through the contact; 1e-6: the contact iteration's force tolerance
            assert rf[1] == pytest.approx(10.0 * span, rel=1e-6)
            p = st["contact/pair_1/CPRESS"][...]
            assert p.max() > 0
            slaves.append(len(p))
    assert slaves[0] < slaves[1] < slaves[2], slaves
