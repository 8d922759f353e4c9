"""JOB.xdmf (docs/output-format.md, "XDMF"): every data item resolves in JOB.h5 with the
declared shape (h5py); the cells and fields that a reader makes of it are the solver's
own .vtu ones (an independent writer): meshio for meshes of one cell kind, VTK's XDMF
reader (ParaView's, when the vtk package is installed) and pvpython (when on the PATH)
for every mesh, VEM polygons, quadratic cells and contact models alike.  --no-vtu
leaves the .vtu/.pvd out and keeps JOB.xdmf."""
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# (deck, XDMF topology, VTK cell types the reader makes)
CASES = [("dam_joint", "Mixed", {5, 7, 9}),            # VEM polygons of 3 to 7 sides, contact along the joint
         ("hertz_329_fem2", "Quadrilateral_8", {23}),  # CPE8, contact
         ("hertz_329_vem2", "Polygon", {7}),           # VPE2: polygons through their 8 nodes
         ("interface_quad", "Quadrilateral", {9})]      # quads on both sides of a contact interface


@pytest.fixture(scope="module")
def runs(tmp_path_factory, vemcontact):
    out = tmp_path_factory.mktemp("xdmf")
    for deck, _, _ in CASES:
        subprocess.run([vemcontact, "-q", "-o", str(out / deck), os.path.join(ROOT, "inputs", deck + ".inp")],
                       check=True)
    return out


def items(path):
    """(element, dims, h5 file, dataset) of every DataItem of an XDMF file."""
    root = ET.parse(path).getroot()
    for parent in root.iter():
        for it in parent.findall("DataItem"):
            f, ds = it.text.strip().split(":")
            yield parent, [int(d) for d in it.get("Dimensions").split()], f, ds


def vtu_cells(path):
    m = meshio.read(path)
    ids = np.concatenate(m.cell_data["ELEMENT_ID"])
    cells = [tuple(c) for b in m.cells for c in b.data]
    return dict(zip(ids.tolist(), cells)), m


@pytest.mark.parametrize("deck,topology,vtk_types", CASES)
def test_items_resolve_in_h5(runs, deck, topology, vtk_types):
    """Every reference names a dataset of JOB.h5 (a sibling file, by relative name) with
    the shape declared; one grid per step, named and timed as the step groups."""
    xdmf = runs / deck / f"{deck}.xdmf"
    root = ET.parse(xdmf).getroot()
    assert root.get("Version") == "3.0"
    grids = root.find("Domain/Grid").findall("Grid")
    with h5py.File(runs / deck / f"{deck}.h5") as f:
        steps = sorted(f["steps"])
        assert [g.get("Name") for g in grids] == [f["steps"][k].attrs["name"].decode() for k in steps]
        assert [float(g.find("Time").get("Value")) for g in grids] == [f["steps"][k].attrs["time"] for k in steps]
        for g in grids:
            assert g.find("Topology").get("TopologyType") == topology
        for _, dims, h5name, ds in items(xdmf):
            assert h5name == f"{deck}.h5"
            assert list(f[ds].shape) == dims, ds
        # every step field of the HDF5 file is in the XDMF file (RF_total and RF_sets are not mesh fields)
        refs = {ds for _, _, _, ds in items(xdmf)}
        for k in steps:
            have = {f"/steps/{k}/{n}" for n in f["steps"][k] if n in ("U", "RF", "S_node", "S_element",
                                                                      "E_node", "E_element", "ERROR_INDICATOR")}
            assert have and have <= refs


