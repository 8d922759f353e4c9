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


def peak(exe, d, pair, pair_type, moduli=(1000.0, 1.0e6), roles="", tag="", law=""):
    """Run the pair with the disc's and the block's moduli; the peak CPRESS.  The
    results are in d/out/{pair}_{first word of pair_type}{tag}.h5."""
    name = f"{pair}_{pair_type.split()[0]}{tag}"
    (d / f"{name}.inp").write_text(f"""*INCLUDE, INPUT=hertz.inp
*MATERIAL, NAME=D
*ELASTIC
{float(moduli[0])}, 0.3
*MATERIAL, NAME=B
*ELASTIC
{float(moduli[1])}, 0.3
*SOLID SECTION, ELSET=DISC, MATERIAL=D
1.0
*SOLID SECTION, ELSET=BLOCK, MATERIAL=B
1.0
*SURFACE INTERACTION, NAME=I
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD
{law}*CONTACT PAIR, INTERACTION=I, TYPE={pair_type}{roles}
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


def pair_roles(h5):
    """(roles_swapped, slave surface, peak CPRESS) of the first step's pair 1."""
    with h5py.File(h5, "r") as f:
        g = f["steps/0001/contact/pair_1"]
        name = g.attrs["slave_surface"]
        return (int(g.attrs["roles_swapped"]), name.decode() if isinstance(name, bytes) else name,
                float(np.array(g["CPRESS"]).max()))


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
    Node to segment constrains the slave's nodes only; with the soft disc (1000x softer,
    its sides 3-4x shorter than the block's node spacing) as the master, its nodes bulge
    between the block's and CPRESS was +23 % (480 sides) / +29 % (240) of p0 whatever
    the iteration.  The roles are exchanged (vemcontact_contact_roles, ROLES=AUTO): the
    HDF5 pair says so (roles_swapped, slave_surface) and its results are on the disc's
    nodes.  Asserted: the peak within 2 % of p0 (measured +1.02 %) and closer to it at
    480 than at 240 (+2.0 %); the transmitted force (sum CPRESS * CNAREA, the normal
    forces the solution balances, is the load: 1e-8 covers the residual tolerance
    1e-10 times the ratio of the disc's stiffness to the block's that it is measured
    on); one increment, no cut-back, at most 10 iterations (issue 22's target; measured
    9 at 480, 8 at 240, with the multipliers' step on the residual's gaps)."""
    peaks = {}
    for narc in (480, 240):
        d = meshes[narc]
        peak(exe, d, "DMASTER", "NODE TO SURFACE")
        assert pair_roles(d / "out" / "DMASTER_NODE.h5")[:2] == (1, "DMASTER_MASTER")
        with h5py.File(d / "out" / "DMASTER_NODE.h5", "r") as f:
            its = np.array(f["steps/0001/contact/iterations/iteration"])
            g = f["steps/0001/contact/pair_1"]
            cp = np.array(g["CPRESS"])
            area = np.array(g["CNAREA"])
        assert np.array_equal(its, np.arange(1, its.size + 1)), its    # one increment, no cut-back
        assert its.size <= 10, its.size
        assert abs(np.sum(cp * area) / 100.0 - 1) <= 1e-8, np.sum(cp * area)
        peaks[narc] = cp.max() / P0 - 1
    assert abs(peaks[480]) <= 0.02, peaks
    assert abs(peaks[480]) < abs(peaks[240]), peaks


def test_roles_keep(exe, meshes):
    """ROLES=KEEP keeps the deck's roles (roles_swapped 0, the block's nodes as the
    slave): the soft, finely meshed disc as the master then gives node to segment's
    mesh-dependent peak, more than 10 % above p0 (measured +23 %), which is why AUTO
    exchanges them."""
    d = meshes[480]
    peak(exe, d, "DMASTER", "NODE TO SURFACE", roles=", ROLES=KEEP", tag="_keep")
    swapped, slave, p = pair_roles(d / "out" / "DMASTER_NODE_keep.h5")
    assert (swapped, slave) == (0, "DMASTER_SLAVE")
    assert p / P0 - 1 > 0.10


def test_roles_kept_with_friction(exe, meshes):
    """A frictional pair keeps the deck's roles (CSHEAR and CSLIP are signed along the
    master's tangent): roles_swapped 0 and the block's nodes as the slave, with a
    warning in the log (not read here)."""
    d = meshes[240]
    peak(exe, d, "DMASTER", "NODE TO SURFACE", tag="_fric", law="*FRICTION\n0.3\n")
    assert pair_roles(d / "out" / "DMASTER_NODE_fric.h5")[:2] == (0, "DMASTER_SLAVE")


def test_stiff_fine_slave_on_soft_master(exe, meshes):
    """Stiffness decides before the mesh: a stiff disc (1e6) as the slave of a soft
    block (1000) has the soft face as the master, and node to segment's pressure on it
    was +322 % of p0 (the disc's nodes pressed into the soft block's long sides).  The
    roles are exchanged (the block, the softer face, becomes the slave although it is
    the coarser): the peak within 1 % of p0 (measured +0.68 %; Hertz' p0 depends on
    the two moduli symmetrically, so it is the same 83.60)."""
    d = meshes[480]
    p = peak(exe, d, "DSLAVE", "NODE TO SURFACE", moduli=(1.0e6, 1000.0), tag="_stiff")
    assert pair_roles(d / "out" / "DSLAVE_NODE_stiff.h5")[0] == 1
    assert abs(p / P0 - 1) <= 0.01, p


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


def disc_as_master(d):
    """The paper's Hertz 1155 with the roles the other way round: the disc's lower arc
    (the sides of its elements with both ends in HERTZ_SLAVE, on the mesh boundary) as
    an element surface DISC_LOWER, the block's top nodes as the node surface BLOCK_TOP;
    the deck's pair then reads BLOCK_TOP, DISC_LOWER.  Returns the deck text."""
    src = os.path.join(os.path.dirname(__file__), "..", "..", "inputs")
    mesh = open(os.path.join(src, "meshes", "ex2_hertz_1155_vem.inp")).read().splitlines()
    elems, nset, block = {}, set(), None
    for line in mesh:
        if line.startswith("*"):
            block = line.upper().replace(" ", "")
            continue
        if block == "*ELEMENT,TYPE=VPE,ELSET=DISC":
            v = [int(t) for t in line.replace(",", " ").split()]
            elems[v[0]] = v[1:]
        elif block == "*NSET,NSET=HERTZ_SLAVE":
            nset |= {int(t) for t in line.replace(",", " ").split()}
    uses = {}
    for c in elems.values():
        for k in range(len(c)):
            key = frozenset((c[k], c[(k + 1) % len(c)]))
            uses[key] = uses.get(key, 0) + 1
    sides = [f"{e}, S{k + 1}" for e, c in elems.items() for k in range(len(c))
             if c[k] in nset and c[(k + 1) % len(c)] in nset and uses[frozenset((c[k], c[(k + 1) % len(c)]))] == 1]
    assert len(sides) == 24
    (d / "disc_lower.inp").write_text("*SURFACE, NAME=DISC_LOWER, TYPE=ELEMENT\n" + "\n".join(sides) +
                                      "\n*SURFACE, NAME=BLOCK_TOP, TYPE=NODE\nHERTZ_MASTER\n")
    text = open(os.path.join(src, "hertz_1155_vem.inp")).read()
    text = text.replace("INPUT=meshes/", f"INPUT={os.path.abspath(os.path.join(src, 'meshes'))}/")
    text = text.replace("*SURFACE INTERACTION", "*INCLUDE, INPUT=disc_lower.inp\n*SURFACE INTERACTION", 1)
    text = text.replace("PRESSURE-OVERCLOSURE=LINEAR\n1.0e5\n", "PRESSURE-OVERCLOSURE=HARD\n")
    text = text.replace("HERTZ_SLAVE, HERTZ_MASTER", "BLOCK_TOP, DISC_LOWER")
    assert "BLOCK_TOP, DISC_LOWER" in text and "HARD" in text
    return text


