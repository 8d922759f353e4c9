"""The Python API (docs/python-api.md): vctools.run on the paper's four examples and a
parameter sweep, every field of docs/output-format.md read through vctools.open,
the conversions checked against the solver's own .vtu."""
import os
import runpy
import subprocess
import sys

import numpy as np
import pytest

import vctools
from vctools.api import RunError, boundary_order

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
INPUTS = os.path.join(ROOT, "inputs")

# docs/output-format.md, "HDF5": the datasets of a step group without output requests
STEP_FIELDS = {"U", "S_element", "S_node", "E_element", "E_node", "RF", "RF_total", "LOAD_total", "ERROR_INDICATOR"}
CONTACT_COLUMNS = {"node_ids", "coordinates", "COPEN", "CPRESS", "CSHEAR", "CSLIP", "CNAREA", "STATUS"}
ITERATION_COLUMNS = {"iteration", "active", "changed", "residual", "max_penetration", "max_pressure", "step",
                     "time", "factorized", "rebuilt", "slip_changes"}


@pytest.fixture(scope="module")
def paper(tmp_path_factory, vemcontact):
    """The paper's four examples, run through the API."""
    out = tmp_path_factory.mktemp("api")
    decks = ["example1_cantilever", "hertz_389_vem", "interface_voronoi_200", "dam_joint"]
    return {d: vctools.run(os.path.join(INPUTS, d + ".inp"), out=str(out / d), exe=vemcontact) for d in decks}


def test_example1_cantilever(paper):
    """The deck's 2d/b = 1 mesh: tip deflection ratio 0.1457 (docs/paper-reproduction.md's
    table, a regression value); the reactions balance the couple (sum RF = 0)."""
    r = paper["example1_cantilever"]
    s = r.step(1)
    assert s.name == "Step-1" and r.last is s and r[1] is s
    assert s["U"][[2, 3], 1].mean() / 0.3 == pytest.approx(0.1457, abs=5e-5)
    # the end couple has zero resultant, so the reactions sum to zero (relative to |RF|)
    assert np.abs(s["RF_total"]).max() <= 1e-12 * np.abs(s["RF"]).sum()


def test_hertz(paper):
    """Example 2, 389 elements: peak CPRESS within 5 % of p0 = 83.60; the pair transmits
    the load on the half disc, sum CPRESS * CNAREA = 100, within 1 %."""
    s = paper["hertz_389_vem"].last
    pair = s.contact[1]
    assert CONTACT_COLUMNS <= set(pair.columns)
    assert pair["CPRESS"].max() == pytest.approx(83.60, rel=0.05)
    assert (pair["CPRESS"] * pair["CNAREA"]).sum() == pytest.approx(100.0, rel=0.01)
    it = s.iterations
    assert ITERATION_COLUMNS <= set(it.columns) and 1 <= len(it) <= 8
    assert it["residual"][-1] < 1e-6


def test_interface(paper):
    """Example 3: mid-interface pressure between the laterally free and confined plane-strain
    values (tests/reference/README.md), every slave node closed."""
    pair = paper["interface_voronoi_200"].last.contact[1]
    e, nu, eps = 1e9, 0.3, 0.05
    x = pair["coordinates"][:, 0]
    p = pair["CPRESS"][(x > 1) & (x < 3)]
    assert (pair["STATUS"] == 1).all()
    assert e / (1 - nu**2) * eps < p.mean() < e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * eps


def test_dam_every_documented_field(paper):
    """Example 4: steps by number and name, every field and table of docs/output-format.md,
    the phases and the contact iterations; the RF totals are the sums of RF."""
    r = paper["dam_joint"]
    assert [s.name for s in r.steps] == ["SELF-WEIGHT", "RESERVOIR"]
    assert r.step("reservoir") is r.step(2) and r.complete and r.attrs["solver"].startswith("cholmod")
    m = r.mesh
    assert m.coordinates.shape == (m.nnode, 2) and len(m.offsets) == m.nelem + 1
    assert m.element_set_names == ["FOUNDATION", "DAM"] and m.material_names == ["ROCK"]
    assert len(m.elements_in("DAM")) + len(m.elements_in("FOUNDATION")) == m.nelem
    for s in r.steps:
        assert set(s.fields) == STEP_FIELDS
        for k in ("U", "RF"):
            assert s[k].shape == (m.nnode, 2)
        for k in ("S_node", "E_node"):
            assert s[k].shape == (m.nnode, 4)
        for k in ("S_element", "E_element"):
            assert s[k].shape == (m.nelem, 4)
        assert s["ERROR_INDICATOR"].shape == (m.nelem,)
        np.testing.assert_allclose(s["RF_total"], s["RF"].sum(axis=0), rtol=1e-12, atol=1e-9 * np.abs(s["RF"]).max())
        assert set(s.rf_sets) == {"BOTTOM", "LEFT", "RIGHT"}
        # error estimate attributes and the relative error the log prints
        assert 0 < s.relative_error < 0.2
        np.testing.assert_allclose(np.sqrt((s["ERROR_INDICATOR"] ** 2).sum()), s.attrs["error_estimate"], rtol=1e-10)
        pair = s.contact[1]
        assert set(pair.columns) == CONTACT_COLUMNS and len(pair) > 0
        assert set(s.iterations.columns) == ITERATION_COLUMNS
    # the geostatic step reports zero displacements (U relative to it), the reservoir moves the dam
    assert not r.step(1)["U"].any() and r.step(2)["U"][:, 0].max() > 0
    ph = r.phases
    assert ph["phase"][-1] == "total"
    top = (ph["within"] == "") & (ph["phase"] != "total")
    # the phases without an enclosing one add up to the total, up to the moments between
    # two timed phases (0.1 ms of 0.55 s measured): 1 %
    assert ph["seconds"][top].sum() == pytest.approx(ph["seconds"][-1], rel=1e-2)
    assert r.log and os.path.exists(r.log)