@pytest.mark.parametrize("deck", ["hertz_329_fem2", "interface_quad"])
def test_meshio_reads_one_kind_meshes(runs, deck):
    """meshio's XDMF time-series reader gives the .vtu's cells and every step's U and S
    (meshio 5.3.5 reads no XDMF polygons, neither a Polygon topology nor polygons in a
    Mixed one: polygon meshes go through vctools.open(...).to_meshio())."""
    xdmf = runs / deck / f"{deck}.xdmf"
    cells_vtu, _ = vtu_cells(runs / deck / f"{deck}_0001.vtu")
    with meshio.xdmf.TimeSeriesReader(str(xdmf)) as r:
        points, cells = r.read_points_cells()
        assert len(cells) == 1
        ids = None
        for k in range(r.num_steps):
            t, pd, cd = r.read_data(k)
            ids = cd["ELEMENT_ID"][0]
            vtu = meshio.read(runs / deck / f"{deck}_{k + 1:04d}.vtu")
            np.testing.assert_array_equal(pd["U"], vtu.point_data["U"][:, :2])
            # the .vtu's tensor (xx, xy, xz, yx, yy, yz, zx, zy, zz) against (xx, yy, zz, xy)
            np.testing.assert_array_equal(pd["S_node"], vtu.point_data["S"][:, [0, 4, 8, 1]])
    np.testing.assert_array_equal(points[:, :2], vtu.points[:, :2])
    ours = dict(zip(ids.tolist(), [tuple(c) for c in cells[0].data]))
    assert ours == cells_vtu


@pytest.mark.parametrize("deck", ["dam_joint", "hertz_329_vem2"])
def test_meshio_polygons_go_through_to_meshio(runs, deck):
    """No XDMF layout carries polygons to meshio 5.3.5 (docs/output-format.md, "XDMF and
    meshio"): its XDMF reader and writer map no XDMF cell kind to its "polygon" (neither
    the Polygon topology nor kind 3 inside Mixed), so JOB.xdmf of a VEM mesh fails in
    meshio whatever the layout (a KeyError on the kind), and `meshio convert` cannot write
    polygons to XDMF.  The documented route: vctools.open(JOB.h5).to_meshio(step), whose
    cells and U are those of the datasets JOB.xdmf references, and which meshio writes
    to a .vtu that it reads back unchanged."""
    import vctools
    from meshio.xdmf import common

    assert "Polygon" not in common.xdmf_to_meshio_type and "polygon" not in common.meshio_to_xdmf_type
    xdmf = runs / deck / f"{deck}.xdmf"
    with pytest.raises(KeyError), meshio.xdmf.TimeSeriesReader(str(xdmf)) as r:
        r.read_points_cells()
    res = vctools.open(str(runs / deck / f"{deck}.h5"))
    m = res.to_meshio(-1)
    cells_vtu, _ = vtu_cells(runs / deck / f"{deck}_{len(res.steps):04d}.vtu")
    ours = {int(i): tuple(c) for b, bid in zip(m.cells, m.cell_data["ELEMENT_ID"]) for i, c in zip(bid, b.data)}
    assert ours == cells_vtu
    assert any(b.type == "polygon" for b in m.cells)
    with h5py.File(runs / deck / f"{deck}.h5") as f:
        np.testing.assert_array_equal(m.points[:, :2], f["mesh/coordinates"][...])
        np.testing.assert_array_equal(m.point_data["U"], f["steps"][sorted(f["steps"])[-1]]["U"][...])
    out = runs / deck / "exported.vtu"
    m.write(out)
    back = meshio.read(out)
    np.testing.assert_array_equal(back.point_data["U"], m.point_data["U"])
    assert [(b.type, b.data.tolist()) for b in back.cells] == [(b.type, b.data.tolist()) for b in m.cells]


def _vtk_reader():
    vtk = pytest.importorskip("vtk")
    if not hasattr(vtk, "vtkXdmfReader"):
        pytest.skip("vtk without its XDMF reader")
    return vtk


