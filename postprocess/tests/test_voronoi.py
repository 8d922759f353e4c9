"""Voronoi bodies: areas, validity, conformity, Lloyd energy, determinism, joints."""
import numpy as np
import pytest
import shapely

from conftest import assert_conforming, assert_valid_cells
from vctools.mesh.polymesh import Joint, VBody, voronoi_group
from vctools.mesh.scene import build, load, mesh_scene_file
from vctools.mesh.sizing import Grading
from pathlib import Path

SCENES = Path(__file__).resolve().parents[1] / "scenes"

L_SHAPE = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]          # non-convex
STAR = [[0, 0], [3, 0], [3, 3], [2, 1.2], [1.5, 3.2], [1, 1.2], [0, 3]]


def body_areas(m):
    area = m.cell_areas()
    return {name: area[m.cell_body == k].sum() for k, (name, _) in enumerate(m.bodies)}


@pytest.mark.parametrize("poly,n", [([[0, 0], [1, 0], [1, 1], [0, 1]], 300), (L_SHAPE, 200), (STAR, 400)])
def test_cells_fill_the_body_exactly(poly, n):
    m = voronoi_group([VBody("B", poly, n)], seed=5, lloyd=10)
    exact = shapely.Polygon(poly).area
    assert abs(m.cell_areas().sum() - exact) <= 1e-12 * exact
    assert_valid_cells(m)
    assert_conforming(m, shapely.Polygon(poly).exterior)
    assert abs(m.ncell - n) <= 0.02 * n
    # every body corner is a node
    for p in poly:
        assert np.min(np.hypot(*(m.nodes - p).T)) < 1e-12


def test_graded_mesh_is_finer_near_the_point():
    g = Grading([{"point": [0.0, 0.0], "ratio": 0.2, "radius": 0.8}], "B")
    m = voronoi_group([VBody("B", [[0, 0], [2, 0], [2, 2], [0, 2]], 600, g)], seed=2, lloyd=15)
    area = m.cell_areas()
    cen = np.array([m.nodes[m.cell(i)].mean(0) for i in range(m.ncell)])
    near = np.hypot(*cen.T) < 0.3
    far = np.hypot(*(cen - 2).T) < 0.6
    assert area[near].mean() < 0.25 * area[far].mean()
    assert abs(area.sum() - 4.0) <= 1e-12 * 4.0


def test_lloyd_energy_decreases():
    m = voronoi_group([VBody("B", L_SHAPE, 400)], seed=11, lloyd=25)
    e = np.array(m.info["lloyd_energy"])
    assert len(e) == 26
    assert np.all(np.diff(e) <= 1e-12 * e[0]), np.diff(e)
    assert e[-1] < 0.8 * e[0]


def test_same_seed_same_file_and_other_seed_other_file(tmp_scene, tmp_path):
    text = """
[mesh]
seed = 7
lloyd = 8
[[body]]
name = "B"
polygon = [[0, 0], [3, 0], [3, 1], [0, 1]]
cells = 150
[[joint]]
name = "J"
polyline = [[1.0, 0.0], [1.6, 0.6]]
[[selection]]
name = "BOTTOM"
y = 0
"""
    p = tmp_scene(text)
    a = Path(mesh_scene_file(p, tmp_path / "a.inp", echo=None)[0][0]).read_text()
    b = Path(mesh_scene_file(p, tmp_path / "b.inp", processes=2, echo=None)[0][0]).read_text()
    c = Path(mesh_scene_file(p, tmp_path / "c.inp", seed=8, echo=None)[0][0]).read_text()
    assert a == b
    assert a != c


def _joint_checks(m, polyline, interior_tips):
    j = m.info["joints"][0]
    segs = np.stack([polyline[:-1], polyline[1:]], 1)
    from vctools.mesh.geometry import distance_to_segments
    cells, sides = j["master"]
    # every master side lies on the polyline (both nodes and midpoint) to 1e-12
    size = np.ptp(m.nodes, axis=0).max()
    for c, s in zip(cells, sides):
        cc = m.cell(c)
        p, q = m.nodes[cc[s - 1]], m.nodes[cc[s % len(cc)]]
        d = distance_to_segments(np.array([p, q, 0.5 * (p + q)]), segs)
        assert d.max() <= 1e-12 * size
    # the joint is covered by master sides: their lengths add up to the polyline's length
    length = np.hypot(*np.diff(polyline, axis=0).T).sum()
    side_len = sum(np.hypot(*(m.nodes[m.cell(c)[s % len(m.cell(c))]] - m.nodes[m.cell(c)[s - 1]]))
                   for c, s in zip(cells, sides))
    assert abs(side_len - length) <= 1e-12 * length
    # duplicated nodes coincide; tips stay shared
    for v, copies in j["copies"].items():
        for w in copies:
            assert np.array_equal(m.nodes[v], m.nodes[w])
    for tip in interior_tips:
        at_tip = np.flatnonzero(np.hypot(*(m.nodes - tip).T) <= 1e-12 * size)
        assert len(at_tip) == 1, "the tip must be one shared node"
        assert at_tip[0] in j["shared"]
        assert at_tip[0] not in j["slave"]
    # every slave node has a coincident master node (a different copy)
    mnodes = set()
    for c, s in zip(cells, sides):
        cc = m.cell(c)
        mnodes |= {cc[s - 1], cc[s % len(cc)]}
    mxy = m.nodes[sorted(mnodes)]
    for v in j["slave"]:
        d = np.hypot(*(mxy - m.nodes[v]).T)
        assert d.min() == 0.0
        assert v not in mnodes
    # the two faces of the joint are separate: open edges along the joint on both sides
    return j


