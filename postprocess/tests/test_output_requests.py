"""Output requests select the fields written (CalculiX's meaning): a deck with
*NODE FILE / *EL FILE / *CONTACT FILE writes, per step, exactly the fields in force
(the step's own requests, else the previous step's); the mesh and the labels always.
A deck without requests writes every field.  *NODE PRINT / *EL PRINT / *CONTACT PRINT
go to JOB_print_NNNN.csv, with the set totals TOTALS=YES|ONLY asks for."""
import csv
import os
import subprocess
import sys
from pathlib import Path

import h5py
import meshio
import numpy as np
import pytest

from test_outputs import grid, nset, run

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, PYTHONPATH=str(ROOT / "postprocess"))

NX, NY, F = 8, 4, 250.0
LABELS_POINT = {"NODE_ID"}
LABELS_CELL = {"ELEMENT_ID", "MATERIAL", "ELSET", "PART"}
MESH = {"coordinates", "node_ids", "element_offsets", "element_connectivity", "element_ids",
        "element_material", "element_type", "element_formulation", "element_set", "element_set_names",
        "material_names", "element_part", "xdmf_topology"}


def plate(requests):
    """A 4 x 2 plate (CPS4), left edge on rollers with one pin, the right edge's five
    nodes pulled by F each; `requests[k]` are the output request lines of step k+1."""
    lines, node = grid(NX, NY, 4.0, 2.0, "CPS4")
    lines += nset("LEFT", [node(0, j) for j in range(NY + 1)]) + nset("RIGHT", [node(NX, j) for j in range(NY + 1)])
    lines += nset("PIN", [node(0, 0)])
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "1e4, 0.25", "*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL", "2.",
              "*BOUNDARY", "LEFT, 1", "PIN, 2"]
    for k, req in enumerate(requests):
        lines += ["*STEP", "*STATIC", "*CLOAD", f"RIGHT, 1, {F * (k + 1)}", *req, "*END STEP"]
    return "\n".join(lines) + "\n"


REQUESTS = [
    ["*NODE FILE", "U", "*NODE PRINT, NSET=LEFT, TOTALS=YES", "RF"],
    ["*NODE FILE", "U", "*EL FILE", "S", "*EL PRINT, ELSET=ALL", "S", "*NODE PRINT, NSET=LEFT, TOTALS=ONLY", "RF"],
    ["*NODE FILE", "RF"],
]


@pytest.fixture(scope="module")
def runs(exe, tmp_path_factory):
    """The plate with requests per step (`req`) and without any (`all`)."""
    out = {}
    for name, requests in (("req", REQUESTS), ("all", [[], [], []])):
        d = tmp_path_factory.mktemp(name)
        (d / "p.inp").write_text(plate(requests))
        run(exe, d / "p.inp", d)
        out[name] = d
    return out


def vtu_fields(path):
    m = meshio.read(path)
    return set(m.point_data), set(m.cell_data)


def h5_fields(path, step):
    """The result fields of a step (its increments table is not one: every step has it)."""
    with h5py.File(path) as f:
        return set(f["steps"][step]) - {"increments"}, set(f["mesh"])