@pytest.mark.parametrize("pair_type", ["NODE TO SURFACE", "SURFACE TO SURFACE"])
def test_hertz_1155_disc_as_master(exe, tmp_path, pair_type):
    """The paper's Hertz 1155 written with the soft disc as the master, HARD.  NODE TO
    SURFACE: the roles are exchanged (roles_swapped; +15.4 % as written, ROLES=KEEP),
    and the peak is the paper deck's (+0.79 %).  SURFACE TO SURFACE keeps the roles:
    CPRESS is recovered on the disc's own sides, the polygon whose corners carry the
    peaks, and the pair normal where both faces end on the symmetry line is their common
    normal (the disc's end chord alone tilts by 0.013 and made a support-shared node of
    it: +2.4 %; now +1.02 %).  Asserted: within 2 % of 83.60 (issue 22's target for a
    curved master), and the peak at the axis."""
    text = disc_as_master(tmp_path).replace("TYPE=NODE TO SURFACE", f"TYPE={pair_type}")
    name = "m1155_" + pair_type.split()[0]
    (tmp_path / f"{name}.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path / "out"), str(tmp_path / f"{name}.inp")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert pair_roles(tmp_path / "out" / f"{name}.h5")[0] == (1 if pair_type == "NODE TO SURFACE" else 0)
    with h5py.File(tmp_path / "out" / f"{name}.h5", "r") as f:
        g = f["steps/0001/contact/pair_1"]
        p = np.array(g["CPRESS"])
        x = np.array(g["coordinates"])[:, 0]
    assert abs(p.max() / P0 - 1) <= 0.02, p.max()
    assert x[np.argmax(p)] < 0.2, x[np.argmax(p)]


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