@pytest.mark.parametrize("deck,topology,vtk_types", CASES)
def test_vtk_reads_every_mesh(runs, deck, topology, vtk_types):
    """VTK's XDMF reader (ParaView's): cell types, each cell's nodes and U as in the .vtu."""
    vtk = _vtk_reader()
    from vtk.util.numpy_support import vtk_to_numpy

    r = vtk.vtkXdmfReader()
    r.SetFileName(str(runs / deck / f"{deck}.xdmf"))
    r.Update()
    g = r.GetOutputDataObject(0)
    cells_vtu, vtu = vtu_cells(runs / deck / f"{deck}_0001.vtu")
    assert g.GetNumberOfCells() == len(cells_vtu) and g.GetNumberOfPoints() == len(vtu.points)
    assert {g.GetCellType(i) for i in range(g.GetNumberOfCells())} == vtk_types
    ids = vtk_to_numpy(g.GetCellData().GetArray("ELEMENT_ID"))
    for i in range(g.GetNumberOfCells()):
        pid = g.GetCell(i).GetPointIds()
        assert tuple(pid.GetId(j) for j in range(pid.GetNumberOfIds())) == cells_vtu[int(ids[i])]
    u = vtk_to_numpy(g.GetPointData().GetArray("U"))
    np.testing.assert_array_equal(u[:, :2], vtu.point_data["U"][:, :2])
    assert vtk_to_numpy(g.GetPointData().GetArray("S_node")).shape == (len(vtu.points), 4)


@pytest.mark.skipif(shutil.which("pvpython") is None, reason="ParaView's pvpython is not installed")
def test_pvpython_opens_the_dam(runs):
    script = ("from paraview.simple import *\n"
              f"r = OpenDataFile({str(runs / 'dam_joint' / 'dam_joint.xdmf')!r})\n"
              "r.UpdatePipeline(2.0)\n"
              "print(r.GetDataInformation().GetNumberOfCells())\n")
    p = subprocess.run(["pvpython", "-c", script], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0 and p.stdout.split()[-1] == "1589", p.stderr


def test_no_vtu(tmp_path, vemcontact):
    """--no-vtu: no .vtu or .pvd, the HDF5, CSV and XDMF files as usual; a rerun with
    VTU files removes the previous run's XDMF file before writing its own."""
    deck = os.path.join(ROOT, "inputs", "interface_quad.inp")
    subprocess.run([vemcontact, "-q", "--no-vtu", "-o", str(tmp_path), deck], check=True)
    names = sorted(os.listdir(tmp_path))
    assert not [n for n in names if n.endswith((".vtu", ".pvd"))]
    assert {"interface_quad.h5", "interface_quad.xdmf", "interface_quad_contact_pair1_0001.csv"} <= set(names)
    m = meshio.xdmf.TimeSeriesReader(str(tmp_path / "interface_quad.xdmf"))
    m.read_points_cells()
    assert m.read_data(0)[1]["U"].shape[1] == 2
    (tmp_path / "interface_quad.xdmf").write_text("stale")
    subprocess.run([vemcontact, "-q", "-o", str(tmp_path), deck], check=True)
    assert (tmp_path / "interface_quad.xdmf").read_text().startswith("<?xml")


def test_failed_run_lists_the_completed_steps(tmp_path, vemcontact):
    """A run that stops in step 2 (its supports leave x free: the model floats, exit 3)
    keeps JOB.h5 (complete = 0) with step 1, and JOB.xdmf lists step 1 only."""
    deck = """*NODE
1, 0, 0
2, 1, 0
3, 1, 1
4, 0, 1
*ELEMENT, TYPE=VPE, ELSET=ALL
1, 1, 2, 3, 4
*MATERIAL, NAME=M
*ELASTIC
100.0, 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
*STEP
*STATIC
*BOUNDARY
1, 1, 2
2, 2
*CLOAD
3, 2, -1.0
*END STEP
*STEP
*STATIC
*BOUNDARY, OP=NEW
1, 2
2, 2
*END STEP
"""
    (tmp_path / "two.inp").write_text(deck)
    p = subprocess.run([vemcontact, "-q", "-o", str(tmp_path), str(tmp_path / "two.inp")], capture_output=True, text=True)
    assert p.returncode == 3, p.stderr
    with h5py.File(tmp_path / "two.h5") as f:
        assert f.attrs["complete"] == 0 and sorted(f["steps"]) == ["0001"]
    grids = ET.parse(tmp_path / "two.xdmf").getroot().find("Domain/Grid").findall("Grid")
    assert [g.get("Name") for g in grids] == ["Step-1"]


if __name__ == "__main__":
    sys.exit(pytest.main([__file__]))
