"""Structured meshes: rectangles, the Hertz half-disc, example 1's cantilever; the scenes."""
import numpy as np
import pytest
from pathlib import Path

from conftest import assert_conforming, assert_valid_cells
from vctools.mesh import structured
from vctools.mesh.scene import build, load, variants

import shapely

SCENES = Path(__file__).resolve().parents[1] / "scenes"


@pytest.mark.parametrize("shape,k", [("quad", 4), ("tri", 3)])
def test_graded_rectangle(shape, k):
    m = structured.rectangle("R", [0, 0, 10, 5], [12, 6], shape, "X", toward=[0, 5], ratio=0.2)
    assert m.ncell == 72 * (1 if shape == "quad" else 2)
    assert (np.diff(m.ptr) == k).all()
    assert abs(m.cell_areas().sum() - 50) <= 1e-12 * 50
    assert_valid_cells(m)
    assert_conforming(m, shapely.box(0, 0, 10, 5).exterior)
    xs = np.unique(m.nodes[:, 0])
    dx = np.diff(xs)
    assert abs(dx[0] / dx[-1] - 0.2) < 1e-12         # smallest / largest = ratio, fine at x = 0


@pytest.mark.parametrize("shape", ["quad", "tri"])
def test_half_disc(shape):
    m = structured.half_disc("D", [0, 20], 10, [6, 6, 4], shape, "X", ratio=0.3, radial_ratio=0.5)
    ncell = 36 + 4 * 18
    assert m.ncell == ncell * (1 if shape == "quad" else 2)
    assert_valid_cells(m)
    r = np.hypot(m.nodes[:, 0], m.nodes[:, 1] - 20)
    assert r.max() <= 10 * (1 + 1e-15) and (m.nodes[:, 0] >= 0).all()
    # the boundary: the diameter x = 0 and the arc, every arc node exactly on the circle
    arc = np.abs(r - 10) < 1e-12
    assert arc.sum() == 2 * 6 + 6 + 1
    # area: the inscribed polygon of the arc nodes plus nothing else
    ring = np.vstack([[0, 10], m.nodes[arc][np.argsort(np.arctan2(m.nodes[arc, 1] - 20, m.nodes[arc, 0]))][1:-1], [0, 30]])
    assert abs(m.cell_areas().sum() - shapely.Polygon(ring).area) < 1e-12 * 157
    # graded toward the contact point (0, 10)
    a = m.cell_areas()
    c = np.array([m.nodes[m.cell(i)].mean(0) for i in range(m.ncell)])
    assert a[np.argmin(np.hypot(c[:, 0], c[:, 1] - 10))] < 0.2 * a.max()


@pytest.mark.parametrize("dist", [0.0, 1.0, 2.5, 4.0])
def test_cantilever(dist):
    m = structured.cantilever("B", 40, 8, dist)
    d = dist * 8 / 2
    assert m.ncell == 2
    assert np.allclose(m.nodes[1], [20 - d, 0]) and np.allclose(m.nodes[4], [20 + d, 8])
    assert np.allclose(m.cell_areas(), 160)
    assert_valid_cells(m)


def test_hertz_scene_counts():
    scene = load(SCENES / "ex2_hertz.toml")
    got = {}
    for name, s in variants(scene):
        m = build(s)
        got[name] = m.ncell
        assert set(m.nsurfaces) == {"HERTZ_SLAVE"} and "HERTZ_MASTER" in m.esurfaces
        slave = m.nodes[m.nsurfaces["HERTZ_SLAVE"]]
        r = np.hypot(slave[:, 0], slave[:, 1] - 20)
        if name.endswith("vem2"):
            # second-order VEM: corners on the circle, side nodes at the middles of
            # the straight sides between them (inside the circle)
            on = np.isclose(r, 10)
            corners = slave[on]
            for q in slave[~on]:
                assert np.min(np.hypot(*(0.5 * (corners[:, None] + corners[None]) - q).T)) < 1e-12
            assert (r <= 10 + 1e-12).all() and (slave[:, 1] <= 20).all()
        else:
            assert np.allclose(r, 10) and (slave[:, 1] <= 20).all()
        c, s_ = m.esurfaces["HERTZ_MASTER"]
        assert (m.cell_body[c] == 1).all()
        assert np.allclose(m.nodes[m.nsets["HERTZ_MASTER"], 1], 10)
        assert np.allclose(m.nodes[m.nsets["DISC_TOP"]], [[0, 30]])
        assert np.allclose(m.nodes[m.nsets["SYMMETRY"], 0], 0)
    assert got == {"389_vem": 389, "389_fem": 389, "600_vem": 600, "600_fem": 600,
                   "1155_vem": 1155, "1155_fem": 1155, "329_vem2": 329, "329_fem2": 329}


def test_interface_scene():
    scene = load(SCENES / "ex3_interface.toml")
    for name, s in variants(scene):
        m = build(s)
        area = m.cell_areas()
        for k in range(2):
            assert abs(area[m.cell_body == k].sum() - 4.0) <= 1e-12 * 4
        if name.startswith("voronoi_"):
            assert m.ncell == int(name.split("_")[1])
        assert_valid_cells(m)
        sl = m.nodes[m.nsurfaces["IFACE_SLAVE"]]
        assert np.allclose(sl[:, 1], 1.0) and sl[:, 0].min() == 0 and sl[:, 0].max() == 4
        c, _ = m.esurfaces["IFACE_MASTER"]
        assert (m.cell_body[c] == 0).all()
        # non-matching meshes: the two bodies share no node
        lower = set(m.conn[np.repeat(m.cell_body == 0, np.diff(m.ptr))].tolist())
        upper = set(m.conn[np.repeat(m.cell_body == 1, np.diff(m.ptr))].tolist())
        assert not lower & upper
