"""Second-order elements through decks: VPE2 (k = 2 VEM), CPE8 and CPE6 read in
Abaqus' node order (corners, then side nodes), loaded by *CLOAD, *DLOAD P<k>
and GRAV, and written as VTU cells that meshio reads with their side nodes
(VTK_QUADRATIC_QUAD, VTK_QUADRATIC_TRIANGLE, and a VTK_POLYGON through all 2n
nodes of a second-order polygon)."""
import subprocess

import h5py
import meshio
import numpy as np
import pytest

# Example 1 (L = 40, b = 8, E = 1000, nu = 0, end moment 16 as the couple +-2 on
# the tip corners) on two second-order elements, shared side skewed by 2d/b = 3
NODES = """1, 0, 0
2, 8, 0
3, 40, 0
4, 40, 8
5, 32, 8
6, 0, 8
7, 4, 0
8, 20, 4
9, 16, 8
10, 0, 4
11, 24, 0
12, 40, 4
13, 36, 8
"""


def deck(etype, body=""):
    return f"""*NODE, NSET=ALL
{NODES}*ELEMENT, TYPE={etype}, ELSET=BEAM
1, 1, 2, 5, 6, 7, 8, 9, 10
2, 2, 3, 4, 5, 11, 12, 13, 8
*MATERIAL, NAME=M
*ELASTIC
1000.0, 0.0
*DENSITY
1.0
*SOLID SECTION, ELSET=BEAM, MATERIAL=M
1.0
*BOUNDARY
1, 1
10, 1
6, 1
1, 2
*STEP
*STATIC
*CLOAD
3, 1, 2.0
4, 1, -2.0
{body}*END STEP
"""


def run(exe, tmp_path, text, name="job"):
    p = tmp_path / f"{name}.inp"
    p.write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(p)], capture_output=True, text=True)
    return r


def test_vpe2_example1_exact_and_vtu(exe, tmp_path):
    r = run(exe, tmp_path, deck("VPE2"))
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "job.h5") as f:
        u = np.array(f["steps/0001/U"])
        ids = list(np.array(f["mesh/node_ids"]))
        types = np.array(f["mesh/element_type"])
    tip = 0.5 * (u[ids.index(3), 1] + u[ids.index(4), 1])
    # pure bending is quadratic: the k = 2 VEM is exact (round-off only)
    assert tip == pytest.approx(0.3, rel=1e-8)
    assert (types == 4).all()
    m = meshio.read(tmp_path / "job_0001.vtu")
    assert [c.type for c in m.cells] == ["polygon"]
    conn = m.cells[0].data
    # boundary order: corner, side node, corner, ... (0-based; node i is id i+1 here)
    assert conn[0].tolist() == [0, 6, 1, 7, 4, 8, 5, 9]
    assert conn[1].tolist() == [1, 10, 2, 11, 3, 12, 4, 7]


def tip_of(tmp_path, job):
    with h5py.File(tmp_path / f"{job}.h5") as f:
        u = np.array(f["steps/0001/U"])
        ids = list(np.array(f["mesh/node_ids"]))
    return 0.5 * (u[ids.index(3), 1] + u[ids.index(4), 1])


def test_formulation_switch(exe, tmp_path):
    """FORMULATION=VEM on CPE8 runs the k = 2 VEM (exact here), FORMULATION=FEM on an
    8-node VPE2 the 8-node quad (the CPE8 answer, below exact on the skewed mesh)."""
    sec = "*SOLID SECTION, ELSET=BEAM, MATERIAL=M"
    assert run(exe, tmp_path, deck("CPE8").replace(sec, sec + ", FORMULATION=VEM"), "q8v").returncode == 0
    assert tip_of(tmp_path, "q8v") == pytest.approx(0.3, rel=1e-8)
    assert run(exe, tmp_path, deck("VPE2").replace(sec, sec + ", FORMULATION=FEM"), "v2f").returncode == 0
    assert run(exe, tmp_path, deck("CPE8"), "q8").returncode == 0
    assert tip_of(tmp_path, "v2f") == pytest.approx(tip_of(tmp_path, "q8"), rel=1e-12)
    assert tip_of(tmp_path, "q8") < 0.99 * 0.3


