"""Hertz contact with SURFACE TO SURFACE (issue 22).  First, an unstructured curved body: the paper's half model
(disc R = 10 at (0, 20), E = 1e3, on the block [0,10]x[0,10], E = 1e6, nu = 0.3, plane
strain, 100 N at the top of the half disc; analytical peak p0 = 83.60), but the disc
is a polygon of `narc` sides on the circle meshed by Voronoi cells (675, graded toward
the contact point, so about the paper's 1155 elements with the block's 24 x 20 quads).
Its boundary has nodes at the polygon's vertices and, where cells are smaller than the
polygon's sides, also on straight pieces between them: the faces that a curvature
guess once bent.  HARD contact, the disc as slave and as master.

SURFACE TO SURFACE keeps each body's polygon (docs/contact-formulation.md, "Curved
faces"), so its peak carries the polygon's own error, O(sagitta / side), which falls
as the polygon is refined: asserted with narc = 240 and 480.  Then the paper's own
meshes: Hertz 1155 (first order) and 329 (VPE2) with SURFACE TO SURFACE, each against
83.60 and a refinement.
"""
import os
import subprocess

import h5py
import numpy as np
import pytest

from vctools.mesh.scene import mesh_scene_file

P0 = 83.60

SCENE = """
[mesh]
seed = 3
lloyd = 20
formulation = "vem"

[[body]]
name = "DISC"
polygon = {disc}
mesher = "voronoi"
cells = 675
grading = {{ point = [0.0, 10.0], ratio = 0.08, radius = 10.0 }}

[[body]]
name = "BLOCK"
rectangle = [0.0, 0.0, 10.0, 10.0]
mesher = "quad"
divisions = [24, 20]
grading = {{ point = [0.0, 10.0], ratio = 0.2 }}

[[selection]]
name = "SYMMETRY"
x = 0.0

[[selection]]
name = "BLOCK_BOTTOM"
y = 0.0

[[selection]]
name = "DISC_TOP"
point = [0.0, 30.0]

[[contact]]
name = "DSLAVE"
slave = "DISC"
master = "BLOCK"
slave_where = {{ polyline = {arc} }}
master_where = {{ y = 10.0 }}

[[contact]]
name = "DMASTER"
slave = "BLOCK"
master = "DISC"
slave_where = {{ y = 10.0 }}
master_where = {{ polyline = {arc} }}
"""


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    out = {}
    for narc in (240, 480):
        d = tmp_path_factory.mktemp(f"hertz_{narc}")
        th = np.linspace(-np.pi / 2, np.pi / 2, narc + 1)
        disc = [[float(10 * np.cos(t)), float(20 + 10 * np.sin(t))] for t in th]
        disc[0], disc[-1] = [0.0, 10.0], [0.0, 30.0]
        scene = d / "hertz.toml"
        scene.write_text(SCENE.format(disc=disc, arc=disc[: narc // 2 + 1]))
        mesh_scene_file(scene, out=d / "hertz.inp", echo=None)
        out[narc] = d
    return out


def peak(exe, d, pair, pair_type):
    name = f"{pair}_{pair_type.split()[0]}"
    (d / f"{name}.inp").write_text(f"""*INCLUDE, INPUT=hertz.inp
*MATERIAL, NAME=D
*ELASTIC
1000.0, 0.3
*MATERIAL, NAME=B
*ELASTIC
1.0e6, 0.3
*SOLID SECTION, ELSET=DISC, MATERIAL=D
1.0
*SOLID SECTION, ELSET=BLOCK, MATERIAL=B
1.0
*SURFACE INTERACTION, NAME=I
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD
*CONTACT PAIR, INTERACTION=I, TYPE={pair_type}
{pair}_SLAVE, {pair}_MASTER
*BOUNDARY
SYMMETRY, 1
BLOCK_BOTTOM, 1, 2
*STEP
*STATIC
*CLOAD
DISC_TOP, 2, -100.0
*END STEP
""")
    r = subprocess.run([exe, "-q", "-o", str(d / "out"), str(d / f"{name}.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(d / "out" / f"{name}.h5", "r") as f:
        return float(np.array(f["steps/0001/contact/pair_1/CPRESS"]).max())


def test_voronoi_disc_slave(exe, meshes):
    """The disc as slave: the peak within 2 % of p0 with both TYPEs (measured +1.04 %
    STS, +1.02 % NTS at narc = 480) and closer to it than with narc = 240."""
    for pair_type in ("SURFACE TO SURFACE", "NODE TO SURFACE"):
        fine = peak(exe, meshes[480], "DSLAVE", pair_type)
        coarse = peak(exe, meshes[240], "DSLAVE", pair_type)
        assert abs(fine / P0 - 1) <= 0.02, (pair_type, fine)
        assert abs(fine / P0 - 1) < abs(coarse / P0 - 1), (pair_type, coarse, fine)


def test_voronoi_disc_master_sts(exe, meshes):
    """The disc as master with SURFACE TO SURFACE: every inserted node on the disc's
    polygon; the peak (813 with the former curvature placement; +3.4 % with the
    disc's own normal at each pair, which tilts by up to a/R = 0.15 across the contact
    zone and so loaded the soft disc with a shear toward the axis) within 2 % of p0
    with the normal of the interface the faces become (common_normal: the stiff
    block's) and the pressure on the block's own sides (measured +0.73 % at narc =
    240, +0.65 % at 480), and closer to it with the finer polygon."""
    fine = peak(exe, meshes[480], "DMASTER", "SURFACE TO SURFACE")
    coarse = peak(exe, meshes[240], "DMASTER", "SURFACE TO SURFACE")
    assert abs(fine / P0 - 1) <= 0.02, fine
    assert abs(fine / P0 - 1) < abs(coarse / P0 - 1), (coarse, fine)


def test_voronoi_disc_master_nts(exe, meshes):
    """The disc as master with NODE TO SURFACE, finite sliding (the default) and HARD.
    The pairing follows the master along its reference normal (ray_projection,
    docs/contact-formulation.md), so that the gap is continuous from one segment of
    the polygon to the next: one increment, no cut-back, 12 iterations at narc = 240
    and 480 (with the closest point: a cut-back, then 13 / 12 / 19 / 37 iterations at
    480).  Read from the HDF5 iteration records: the step's records restart their
    count after a cut-back.  The target of issue 22, 10, is not reached: 4 iterations
    find the active set, 8 converge the multipliers with the pairing (SMALL SLIDING: 1).

    The peak is node to segment's, not the iteration's: the block's 8 slave nodes in
    the contact zone face 2-3 times as many nodes of the soft disc, whose surface
    bulges between them, and CPRESS oscillates from node to node (+23.2 % at narc =
    480, +28.7 % at 240, the same before the ray pairing; SMALL SLIDING +50 / +43 %).
    Asserted: the transmitted force (the vertical part of sum CPRESS * CNAREA is the
    load), the peak below +25 % and lower with the finer polygon."""
    peaks = {}
    for narc in (480, 240):
        d = meshes[narc]
        peak(exe, d, "DMASTER", "NODE TO SURFACE")
        h5 = d / "out" / "DMASTER_NODE.h5"
        with h5py.File(h5, "r") as f:
            its = np.array(f["steps/0001/contact/iterations/iteration"])
            cp = np.array(f["steps/0001/contact/pair_1/CPRESS"])
            area = np.array(f["steps/0001/contact/pair_1/CNAREA"])
            x = np.array(f["steps/0001/contact/pair_1/coordinates"])[:, 0]
        assert np.array_equal(its, np.arange(1, its.size + 1)), its    # one increment, no cut-back
        assert its.size <= 12, its.size
        # CPRESS acts along the disc's normal, tilted by about x/R: its vertical part
        # carries the load, within the polygon's normals against the circle's at the
        # node (half a side's turn, pi/narc/2, times the tilt, at most 0.15: 1e-3)
        fy = np.sum(cp * area * np.sqrt(1 - (x / 10.0) ** 2))
        assert abs(fy / 100.0 - 1) <= 1e-3, fy
        peaks[narc] = cp.max() / P0 - 1
    assert peaks[480] <= 0.25, peaks
    assert peaks[480] < peaks[240], peaks


def test_voronoi_disc_slave_nts_iterations(exe, meshes):
    """The disc as SLAVE with NODE TO SURFACE, finite sliding and HARD (issue 22's
    target, at most 10 contact iterations per increment): one increment, no cut-back,
    at most 10 iterations at narc = 240 and 480 (measured 8 and 9; 10 and 12 when the
    multipliers' step aimed at the gaps at u instead of those the next Newton step
    leaves, multiplier_step in src/contact/iteration.f90).  The converged answer: no
    overclosure beyond the tolerance (1e-10 of a tributary length), the load carried
    by the nodal forces (the flat block's normal is vertical: sum CPRESS * CNAREA =
    100 up to round-off, 1e-14 measured), the peak within 2 % of p0 at 480 (+1.02 %)
    and within 2.5 % at 240 (+2.02 %)."""
    for narc, band in ((480, 0.02), (240, 0.025)):
        d = meshes[narc]
        p = peak(exe, d, "DSLAVE", "NODE TO SURFACE")
        with h5py.File(d / "out" / "DSLAVE_NODE.h5", "r") as f:
            its = np.array(f["steps/0001/contact/iterations/iteration"])
            g = f["steps/0001/contact/pair_1"]
            cp, area, opening = (np.array(g[k]) for k in ("CPRESS", "CNAREA", "COPEN"))
        assert np.array_equal(its, np.arange(1, its.size + 1)), its    # one increment, no cut-back
        assert its.size <= 10, (narc, its.size)
        assert opening.min() >= -1e-10 * area.max(), (narc, opening.min())
        assert np.sum(cp * area) == pytest.approx(100.0, rel=1e-9)
        assert abs(p / P0 - 1) <= band, (narc, p)


def hertz_1155(exe, d, include, pair_type):
    """inputs/hertz_1155_vem.inp (the paper's Hertz, 1155 first-order VEM elements) with
    HARD and `pair_type` on the mesh `include`: (x, CPRESS, CNAREA, closed) of its slave
    nodes."""
    src = os.path.join(os.path.dirname(__file__), "..", "..", "inputs")
    text = open(os.path.join(src, "hertz_1155_vem.inp")).read()
    text = text.replace("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.0e5\n",
                        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n")
    assert "PRESSURE-OVERCLOSURE=HARD" in text
    text = text.replace("TYPE=NODE TO SURFACE", f"TYPE={pair_type}")
    text = text.replace("INPUT=meshes/ex2_hertz_1155_vem.inp", f"INPUT={include}")
    name = "h1155_" + pair_type.split()[0]
    (d / f"{name}.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(d / "out"), str(d / f"{name}.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(d / "out" / f"{name}.h5", "r") as f:
        g = f["steps/0001/contact/pair_1"]
        return (np.array(g["coordinates"])[:, 0], np.array(g["CPRESS"]), np.array(g["CNAREA"]),
                np.isin(np.array(g["STATUS"]), (1, 3, 4)))


def test_hertz_1155_sts(exe, tmp_path):
    """The paper's Hertz 1155 with SURFACE TO SURFACE: the disc's mesh is a polygon,
    whose vertices are corners of the interface, and the inserted nodes next to them
    resolve the corners' pressure peaks (the vertices read +2.3 % to +3.9 % above
    p0 sqrt(1 - x^2/a^2), the inserted nodes between them -0.7 % to -1.8 %, peak +2.3 %).
    CPRESS on the slave's own sides (src/contact/recovery.f90) removes that O(h) polygon
    error: within 2.5 % of the closed form at every closed node with x < a/2 (measured
    1.9 %, at x = 0.49 a; 3.9 % before), the peak within 1 % of 83.60 (measured +0.95 %; NODE TO SURFACE
    +0.79 %), and closer to the finite bodies' limit 83.95 with the divisions doubled
    (+0.77 %; +0.53 % at 4x).  The forces still add up: sum CPRESS x CNAREA = the load
    100 (the recovery moves force between nodes, never adds any)."""
    # the half-width of plane-strain Hertz for the full disc's load P = 200, R = 10
    e_star = 1.0 / ((1 - 0.3**2) / 1.0e3 + (1 - 0.3**2) / 1.0e6)
    a = np.sqrt(4 * 200.0 * 10.0 / (np.pi * e_star))
    mesh = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "meshes",
                                        "ex2_hertz_1155_vem.inp"))
    x, p, area, closed = hertz_1155(exe, tmp_path, mesh, "SURFACE TO SURFACE")
    assert abs(p.max() / P0 - 1) <= 0.01, p.max()
    # the pairs' normals are the block's tilted toward the disc's by c_block / c_disc =
    # 1e-3 of the disc's tilt (at most a/R = 0.15; common_normal), so the normal forces
    # add up to the vertical load within 1 - cos(1.5e-4) = 1.1e-8
    assert np.sum(p * area) == pytest.approx(100.0, rel=2e-8)
    inner = closed & (x < a / 2)
    assert inner.sum() >= 5
    assert np.max(np.abs(p[inner] / (P0 * np.sqrt(1 - (x[inner] / a) ** 2)) - 1)) <= 0.025
    scene = open(os.path.join(os.path.dirname(__file__), "..", "scenes", "ex2_hertz.toml")).read()
    scene = scene[:scene.index("[[variant]]")]
    scene = scene.replace("divisions = [12, 12, 6]", "divisions = [30, 30, 20]")
    scene = scene.replace("divisions = [16, 15]", "divisions = [48, 40]")
    (tmp_path / "fine.toml").write_text(scene)
    mesh_scene_file(tmp_path / "fine.toml", out=tmp_path / "fine.inp", echo=None)
    fine = hertz_1155(exe, tmp_path, "fine.inp", "SURFACE TO SURFACE")[1].max()
    assert abs(fine / 83.95 - 1) < abs(p.max() / 83.95 - 1), (p.max(), fine)


def hertz_vpe2(exe, d, include, pair_type):
    """inputs/hertz_329_vem2.inp (the paper's Hertz with VPE2 bodies, the disc's side
    nodes on the circle) with HARD and `pair_type`, on the mesh `include`."""
    src = os.path.join(os.path.dirname(__file__), "..", "..", "inputs")
    text = open(os.path.join(src, "hertz_329_vem2.inp")).read()
    text = text.replace("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.0e5\n",
                        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n")
    assert "PRESSURE-OVERCLOSURE=HARD" in text
    text = text.replace("TYPE=NODE TO SURFACE", f"TYPE={pair_type}")
    text = text.replace("INPUT=meshes/ex2_hertz_329_vem2.inp", f"INPUT={include}")
    name = "vpe2_" + pair_type.split()[0]
    (d / f"{name}.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(d / "out"), str(d / f"{name}.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(d / "out" / f"{name}.h5", "r") as f:
        return float(np.array(f["steps/0001/contact/pair_1/CPRESS"]).max())


def test_hertz_vpe2_sts(exe, tmp_path):
    """SURFACE TO SURFACE with second-order virtual elements on the paper's Hertz: the
    block's corners inserted into the disc's curved sides lie on the sides' quadratics,
    each piece with its own side node on the same curve.  The nodal forces of a
    second-order face alternate between its corners and side nodes (l/6, 4l/6, l/6
    weights; +1.22 % at a side node, -3 % to -10 % at the disc's corners); CPRESS on
    the slave's own nodes (corners and side nodes, src/contact/recovery.f90) gives
    +0.59 % on the 329-element mesh (1081 nodes; NODE TO SURFACE -0.29 %) and +0.44 %
    with the divisions doubled (the finite bodies' limit is about +0.41 %): asserted
    within 1 % on both, and approaching 83.95."""
    src = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "meshes")
    coarse = hertz_vpe2(exe, tmp_path, os.path.abspath(os.path.join(src, "ex2_hertz_329_vem2.inp")),
                        "SURFACE TO SURFACE")
    scene = open(os.path.join(os.path.dirname(__file__), "..", "scenes", "ex2_hertz.toml")).read()
    scene = scene[:scene.index("[[variant]]")].replace("[mesh]\n", "[mesh]\norder = 2\n")
    scene = scene.replace("divisions = [12, 12, 6]", "divisions = [16, 16, 8]")
    scene = scene.replace("divisions = [16, 15]", "divisions = [26, 26]")
    (tmp_path / "fine.toml").write_text(scene)
    mesh_scene_file(tmp_path / "fine.toml", out=tmp_path / "fine.inp", echo=None)
    fine = hertz_vpe2(exe, tmp_path, "fine.inp", "SURFACE TO SURFACE")
    assert abs(coarse / P0 - 1) <= 0.01, coarse
    assert abs(fine / P0 - 1) <= 0.01, fine
    assert abs(fine / 83.95 - 1) < abs(coarse / 83.95 - 1)