def test_meshio_matches_the_solver_vtu(paper):
    """to_meshio gives the same cells and fields as the solver's own .vtu (an independent writer)."""
    import meshio

    r = paper["dam_joint"]
    ours = r.to_meshio("RESERVOIR")
    vtu = meshio.read(os.path.join(r.folder, "dam_joint_0002.vtu"))
    np.testing.assert_array_equal(ours.points, vtu.points)
    np.testing.assert_array_equal(ours.point_data["U"], vtu.point_data["U"][:, :2])
    ids = np.concatenate(ours.cell_data["ELEMENT_ID"])
    ids_vtu = np.concatenate(vtu.cell_data["ELEMENT_ID"])
    cells = {int(i): tuple(c) for b, bid in zip(ours.cells, ours.cell_data["ELEMENT_ID"]) for i, c in zip(bid, b.data)}
    cells_vtu = {int(i): tuple(c) for b, bid in zip(vtu.cells, vtu.cell_data["ELEMENT_ID"]) for i, c in zip(bid, b.data)}
    assert sorted(ids) == sorted(ids_vtu) and cells == cells_vtu
    # polygons grouped by vertex count: a handful of blocks, not one per run
    assert len(ours.cells) <= 6
    err = dict(zip(ids, np.concatenate(ours.cell_data["ERROR_INDICATOR"])))
    err_vtu = dict(zip(ids_vtu, np.concatenate(vtu.cell_data["ERROR_INDICATOR"])))
    assert err == err_vtu


def test_second_order_cells(tmp_path, vemcontact):
    """CPE8 cells stay quad8 (corners, then side nodes); VPE2 polygons go round the boundary."""
    r = vctools.run(os.path.join(INPUTS, "hertz_329_fem2.inp"), out=str(tmp_path / "fem2"), exe=vemcontact)
    m = r.to_meshio()
    assert {b.type for b in m.cells} == {"quad8"}
    cells, types = r.vtk_cells()
    assert set(types) == {23} and len(cells) == 9 * r.mesh.nelem
    np.testing.assert_array_equal(boundary_order(np.arange(8), 4), [0, 4, 1, 5, 2, 6, 3, 7])
    np.testing.assert_array_equal(boundary_order(np.arange(5), 1), np.arange(5))


def test_pyvista_when_installed(paper):
    pytest.importorskip("pyvista")
    g = paper["dam_joint"].to_pyvista(2)
    assert g.n_cells == paper["dam_joint"].mesh.nelem and "U" in g.point_data


def test_sweep_example_script(tmp_path, vemcontact, monkeypatch):
    """The example script of docs/python-api.md: the distortion sweep built from arrays.
    VPE2 is exact for pure bending (ratio 1 at every distortion, to round-off); CPE4 on
    the undistorted mesh gives the bilinear quad's closed form 1/4.125 and loses
    deflection as the mesh is skewed."""
    monkeypatch.setenv("VEMCONTACT_EXE", vemcontact)
    ex = runpy.run_path(os.path.join(ROOT, "postprocess", "examples", "cantilever_sweep.py"))
    r = ex["sweep"](str(tmp_path))
    for db in (0.0, 1.0, 2.0, 4.0):
        assert r["VPE2", db] == pytest.approx(1.0, abs=1e-9)
    assert r["CPE4", 0.0] == pytest.approx(1 / 4.125, rel=1e-9)
    assert r["CPE4", 0.0] > r["CPE4", 1.0] > r["CPE4", 2.0] > r["CPE4", 4.0]
    # the script itself runs and prints the table
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))
    p = subprocess.run([sys.executable, os.path.join(ROOT, "postprocess", "examples", "cantilever_sweep.py"),
                        str(tmp_path / "script")], capture_output=True, text=True, env=env)
    assert p.returncode == 0 and "VPE2" in p.stdout, p.stderr


def test_deck_text_and_errors(tmp_path, vemcontact):
    """Deck text runs as it is; a bad deck raises RunError with the exit status and the
    solver's one-line message; an unknown step name is a KeyError naming the steps."""
    text = open(os.path.join(INPUTS, "example1_cantilever.inp")).read()
    r = vctools.run(text, out=str(tmp_path / "t"), job="cant", exe=vemcontact)
    assert r.job == "cant" and r.mesh.nelem == 2
    with pytest.raises(KeyError, match="Step-1"):
        r.step("NOPE")
    with pytest.raises(RunError) as e:
        vctools.run(text.replace("*ELASTIC\n1000.0, 0.0", "*ELASTIC\n-1000.0, 0.0"), out=str(tmp_path / "bad"),
                    exe=vemcontact)
    assert e.value.status == 1
    assert ".inp:" in e.value.message


def test_find_executable(monkeypatch, tmp_path):
    """VEMCONTACT_EXE first; a missing executable is one message naming what was tried."""
    from vctools.api import find_executable
    from vctools.plot.results import ResultError

    monkeypatch.setenv("VEMCONTACT_EXE", str(tmp_path / "nothing"))
    with pytest.raises(ResultError, match="nothing"):
        find_executable(str(tmp_path / "nothing"))