def test_cpe8_cpe6_cells(exe, tmp_path):
    r = run(exe, tmp_path, deck("CPE8"), "q8")
    assert r.returncode == 0, r.stderr
    m = meshio.read(tmp_path / "q8_0001.vtu")
    assert [c.type for c in m.cells] == ["quad8"]
    assert m.cells[0].data[0].tolist() == [0, 1, 4, 5, 6, 7, 8, 9]
    # two CPE6 triangles on the rectangle [0,2] x [0,1]
    text = """*NODE
1, 0, 0
2, 2, 0
3, 2, 1
4, 0, 1
5, 1, 0
6, 2, 0.5
7, 1, 0.5
8, 1, 1
9, 0, 0.5
*ELEMENT, TYPE=CPS6, ELSET=E
1, 1, 2, 3, 5, 6, 7
2, 1, 3, 4, 7, 8, 9
*MATERIAL, NAME=M
*ELASTIC
100.0, 0.25
*SOLID SECTION, ELSET=E, MATERIAL=M
1.0
*BOUNDARY
1, 1, 2
5, 2
2, 2
9, 1
4, 1
*STEP
*STATIC
*DLOAD
2, P2, 3.0
*END STEP
"""
    r = run(exe, tmp_path, text, "t6")
    assert r.returncode == 0, r.stderr
    m = meshio.read(tmp_path / "t6_0001.vtu")
    assert [c.type for c in m.cells] == ["triangle6"]
    with h5py.File(tmp_path / "t6.h5") as f:
        u = np.array(f["steps/0001/U"])
        s = np.array(f["steps/0001/S_element"])
    # uniform pressure 3 on the top side (side 2 of element 2: nodes 3-4): syy = -3
    # everywhere, plane stress: uy = -3 y / E, ux = 0.25 * 3 x / E
    assert s[:, 1] == pytest.approx([-3.0, -3.0], rel=1e-10)
    assert u[2] == pytest.approx([0.25 * 3 * 2 / 100, -3 / 100], rel=1e-10)


