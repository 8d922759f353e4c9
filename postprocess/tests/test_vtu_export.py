"""The .vtu files as other programs read them: meshio reads the zlib-compressed
(default) and the raw (--raw-vtu) files of a run with FEM and VEM triangles and
quadrilaterals, finds cell types triangle and quad and the values of the HDF5
file bit for bit, and exports them to XDMF and Gmsh (formats without polygons)."""
import subprocess
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np
import pytest

# 120 x 100 unit cells: 12221 nodes, so U (3 doubles a node, 293 kB) spans two
# of the writer's 256 KiB zlib blocks and the block table is exercised.
NX, NY = 120, 100


def grid_deck(path, nx=NX, ny=NY, quads_only=False):
    """A nx x ny block of unit cells, bottom fixed, self-weight: the columns in four
    bands of CPE4 quads, CPE3 triangles, VPE (VEM) quads and VPE triangles (or all
    CPE4 quads)."""
    def node(i, j):
        return j * (nx + 1) + i + 1
    lines = ["*NODE, NSET=NALL"]
    lines += [f"{node(i, j)}, {float(i)}, {float(j)}" for j in range(ny + 1) for i in range(nx + 1)]
    bands = {"FEMQ": [], "FEMT": [], "VEMQ": [], "VEMT": []}
    eid = 0
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            band = "FEMQ" if quads_only else ["FEMQ", "FEMT", "VEMQ", "VEMT"][min(3, 4 * i // nx)]
            if band.endswith("Q"):
                eid += 1
                bands[band].append(f"{eid}, {a}, {b}, {c}, {d}")
            else:
                eid += 1
                bands[band].append(f"{eid}, {a}, {b}, {c}")
                eid += 1
                bands[band].append(f"{eid}, {a}, {c}, {d}")
    # quads first, then triangles: one cell block per type (meshio 5.3.5 reads back
    # Gmsh element data wrongly when a type comes in two separate blocks)
    for name, etype in (("FEMQ", "CPE4"), ("VEMQ", "VPE"), ("FEMT", "CPE3"), ("VEMT", "VPE")):
        lines += [f"*ELEMENT, TYPE={etype}, ELSET={name}"] + bands[name]
    lines += ["*ELSET, ELSET=ALL", "FEMQ, FEMT, VEMQ, VEMT",
              "*NSET, NSET=BASE, GENERATE", f"1, {nx + 1}, 1",
              "*MATERIAL, NAME=ROCK", "*ELASTIC", "1.0e10, 0.25", "*DENSITY", "2400.",
              "*SOLID SECTION, ELSET=ALL, MATERIAL=ROCK", "1.0",
              "*BOUNDARY", "BASE, 1, 2",
              "*STEP, NAME=SELF", "*STATIC", "*DLOAD", "ALL, GRAV, 9.81, 0., -1.", "*END STEP"]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture(scope="module")
def grid_runs(tmp_path_factory, exe):
    """The grid deck run twice, compressed (default) and --raw-vtu, and a small
    grid of quads only."""
    root = tmp_path_factory.mktemp("grid")
    grid_deck(root / "grid.inp")
    grid_deck(root / "quads.inp", 20, 10, quads_only=True)
    for sub, extra, deck in (("z", [], "grid"), ("raw", ["--raw-vtu"], "grid"), ("z", [], "quads")):
        r = subprocess.run([exe, "-q", "-o", str(root / sub), *extra, str(root / f"{deck}.inp")],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    return root


def tensor9(s):
    """(n, 4) rows xx, yy, zz, xy of the HDF5 file as the .vtu's (n, 9) full tensors."""
    z = np.zeros(len(s))
    return np.column_stack([s[:, 0], s[:, 3], z, s[:, 3], s[:, 1], z, z, z, s[:, 2]])


def concat(arrays):
    return np.concatenate([np.asarray(a) for a in arrays])


@pytest.mark.parametrize("sub, compressed", [("z", True), ("raw", False)])
def test_meshio_reads_cell_types_and_hdf5_values(grid_runs, sub, compressed):
    vtu = grid_runs / sub / "grid_0001.vtu"
    root = ET.parse(vtu).getroot()
    assert (root.get("compressor") == "vtkZLibDataCompressor") == compressed
    m = meshio.read(vtu)
    with h5py.File(grid_runs / sub / "grid.h5") as f:
        x = f["mesh/coordinates"][...]
        off = f["mesh/element_offsets"][...]
        conn = f["mesh/element_connectivity"][...]
        form = f["mesh/element_formulation"][...]
        step = f["steps/0001"]
        u, s_node, s_elem = step["U"][...], step["S_node"][...], step["S_element"][...]
    # cells: triangles and quads by node count, VEM (formulation 1) and FEM (2) alike
    nv = np.diff(off)
    types = np.concatenate([[b.type] * len(b.data) for b in m.cells])
    assert set(types) == {"triangle", "quad"}
    assert (types == np.where(nv == 3, "triangle", "quad")).all()
    assert {(t, fm) for t, fm in zip(types, form)} == {("quad", 2), ("triangle", 2), ("quad", 1), ("triangle", 1)}
    assert np.array_equal(np.concatenate([b.data.ravel() for b in m.cells]), conn)
    # values: the same doubles as in the HDF5 file
    assert np.array_equal(m.points[:, :2], x) and not m.points[:, 2].any()
    assert np.array_equal(m.point_data["U"][:, :2], u)
    assert np.array_equal(m.point_data["S"], tensor9(s_node))
    assert np.array_equal(concat(m.cell_data["S"]), tensor9(s_elem))
    assert np.abs(u).max() > 0


def test_compressed_is_smaller(grid_runs):
    z = (grid_runs / "z" / "grid_0001.vtu").stat().st_size
    raw = (grid_runs / "raw" / "grid_0001.vtu").stat().st_size
    assert z < 0.8 * raw, (z, raw)      # integer arrays and zeros compress well


@pytest.mark.parametrize("job, fmt, suffix", [("grid", "xdmf", ".xdmf"), ("quads", "xdmf", ".xdmf"),
                                              ("quads", "gmsh", ".msh"), ("quads", "gmsh22", ".msh")])
def test_meshio_exports(grid_runs, tmp_path, job, fmt, suffix):
    """meshio writes XDMF and Gmsh (4.1 and 2.2) from the .vtu, every field
    included, and reads them back with the same values."""
    m = meshio.read(grid_runs / "z" / f"{job}_0001.vtu")
    out = tmp_path / f"{job}{suffix}"
    meshio.write(out, m, file_format=fmt)
    back = meshio.read(out)
    assert [b.type for b in back.cells] == [b.type for b in m.cells]
    assert np.array_equal(back.points[:, :2], m.points[:, :2])
    for name in ("U", "S", "MISES"):
        assert np.array_equal(back.point_data[name], m.point_data[name])
    assert np.array_equal(concat(back.cell_data["S"]), concat(m.cell_data["S"]))


def test_meshio_gmsh22_mixed_cells(grid_runs, tmp_path):
    """Triangles and quads together: meshio writes Gmsh 2.2 with every field.  (Its
    Gmsh 4.1 writer wants gmsh:dim_tags for more than one cell type, and its
    reader mis-splits element data over several blocks, so the check reads back
    a copy with the point data only.)"""
    m = meshio.read(grid_runs / "z" / "grid_0001.vtu")
    meshio.write(tmp_path / "all.msh", m, file_format="gmsh22")
    assert (tmp_path / "all.msh").stat().st_size > 0
    points_only = meshio.Mesh(m.points, m.cells, point_data=m.point_data)
    meshio.write(tmp_path / "grid.msh", points_only, file_format="gmsh22")
    back = meshio.read(tmp_path / "grid.msh")
    assert [b.type for b in back.cells] == ["quad", "triangle"]
    assert np.array_equal(back.point_data["U"], m.point_data["U"])
    assert np.array_equal(back.point_data["S"], m.point_data["S"])