def test_interior_joint_with_two_tips_and_a_kink():
    poly = [[0, 0], [4, 0], [4, 3], [0, 3]]
    pl = np.array([[1.0, 1.0], [2.0, 1.7], [3.1, 1.4]])
    m = voronoi_group([VBody("B", poly, 500)], [Joint("J", pl)], seed=3, lloyd=15)
    assert abs(m.cell_areas().sum() - 12.0) <= 1e-12 * 12
    assert_valid_cells(m)
    assert_conforming(m, shapely.Polygon(poly).exterior, [pl])
    _joint_checks(m, pl, [pl[0], pl[-1]])


def test_edge_crack_from_the_boundary():
    poly = [[0, 0], [2, 0], [2, 1], [0, 1]]
    pl = np.array([[0.7, 1.0], [1.1, 0.45]])
    m = voronoi_group([VBody("B", poly, 300)], [Joint("J", pl)], seed=1, lloyd=10)
    assert_valid_cells(m)
    assert_conforming(m, shapely.Polygon(poly).exterior, [pl])
    j = _joint_checks(m, pl, [pl[-1]])
    # the mouth on the boundary opens: two nodes at (0.7, 1)
    assert len(np.flatnonzero(np.hypot(*(m.nodes - pl[0]).T) == 0)) == 2
    assert len(j["copies"]) >= 3


def test_dam_scene():
    m = build(load(SCENES / "ex4_dam.toml"))
    areas = body_areas(m)
    assert abs(areas["FOUNDATION"] - 250.0) <= 1e-12 * 250
    assert abs(areas["DAM"] - 17.5) <= 1e-12 * 17.5
    assert_valid_cells(m)
    pl = np.array([[4.0, 10.0], [10.0, 4.0]])
    dom = shapely.Polygon([[0, 0], [25, 0], [25, 10], [9, 10], [6, 15], [4, 15], [4, 10], [0, 10]])
    assert_conforming(m, dom.exterior, [pl])
    _joint_checks(m, pl, [pl[-1]])
    # bonded: dam and foundation share their nodes on y = 10 between x = 4 and 9
    on = np.flatnonzero((np.abs(m.nodes[:, 1] - 10) < 1e-12) & (m.nodes[:, 0] > 4) & (m.nodes[:, 0] < 9))
    assert len(on) > 5
    for v in on:
        bodies = {int(m.cell_body[c]) for c in range(m.ncell) if v in m.cell(c)}
        assert bodies == {0, 1}
    # the selections
    up = m.nodes[m.nsets["UPSTREAM"]]
    assert np.allclose(up[:, 0], 4.0) and up[:, 1].min() == 10.0 and up[:, 1].max() == 15.0
    c, s = m.esurfaces["UPSTREAM"]
    assert (m.cell_body[c] == 1).all()
    assert len(m.esurfaces["BOTTOM"][0]) > 5 and np.allclose(m.nodes[m.nsets["BOTTOM"], 1], 0)


def test_tiled_mesh_is_exact_and_the_same_with_one_or_two_processes():
    # many small tiles on a non-convex body: the bucketed halo search, redone tiles with a
    # wider halo, clipped cells in several parts, in one and in two processes
    pl = np.array([[0.5, 0.5], [1.5, 0.9], [2.5, 0.6]])
    g = Grading([{"point": [1.5, 0.9], "ratio": 0.4, "radius": 1.0}], "B")
    m1, m2 = (voronoi_group([VBody("B", STAR, 3000, g)], [Joint("J", pl)], seed=4, lloyd=4,
                            per_tile=300, processes=p) for p in (1, 2))
    assert np.array_equal(m1.nodes, m2.nodes) and np.array_equal(m1.conn, m2.conn)
    assert m1.info["lloyd_energy"] == m2.info["lloyd_energy"]
    exact = shapely.Polygon(STAR).area
    assert abs(m1.cell_areas().sum() - exact) <= 1e-12 * exact
    assert_valid_cells(m1)
    assert_conforming(m1, shapely.Polygon(STAR).exterior, [pl])
    _joint_checks(m1, pl, [pl[0], pl[-1]])


def test_triangle_and_qhull_give_the_same_cells():
    # The Delaunay library is an implementation detail: with uniform density the Lloyd
    # energies (sums over all cells) agree to rounding (1e-12 relative allows for the
    # different summation order of the few cocircular quadruples), and both meshes are exact.
    pl = np.array([[0.5, 0.5], [1.5, 0.9], [2.5, 0.6]])
    ms = [voronoi_group([VBody("B", STAR, 400)], [Joint("J", pl)], seed=4, lloyd=10, processes=1,
                        delaunay=b) for b in ("qhull", "triangle")]
    e0, e1 = (np.asarray(m.info["lloyd_energy"]) for m in ms)
    assert len(e0) == len(e1) and np.allclose(e0, e1, rtol=1e-12, atol=0)
    exact = shapely.Polygon(STAR).area
    for m in ms:
        assert m.ncell == ms[0].ncell
        assert abs(m.cell_areas().sum() - exact) <= 1e-12 * exact
        assert_valid_cells(m)
        assert_conforming(m, shapely.Polygon(STAR).exterior, [pl])
        _joint_checks(m, pl, [pl[0], pl[-1]])