def test_vpe2_gravity_column(exe, tmp_path):
    """GRAV on the k = 2 element (its load sits on the condensed cell moments,
    and the stress recovery uses it): a free-standing block [0,2] x [0,1], nu = 0,
    rho g = 0.01 downwards, bottom on rollers: syy = rho g (y - 1) and
    uy = rho g (y^2/2 - y)/E are quadratic, so exact."""
    text = """*NODE
1, 0, 0
2, 1, 0
3, 2, 0
4, 2, 1
5, 1, 1
6, 0, 1
7, 0.5, 0
8, 1, 0.5
9, 0.5, 1
10, 0, 0.5
11, 1.5, 0
12, 2, 0.5
13, 1.5, 1
*ELEMENT, TYPE=VPS2, ELSET=E
1, 1, 2, 5, 6, 7, 8, 9, 10
2, 2, 3, 4, 5, 11, 12, 13, 8
*MATERIAL, NAME=M
*ELASTIC
1000.0, 0.0
*DENSITY
1.0
*SOLID SECTION, ELSET=E, MATERIAL=M
1.0
*BOUNDARY
1, 1, 2
7, 2
2, 2
11, 2
3, 2
*STEP
*STATIC
*DLOAD
E, GRAV, 0.01, 0.0, -1.0
*END STEP
"""
    r = run(exe, tmp_path, text, "g")
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "g.h5") as f:
        u = np.array(f["steps/0001/U"])
        s = np.array(f["steps/0001/S_element"])
        x = np.array(f["mesh/coordinates"])
    uy = 0.01 * (x[:, 1] ** 2 / 2 - x[:, 1]) / 1000.0
    assert np.abs(u[:, 1] - uy).max() <= 1e-10 * np.abs(uy).max()
    assert np.abs(u[:, 0]).max() <= 1e-10 * np.abs(uy).max()
    # element mean stress: syy at the centroid height 0.5
    assert s[:, 1] == pytest.approx([-0.005, -0.005], rel=1e-10)
    # nodal stress: the elements' own (linear) stresses at the nodes, averaged:
    # exact at every node, side nodes included
    with h5py.File(tmp_path / "g.h5") as f:
        sn = np.array(f["steps/0001/S_node"])
    assert np.abs(sn[:, 1] - 0.01 * (x[:, 1] - 1)).max() <= 1e-10 * 0.01
    assert np.abs(sn[:, [0, 3]]).max() <= 1e-10 * 0.01
    # strains E from the same recovery (nu = 0, plane stress: eyy = syy / E, exx =
    # gamma = 0, ezz = 0): exact at the element (centroid height 0.5) and at every node
    with h5py.File(tmp_path / "g.h5") as f:
        ee = np.array(f["steps/0001/E_element"])
        en = np.array(f["steps/0001/E_node"])
        rf = np.array(f["steps/0001/RF"])
        rf_total = np.array(f["steps/0001/RF_total"])
    assert ee[:, 1] == pytest.approx([-0.005 / 1000, -0.005 / 1000], rel=1e-10)
    assert np.abs(en[:, 1] - 0.01 * (x[:, 1] - 1) / 1000).max() <= 1e-10 * 1e-5
    assert np.abs(en[:, [0, 2, 3]]).max() <= 1e-10 * 1e-5
    # reactions: the bottom (corners and side nodes) carries the weight rho g |block| t = 0.02,
    # with the consistent side-node share of the k = 2 element (not zero at the side nodes)
    assert rf_total == pytest.approx([0.0, 0.02], abs=1e-12)
    assert rf[:, 1].sum() == pytest.approx(0.02, rel=1e-12)
    assert np.abs(rf[x[:, 1] > 0]).max() == 0.0
    m = meshio.read(tmp_path / "g_0001.vtu")
    assert [c.type for c in m.cells] == ["polygon"] and m.cells[0].data.shape == (2, 8)
    assert np.array_equal(m.point_data["RF"][:, :2], rf)
    assert np.allclose(m.point_data["E"][:, 4], en[:, 1], rtol=0, atol=1e-20)


@pytest.mark.parametrize("text,msg", [
    (deck("VPE2").replace("2, 2, 3, 4, 5, 11, 12, 13, 8", "2, 2, 3, 4, 5, 11, 12, 13"),
     "needs an even number of nodes"),
    (deck("VPE2").replace("11, 24, 0", "11, 30, 0"), "too far along side 2-3 from its middle"),
    (deck("VPE2").replace("11, 24, 0", "11, 24, -20"), "too far off side 2-3"),
    (deck("VPE2").replace("*CLOAD", "*DLOAD\n1, P5, 1.0\n*CLOAD"), "has 4 sides, so there is no side P5"),
    (deck("CPE8").replace("*BOUNDARY", "*SURFACE, NAME=A\n1, S1\n*SURFACE, NAME=B\n2, S1\n"
                          "*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                          "1.0e3\n*CONTACT PAIR, INTERACTION=I, TYPE=SURFACE TO SURFACE\nA, B\n*BOUNDARY"),
     "FEM elements have sides on the surfaces of this TYPE=SURFACE TO SURFACE pair"),
])
def test_second_order_errors(exe, tmp_path, text, msg):
    r = run(exe, tmp_path, text, "bad")
    assert r.returncode != 0
    assert "job" not in r.stderr and "bad.inp:" in r.stderr, r.stderr
    assert msg in r.stderr, r.stderr
