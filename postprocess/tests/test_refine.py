"""Refinement by splitting marked cells (vctools.mesh.refine): areas, conformity, shape
over repeated cycles, and the joints, contact surfaces and named sets carried over."""
import numpy as np
import pytest

from vctools.mesh.errors import MeshError
from vctools.mesh.geometry import distance_to_segments
from vctools.mesh.refine import refine, shape_quality
from vctools.mesh.scene import build

DAM = """[mesh]
seed = 2
lloyd = 2
[[body]]
name = "B"
polygon = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]
cells = 40
[[joint]]
name = "J"
polyline = [[0.0, 1.5], [2.2, 1.5]]
[[selection]]
name = "BOTTOM"
y = 0.0
[[selection]]
name = "TOP"
y = 3.0
"""

HERTZ = """[mesh]
formulation = "vem"
[[body]]
name = "DISC"
half_disc = { center = [0.0, 20.0], radius = 10.0, core = 0.5 }
mesher = "quad"
divisions = [3, 3, 2]
[[body]]
name = "BLOCK"
rectangle = [0.0, 0.0, 10.0, 10.0]
mesher = "quad"
divisions = [4, 3]
[[selection]]
name = "SYMMETRY"
x = 0.0
[[contact]]
name = "HERTZ"
slave = "DISC"
master = "BLOCK"
slave_where = { circle = { center = [0.0, 20.0], radius = 10.0 }, ymax = 20.0 }
master_where = { y = 10.0 }
"""


def scene(text):
    import tomllib
    return tomllib.loads(text)


def boundary_edges(m):
    """Directed edges (u, w) of the cells with no cell holding (w, u)."""
    a, b, _, _ = m.edges()
    fw = set(zip(a.tolist(), b.tolist()))
    return np.array([(u, w) for u, w in fw if (w, u) not in fw]).reshape(-1, 2)


def check_split(m0, m, parent):
    """The children fill their parents and the mesh stays conforming: every side is shared by
    two cells in opposite directions or lies on a side of the old mesh's boundary (joint
    faces and contact surfaces are boundary); returns the children's areas."""
    area = m.cell_areas()
    assert (area > 0).all()
    # an edge appears at most once per direction: no overlapping cells
    a, b, _, _ = m.edges()
    assert len(set(zip(a.tolist(), b.tolist()))) == len(a)
    old = boundary_edges(m0)
    segs = np.stack([m0.nodes[old[:, 0]], m0.nodes[old[:, 1]]], 1)
    new = boundary_edges(m)
    # both ends and the middle of every new boundary side on the old boundary (straight sides)
    for pts in (m.nodes[new[:, 0]], m.nodes[new[:, 1]], 0.5 * (m.nodes[new[:, 0]] + m.nodes[new[:, 1]])):
        assert distance_to_segments(pts, segs).max() < 1e-12 * np.ptp(m0.nodes)
    # the boundary's length is that of the old boundary
    L = lambda m, e: np.hypot(*(m.nodes[e[:, 1]] - m.nodes[e[:, 0]]).T).sum()   # noqa: E731
    assert L(m, new) == pytest.approx(L(m0, old), rel=1e-12)
    return area


