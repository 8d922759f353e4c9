"""vc-plot draws each cell's polygon (no whole-mesh triangulation): deformed pictures of
contact and joint models (coincident nodes), CPE8 and VPE2 results; --units converts."""
import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ENV = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))
PNG = b"\x89PNG\r\n\x1a\n"


def run_plot(*args):
    return subprocess.run([sys.executable, "-m", "vctools.plot", *args], capture_output=True, text=True, env=ENV)


@pytest.fixture(scope="module")
def results(vemcontact, tmp_path_factory):
    out = tmp_path_factory.mktemp("plots")
    for deck in ("dam_joint", "hertz_329_fem2", "hertz_329_vem2"):
        subprocess.run([vemcontact, "-q", "-o", str(out / deck), os.path.join(ROOT, "inputs", deck + ".inp")], check=True)
    return out


@pytest.mark.parametrize("deck,args", [
    # the dam (coincident joint nodes, contact), Hertz and the CPE8 Hertz drawn deformed are the
    # README's vc-plot example, run by test_doc_commands.py; here the VPE2 polygons with units
    ("hertz_329_vem2", ["--field", "MISES", "--field", "U:y", "--deformed", "auto", "--line", "0,10,5,10",
                        "--units", "mm,MPa"]),
])
def test_deformed_pictures(results, tmp_path, deck, args):
    r = run_plot(str(results / deck / f"{deck}.pvd"), *args, "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    files = r.stdout.split()
    assert files and all(open(f, "rb").read(8) == PNG and os.path.getsize(f) > 10000 for f in files)


def test_quadratic_cells_are_polygons_through_their_side_nodes(results):
    """A CPE8 cell read from the .vtu becomes the 8-gon corner, side node, corner, ...:
    the same polygon as the HDF5 file's connectivity put in boundary order (vctools.open),
    counter-clockwise."""
    import vctools
    from vctools.plot.results import read_vtu
    res = read_vtu(str(results / "hertz_329_fem2" / "hertz_329_fem2_0001.vtu"))
    h5 = vctools.open(str(results / "hertz_329_fem2" / "hertz_329_fem2.h5"))
    ids = res.cell_data["ELEMENT_ID"]
    ours = dict(zip(h5.mesh.element_ids.tolist(), [tuple(p) for p in h5.mesh.polygons()]))
    assert len(res.polygons) == 329 and {len(p) for p in res.polygons} == {8}
    for i, p in zip(ids, res.polygons):
        assert tuple(p) == ours[int(i)]
        x, y = res.points[p, 0], res.points[p, 1]
        assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0    # counter-clockwise


def test_cell_fans_share_no_vertex():
    from vctools.plot.contour import cell_fans
    polys = [np.array([0, 1, 2, 3]), np.array([1, 4, 5, 6, 2]), np.array([7, 8, 9])]
    nodes, tris = cell_fans(polys)
    assert len(tris) == 2 + 3 + 1 and len(nodes) == 12
    np.testing.assert_array_equal(nodes, np.concatenate(polys))
    owner = np.repeat(np.arange(3), [4, 5, 3])
    assert (owner[tris] == owner[tris[:, :1]]).all()                   # each triangle within one cell
    # the fan of cell 1: (1,4,5), (1,5,6), (1,6,2) in mesh nodes
    np.testing.assert_array_equal(nodes[tris[2:5]], [[1, 4, 5], [1, 5, 6], [1, 6, 2]])


def test_displacement_at_coincident_nodes():
    """Two squares side by side with their own nodes on the shared edge (a joint) and
    different linear displacements: a point inside each takes its square's field exactly."""
    from vctools.plot.contour import displacement_at
    from vctools.plot.results import PolyResult
    pts = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [1, 0], [2, 0], [2, 1], [1, 1]], float)
    polys = [np.array([0, 1, 2, 3]), np.array([4, 5, 6, 7])]
    u = np.zeros((8, 3))
    u[:4, 0] = 0.1 * pts[:4, 0]                  # left: u_x = 0.1 x
    u[4:, 1] = -0.2 * pts[4:, 1]                 # right: u_y = -0.2 y
    res = PolyResult(points=pts, polygons=polys, point_data={"U": u}, cell_data={}, path="mem")
    got = displacement_at(res, [[0.3, 0.4], [1.6, 0.7]])
    np.testing.assert_allclose(got, [[0.03, 0.0], [0.0, -0.14]], atol=1e-15)


def test_units_convert(results):
    """--units mm,MPa on an SI model: coordinates and U times 1000, stresses times 1e-6,
    RF (stress times area) unchanged in N; the colour bar units follow the field."""
    from vctools.plot.contour import convert_result, field_unit, unit_factors
    from vctools.plot.results import read_vtu
    lf, sf, lu, su = unit_factors("mm,MPa", "m,Pa")
    assert (lf, sf, lu, su) == (1000.0, 1e-6, "mm", "MPa")
    assert unit_factors("mm,MPa", "mm,MPa")[:2] == (1.0, 1.0)
    assert unit_factors("m", "mm,MPa")[:2] == (1e-3, 1.0) and unit_factors("m", "mm,MPa")[3] == "MPa"
    assert unit_factors("in,psi")[1] == pytest.approx(1 / 6894.757293168361)
    with pytest.raises(ValueError, match="furlong"):
        unit_factors("furlong,Pa")
    res = read_vtu(str(results / "dam_joint" / "dam_joint_0002.vtu"))
    mm = convert_result(res, lf, sf)
    assert np.ptp(mm.points[:, 0]) == pytest.approx(25000.0)             # the 25 m dam model
    assert mm.point_data["S3"].min() == pytest.approx(res.point_data["S3"].min() * 1e-6)
    np.testing.assert_allclose(mm.point_data["U"], res.point_data["U"] * 1000.0)
    np.testing.assert_allclose(mm.point_data["RF"], res.point_data["RF"])
    assert mm.point_data["E"] is res.point_data["E"]
    assert [field_unit(f, "mm", "MPa") for f in ("U:x", "S3", "cell:S:yy", "E:xx", "RF:y")] == \
        ["mm", "MPa", "MPa", "", "N"]