def read_print(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        r["value"] = float(r["value"])
        r["id"] = int(r["id"])
    return rows


def test_fields_per_step(runs):
    """Step 1 U; step 2 U and S; step 3 RF and (carried over from step 2) S.  The
    error estimate's ERROR_INDICATOR goes with S."""
    d = runs["req"]
    stress = {"S", "S1", "S3", "MISES"}
    cell_s = {"S", "ERROR_INDICATOR"}
    h5_s = {"S_element", "S_node", "ERROR_INDICATOR"}
    want_vtu = [({"U"}, set()), ({"U"} | stress, cell_s), ({"RF"} | stress, cell_s)]
    want_h5 = [{"U"}, {"U"} | h5_s, {"RF", "RF_total", "LOAD_total", "RF_sets"} | h5_s]
    for k in range(3):
        point, cell = vtu_fields(d / f"p_{k + 1:04d}.vtu")
        assert point == want_vtu[k][0] | LABELS_POINT, (k + 1, point)
        assert cell == want_vtu[k][1] | LABELS_CELL, (k + 1, cell)
        steps, mesh = h5_fields(d / "p.h5", f"{k + 1:04d}")
        assert steps == want_h5[k], (k + 1, steps)
        assert mesh == MESH
    # the fields written are those of the run without requests, bit for bit
    for k, name in ((1, "U"), (2, "S_node"), (3, "RF")):
        with h5py.File(d / "p.h5") as a, h5py.File(runs["all"] / "p.h5") as b:
            assert np.array_equal(a[f"steps/{k:04d}/{name}"][...], b[f"steps/{k:04d}/{name}"][...])


def test_no_requests_writes_everything(runs):
    """A deck without requests: every field, as before the requests were honoured."""
    d = runs["all"]
    for k in range(1, 4):
        point, cell = vtu_fields(d / f"p_{k:04d}.vtu")
        assert point == {"U", "S", "S1", "S3", "MISES", "RF", "E"} | LABELS_POINT
        assert cell == {"S", "E", "ERROR_INDICATOR"} | LABELS_CELL
        steps, _ = h5_fields(d / "p.h5", f"{k:04d}")
        assert steps == {"U", "S_element", "S_node", "ERROR_INDICATOR", "E_element", "E_node", "RF", "RF_total",
                         "LOAD_total", "RF_sets"}
    assert not list(d.glob("*_print_*.csv"))


def test_print_totals_balance_the_load(runs):
    """*NODE PRINT, NSET=LEFT, TOTALS=YES, RF: the set's reaction total balances the
    five loads of F (the only other support, PIN, lies in LEFT), to round-off
    (1e-10 relative: a sum of 5 reactions of a well-conditioned 90-dof system);
    the listed node values add up to the total row."""
    d = runs["req"]
    rows = read_print(d / "p_print_0001.csv")
    rf = [r for r in rows if r["variable"] == "RF" and r["set"] == "LEFT"]
    nodes = [r for r in rf if r["entity"] == "node"]
    total = {r["component"]: r["value"] for r in rf if r["entity"] == "total"}
    assert len(nodes) == 2 * (NY + 1) and set(total) == {"RF1", "RF2"}
    assert total["RF1"] == pytest.approx(-5 * F, rel=1e-10)
    assert abs(total["RF2"]) <= 1e-10 * 5 * F
    assert sum(r["value"] for r in nodes if r["component"] == "RF1") == pytest.approx(total["RF1"], rel=1e-12)
    # TOTALS=ONLY (step 2, load 2F): the total rows alone
    rows = read_print(d / "p_print_0002.csv")
    rf = [r for r in rows if r["variable"] == "RF"]
    assert {r["entity"] for r in rf} == {"total"}
    assert {r["component"]: r["value"] for r in rf}["RF1"] == pytest.approx(-10 * F, rel=1e-10)
    # *EL PRINT, ELSET=ALL, S: every element's stress, as in the HDF5 file (17 digits round-trip)
    s = [r for r in rows if r["variable"] == "S"]
    assert len(s) == 4 * NX * NY
    with h5py.File(d / "p.h5") as f:
        ids = f["mesh/element_ids"][...]
        s_elem = f["steps/0002/S_element"][...]
    comp = {"S11": 0, "S22": 1, "S33": 2, "S12": 3}
    pos = {int(e): i for i, e in enumerate(ids)}
    for r in s:
        assert r["value"] == s_elem[pos[r["id"]], comp[r["component"]]]
    # step 3 has no PRINT request of its own: step 2's hold (CalculiX's carry-over)
    rows = read_print(d / "p_print_0003.csv")
    assert {r["component"]: r["value"] for r in rows if r["entity"] == "total"}["RF1"] == \
        pytest.approx(-15 * F, rel=1e-10)


CONTACT_DECK = ROOT / "tests" / "data" / "calculix" / "two_blocks_contact.inp"


def contact_variant(tmp_path, exe, replace):
    """two_blocks_contact.inp with its *CONTACT FILE line and data line replaced."""
    tmp_path.mkdir()
    text = CONTACT_DECK.read_text()
    assert "*CONTACT FILE\nCDIS, CSTR\n" in text
    (tmp_path / "c.inp").write_text(text.replace("*CONTACT FILE\nCDIS, CSTR\n", replace))
    run(exe, tmp_path / "c.inp", tmp_path)
    return tmp_path


def test_contact_requests(exe, tmp_path):
    """CSTR alone: CPRESS and CSHEAR (with the labels CNAREA, STATUS) but no COPEN, CSLIP in the CSV,
    the contact VTU and HDF5; no *CONTACT FILE: no contact results at all."""
    d = contact_variant(tmp_path / "cstr", exe, "*CONTACT FILE\nCSTR\n")
    with open(d / "c_contact_pair1_0001.csv") as fh:
        assert fh.readline().strip() == "node,x,y,CPRESS,CSHEAR,CNAREA,STATUS"
    point, _ = vtu_fields(d / "c_contact_0001.vtu")
    assert point == {"U", "CPRESS", "CSHEAR", "CNAREA", "STATUS", "PAIR", "NODE_ID"}
    with h5py.File(d / "c.h5") as f:
        assert set(f["steps/0001/contact/pair_1"]) == {"node_ids", "coordinates", "CPRESS", "CSHEAR", "CNAREA",
                                                       "STATUS"}
    # *CONTACT PRINT CSTR, CDIS: every slave node's CPRESS, COPEN, CSLIP, named by the slave surface
    rows = read_print(d / "c_print_0001.csv")
    with h5py.File(d / "c.h5") as f:
        nslave = len(f["steps/0001/contact/pair_1/node_ids"])
        cpress = dict(zip(f["steps/0001/contact/pair_1/node_ids"][...], f["steps/0001/contact/pair_1/CPRESS"][...]))
    for var in ("CPRESS", "CSHEAR", "COPEN", "CSLIP"):
        assert len([r for r in rows if r["variable"] == var]) == nslave
    for r in rows:
        if r["variable"] == "CPRESS":
            assert r["value"] == cpress[r["id"]]

    d = contact_variant(tmp_path / "none", exe, "")
    assert not list(d.glob("c_contact_*"))
    with h5py.File(d / "c.h5") as f:
        assert not any(k.startswith("pair_") for k in f["steps/0001"].get("contact", {}))
    assert "c_contact_" not in (d / "c.pvd").read_text()


def run_plot(*args):
    return subprocess.run([sys.executable, "-m", "vctools.plot", *args], capture_output=True, text=True, env=ENV)


def test_plot_says_which_field_is_missing(runs, tmp_path):
    """vc-plot draws what a step has and names what its requests left out."""
    d = runs["req"]
    r = run_plot(str(d / "p.pvd"), "--step", "1", "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "no S1, S3, MISES" in r.stderr and "output requests" in r.stderr
    assert sorted(os.listdir(tmp_path)) == ["p_0001_U_x.png", "p_0001_U_y.png"]
    r = run_plot(str(d / "p.pvd"), "--step", "1", "--field", "MISES", "-o", str(tmp_path))
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert "no point field MISES" in r.stderr and "S under *EL FILE" in r.stderr
    r = run_plot(str(d / "p.pvd"), "--step", "3", "--deformed", "auto", "-o", str(tmp_path))
    assert r.returncode == 1 and "--deformed needs U" in r.stderr and "Traceback" not in r.stderr


def test_compare_names_fields_left_out(runs):
    """vc-compare on filtered results: a field in neither file is a note, not a
    failure; one in the reference only is a mismatch that names it."""
    def compare(*args):
        return subprocess.run([sys.executable, "-m", "vctools.compare", *args], capture_output=True, text=True,
                              env=ENV)
    req, full = str(runs["req"] / "p.h5"), str(runs["all"] / "p.h5")
    r = compare(req, req)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "note: step 1: S_element not compared: in neither file (the deck's output requests do not select it)" \
        in r.stdout
    r = compare(req, full)
    assert r.returncode == 1 and "step 1: S_node missing in the result" in r.stdout