def test_split_voronoi_with_joint():
    m0 = build(scene(DAM))
    joint = m0.info["joints"][0]
    tip = joint["shared"]
    assert len(tip) == 1
    rng = np.random.default_rng(1)
    m = m0
    q0 = shape_quality(m0)
    for _ in range(4):
        mark = rng.random(m.ncell) < 0.4
        mark[np.flatnonzero(np.isin(np.arange(m.ncell), m.esurfaces["J_MASTER"][0]))[:3]] = True
        m1, parent = refine(m, mark)
        area = check_split(m, m1, parent)
        # children fill their parent exactly (areas sum to the parent's, roundoff)
        np.testing.assert_allclose(np.bincount(parent, area, minlength=m.ncell), m.cell_areas(), rtol=1e-12)
        assert np.array_equal(np.bincount(parent, minlength=m.ncell) > 1, mark)
        # a split n-gon gives one quadrilateral per corner (with hanging nodes, more vertices)
        assert (np.diff(m1.ptr)[mark[parent]] >= 4).all()
        # node sets on straight boundaries: every node of the set on its line, the set closed
        # under the new midpoints (both ends in the set: the midpoint too)
        for name, y in (("BOTTOM", 0.0), ("TOP", 3.0)):
            s = m1.nsets[name]
            assert np.abs(m1.nodes[s, 1] - y).max() < 1e-12
            assert len(s) == np.sum(np.abs(m1.nodes[np.unique(boundary_edges(m1)), 1] - y) < 1e-12)
            assert set(m.nsets[name]) <= set(s)
        # the joint: its faces keep different nodes, the tip stays shared, the master surface's
        # faces cover the joint's length and the slave nodes lie on it, none on the master face
        ms_c, ms_s = m1.esurfaces["J_MASTER"]
        ends = np.array([[m1.cell(c)[s - 1], m1.cell(c)[s % len(m1.cell(c))]] for c, s in zip(ms_c, ms_s)])
        assert np.hypot(*(m1.nodes[ends[:, 1]] - m1.nodes[ends[:, 0]]).T).sum() == pytest.approx(2.2, rel=1e-12)
        assert np.abs(m1.nodes[ends.ravel(), 1] - 1.5).max() < 1e-12
        slave = m1.nsets["J_SLAVE"]
        assert np.abs(m1.nodes[slave, 1] - 1.5).max() < 1e-12
        assert not set(slave) & set(ends.ravel())
        assert tip[0] in ends.ravel() and tip[0] not in slave
        # the faces are split independently (a joint side is boundary): the slave set is every
        # node on the joint but the tip and the master face's nodes; the master set those
        on = np.flatnonzero((np.abs(m1.nodes[:, 1] - 1.5) < 1e-12) & (m1.nodes[:, 0] < 2.2 + 1e-9))
        on = on[np.isin(on, np.unique(boundary_edges(m1)))]
        assert np.array_equal(np.sort(slave), np.setdiff1d(on, np.append(ends.ravel(), tip)))
        assert np.array_equal(np.sort(m1.nsets["J_MASTER"]), np.unique(ends))
        # the faces are split together: a slave node at every master node but the tip
        x_of = np.round(m1.nodes[:, 0], 12)
        assert np.array_equal(np.unique(x_of[slave]), np.setdiff1d(np.unique(x_of[ends]), x_of[tip]))
        m = m1
    # shape over four cycles (40 % of the cells marked at random each): the largest
    # diameter^2 / area and the smallest corner angle stay near the Voronoi mesh's
    # (measured: 4.91 -> 5.89, 38.9 -> 31.0 degrees; without merging short sides into bent
    # ones the chunkiness doubled every cycle, 28 after four)
    chunk, amin = shape_quality(m)
    assert chunk.max() < 1.5 * q0[0].max() and amin.min() > 0.7 * q0[1].min(), (chunk.max(), amin.min())


def test_split_hertz_contact_and_arc():
    m0 = build(scene(HERTZ))
    m = m0
    for cycle in range(3):
        # refine next to the contact point (0, 10)
        c = np.array([m.nodes[m.cell(i)].mean(0) for i in range(m.ncell)])
        mark = np.hypot(c[:, 0], c[:, 1] - 10.0) < 4.0 / (cycle + 1)
        m1, parent = refine(m, mark)
        # new boundary nodes of the disc's arc sit on the circle
        sl = m1.nsets["HERTZ_SLAVE"]
        assert np.abs(np.hypot(m1.nodes[sl, 0], m1.nodes[sl, 1] - 20.0) - 10.0).max() < 1e-12
        assert len(sl) > len(m.nsets["HERTZ_SLAVE"])
        # the master surface: faces of block cells on y = 10 covering [0, 10]
        mc, ms = m1.esurfaces["HERTZ_MASTER"]
        assert (m1.cell_body[mc] == 1).all()
        ends = np.array([[m1.cell(c)[s - 1], m1.cell(c)[s % len(m1.cell(c))]] for c, s in zip(mc, ms)])
        assert np.abs(m1.nodes[ends.ravel(), 1] - 10.0).max() < 1e-12
        assert np.hypot(*(m1.nodes[ends[:, 1]] - m1.nodes[ends[:, 0]]).T).sum() == pytest.approx(10.0, rel=1e-12)
        # the block (straight sides) keeps its area exactly; the disc grows toward the circle
        area = m1.cell_areas()
        blk = m1.cell_body == 1
        assert area[blk].sum() == pytest.approx(100.0, rel=1e-12)
        disc_old = m.cell_areas()[m.cell_body == 0].sum()
        assert disc_old <= area[~blk].sum() < 50 * np.pi
        # the contact's two sides are different bodies: no node of the slave on the master face
        assert not set(sl) & set(ends.ravel())
        m = m1
    # quadrilaterals stay as regular as the structured mesh
    chunk, amin = shape_quality(m)
    c0, a0 = shape_quality(m0)
    assert chunk.max() <= 1.01 * c0.max() and amin.min() >= 0.99 * a0.min()


def test_split_sets_and_fem_refused():
    m0 = build(scene(HERTZ))
    m0.elsets["E"] = np.array([0, 5])
    mark = np.zeros(m0.ncell, bool)
    mark[[0, 1]] = True
    m1, parent = refine(m0, mark)
    # children inherit the parent's element sets
    assert np.array_equal(m1.elsets["E"], np.flatnonzero(np.isin(parent, [0, 5])))
    fem = build(scene(HERTZ.replace('formulation = "vem"', 'formulation = "fem"')))
    with pytest.raises(MeshError, match="FEM"):
        refine(fem, mark)
