"""Second-order meshes from the mesher ([mesh] order = 2): one node per side, shared
by the two cells on an interior side, split on joints like the corners, at the
middle of the side, or on the circle on a curved boundary (FEM and VEM); the deck lists
corners then side nodes (VPE2, CPE8, CPE6) and vemcontact runs it."""
import subprocess

import numpy as np
import pytest

from vctools.mesh import MeshError
from vctools.mesh.deck import write_deck
from vctools.mesh.scene import build, header

import tomllib

VORONOI_JOINT = """
[mesh]
seed = 2
lloyd = 10
order = 2
[[body]]
name = "B"
polygon = [[0, 0], [4, 0], [4, 2], [0, 2]]
cells = 120
[[joint]]
name = "J"
polyline = [[1, 1], [3, 1.2]]
[[selection]]
name = "BOTTOM"
y = 0.0
"""


def sides(m):
    a, b, cell, _ = m.edges()
    return a, b, cell, m.side_nodes


def test_voronoi_side_nodes_shared_and_split_on_the_joint():
    m = build(tomllib.loads(VORONOI_JOINT))
    a, b, cell, s = sides(m)
    assert s is not None and len(s) == len(a)
    # at the middle of every side
    assert np.abs(m.nodes[s] - 0.5 * (m.nodes[a] + m.nodes[b])).max() <= 1e-14 * 4
    # one side node per undirected side: shared exactly by the cells sharing the corners
    key = np.minimum(a, b) * len(m.nodes) + np.maximum(a, b)
    for k in np.unique(key):
        assert len(set(s[key == k].tolist())) == 1
    assert len(np.unique(s)) == len(np.unique(key))
    # the joint: its two faces have different corner nodes, hence different side nodes
    on_joint = []
    pl = np.array([[1, 1], [3, 1.2]])
    t = (pl[1] - pl[0]) / np.hypot(*(pl[1] - pl[0]))
    mid = m.nodes[s]
    d = np.abs((mid[:, 0] - pl[0, 0]) * t[1] - (mid[:, 1] - pl[0, 1]) * t[0])
    along = (mid - pl[0]) @ t
    on_joint = np.flatnonzero((d < 1e-9) & (along > 0) & (along < np.hypot(*(pl[1] - pl[0]))))
    # each joint side appears twice (one per face), with two different side nodes
    pts = {}
    for i in on_joint:
        pts.setdefault(tuple(np.round(mid[i], 9)), set()).add(int(s[i]))
    assert pts and all(len(v) == 2 for v in pts.values())
    # the node set of a selection takes the side nodes on its line
    bottom = m.nodes[m.nsets["BOTTOM"]]
    assert np.allclose(bottom[:, 1], 0.0)
    assert len(m.nsets["BOTTOM"]) == 2 * np.count_nonzero(
        (np.abs(m.nodes[a, 1]) < 1e-12) & (np.abs(m.nodes[b, 1]) < 1e-12)) + 1


def test_voronoi_order2_deck_runs(exe, tmp_path):
    m = build(tomllib.loads(VORONOI_JOINT))
    mesh = tmp_path / "mesh.inp"
    write_deck(m, str(mesh), header(m))
    text = mesh.read_text()
    assert "TYPE=VPE2" in text and "TYPE=VPE," not in text
    deck = tmp_path / "run.inp"
    deck.write_text(f"""*INCLUDE, INPUT={mesh}
*MATERIAL, NAME=M
*ELASTIC
1000.0, 0.25
*DENSITY
1.0
*SOLID SECTION, ELSET=B, MATERIAL=M
1.0
*BOUNDARY
BOTTOM, 1, 2
*STEP
*STATIC
*DLOAD
B, GRAV, 1.0, 0.0, -1.0
*END STEP
""")
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_fem_half_disc_side_nodes_on_the_circle():
    scene = """
[mesh]
order = 2
formulation = "fem"
[[body]]
name = "D"
half_disc = { center = [0, 10], radius = 10 }
divisions = [3, 3, 3]
"""
    m = build(tomllib.loads(scene))
    a, b, cell, s = sides(m)
    r = np.hypot(m.nodes[:, 0], m.nodes[:, 1] - 10)
    on_arc = (np.abs(r[a] - 10) < 1e-9) & (np.abs(r[b] - 10) < 1e-9)
    assert on_arc.sum() > 0
    assert np.abs(r[s[on_arc]] - 10).max() <= 1e-12 * 10
    # elsewhere at the middle
    assert np.abs(m.nodes[s[~on_arc]] - 0.5 * (m.nodes[a[~on_arc]] + m.nodes[b[~on_arc]])).max() <= 1e-12
    text = write_deck(m, str("/dev/null"))
    assert "TYPE=CPE8" in text
    # the VEM body (curved sides of the k = 2 virtual element) the same way
    m2 = build(tomllib.loads(scene.replace('"fem"', '"vem"')))
    a, b, cell, s = sides(m2)
    r = np.hypot(m2.nodes[:, 0], m2.nodes[:, 1] - 10)
    on_arc = (np.abs(r[a] - 10) < 1e-9) & (np.abs(r[b] - 10) < 1e-9)
    assert on_arc.sum() > 0
    assert np.abs(r[s[on_arc]] - 10).max() <= 1e-12 * 10
    assert np.abs(m2.nodes[s[~on_arc]] - 0.5 * (m2.nodes[a[~on_arc]] + m2.nodes[b[~on_arc]])).max() <= 1e-12


def test_triangles_become_cpe6_and_errors():
    scene = """
[mesh]
order = 2
formulation = "fem"
plane = "stress"
[[body]]
name = "R"
rectangle = [0, 0, 2, 1]
mesher = "tri"
divisions = [2, 2]
"""
    m = build(tomllib.loads(scene))
    text = write_deck(m, "/dev/null")
    assert "TYPE=CPS6" in text
    line = [ln for ln in text.splitlines() if ln.startswith("1, ")][-1]
    assert len(line.split(",")) == 7      # id, 3 corners, 3 side nodes
    with pytest.raises(MeshError, match="order must be 1 or 2"):
        build(tomllib.loads(scene.replace("order = 2", "order = 3")))
