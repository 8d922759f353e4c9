"""Curve tools (vctools.plot.curves) and the paper reproduction (vctools.paper)."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vctools.paper import reproduce, runs
from vctools.plot import curves
from vctools.plot.results import ResultError

ENV = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(__file__), ".."))
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PNG = b"\x89PNG\r\n\x1a\n"




@pytest.fixture(scope="module")
def hertz389(vemcontact, tmp_path_factory):
    """The 389-element Hertz deck (VEM) run once: its output folder."""
    out = tmp_path_factory.mktemp("hertz389")
    subprocess.run([vemcontact, "-q", "-o", str(out), os.path.join(ROOT, "inputs", "hertz_389_vem.inp")], check=True)
    return out


def run_curves(*args):
    return subprocess.run([sys.executable, "-m", "vctools.plot.curves", *args], capture_output=True, text=True,
                          env=ENV)


def one_line_error(r, *words):
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    for w in words:
        assert w in lines[0], lines[0]


def test_hertz_formula():
    """The paper's example 2: a = 1.523 and p0 = 83.60 for P = 200 on the full disc."""
    a, p0, estar = curves.hertz(200.0, 10.0, 1.0e3, 0.3, 1.0e6, 0.3)
    assert round(a, 3) == 1.523
    assert round(p0, 2) == 83.60
    assert estar == pytest.approx(1.0 / (0.91e-3 + 0.91e-6), rel=1e-12)
    # p(x) vanishes at x = a, equals p0 at 0, and integrates to P: (pi/2) a p0 = P
    assert curves.hertz_pressure([0.0, a, 2 * a], a, p0).tolist() == pytest.approx([p0, 0.0, 0.0])
    assert 0.5 * 3.141592653589793 * a * p0 == pytest.approx(200.0, rel=1e-12)


def test_pressure_plot_on_hertz_run(hertz389, tmp_path):
    out = tmp_path / "p.png"
    r = run_curves("pressure", str(hertz389), str(hertz389), "--label", "one", "--label", "two",
                   "--hertz", "200,10,1e3,0.3,1e6,0.3", "--units", "m,Pa", "--xmax", "3", "-o", str(out))
    assert r.returncode == 0, r.stderr
    assert out.read_bytes()[:8] == PNG and out.stat().st_size > 20000
    assert "p0 = 83.5992" in r.stdout
    c = runs.read_contact(str(hertz389))
    t, label = c.along("auto")
    assert label == "x" and (t == c.x).all()      # the nearly flat contact zone: along x
    # the peak is at the symmetry line and within 2 % of the analytical 83.60
    assert c.x[c.cpress.argmax()] == pytest.approx(0.0, abs=1e-12)
    assert c.cpress.max() == pytest.approx(83.60, rel=0.02)
    assert (c.cpress[~c.closed] == 0).all() and (c.copen[c.closed] <= 0).all()


def test_iterations_parser(hertz389):
    lg = runs.read_log(str(hertz389))
    name, its, converged = lg.step()
    assert converged and len(its) >= 2
    assert [it.iteration for it in its] == list(range(1, len(its) + 1))
    # the last iteration's peak is the converged CPRESS of the CSV, and K is read back
    assert its[-1].pressure == pytest.approx(runs.read_contact(str(hertz389)).cpress.max(), rel=1e-4)
    assert lg.penalty() == pytest.approx(1.0e5, rel=1e-3)
    s = curves.iteration_series([str(hertz389)])
    assert s[0]["peaks"] == [it.pressure for it in its] and s[0]["label"] == "K = 1e+05"
    md = curves.iterations_markdown(s, curves.PAPER_TABLE1)
    assert "paper, omega = 1e+05" in md and "| 2 |" in md and "98.20" in md


def test_iterations_command(hertz389, tmp_path):
    md = tmp_path / "t1.md"
    r = run_curves("iterations", str(hertz389 / "hertz_389_vem.log"), "--paper-table1", "-o", str(tmp_path / "i.png"),
                   "--markdown", str(md))
    assert r.returncode == 0, r.stderr
    assert md.read_text() == r.stdout and "| iteration |" in r.stdout
    assert (tmp_path / "i.png").read_bytes()[:8] == PNG


def test_bad_input(tmp_path, hertz389, vemcontact):
    one_line_error(run_curves("pressure", str(tmp_path / "none.csv")), "none.csv", "no such file")
    bad = tmp_path / "bad.csv"
    bad.write_text("node,x,y,PRESSURE\n1,0,0,1\n")
    one_line_error(run_curves("pressure", str(bad)), "bad.csv", "COPEN")
    # the iterations are read from the run's JOB.h5: a run without results, and one
    # without contact (its results carry no iteration records)
    log = tmp_path / "nolog.log"
    log.write_text("vemcontact 0.1.0: job x\nstep Step-1\n  solve 0.001 s\n")
    one_line_error(run_curves("iterations", str(log)), "nolog.h5", "no such file")
    nocontact = tmp_path / "nocontact"
    subprocess.run([vemcontact, "-q", "-o", str(nocontact), os.path.join(ROOT, "inputs", "block_selfweight.inp")],
                   check=True, capture_output=True)
    one_line_error(run_curves("iterations", str(nocontact / "block_selfweight.h5")), "block_selfweight.h5",
                   "no contact iterations")
    one_line_error(run_curves("pressure", str(hertz389), "--hertz", "200,10"), "--hertz", "six numbers")
    one_line_error(run_curves("deflection", str(hertz389)), "not the two-element cantilever")
    r = run_curves("--help")
    assert r.returncode == 0 and "pressure" in r.stdout and "iterations" in r.stdout


def test_paper_quick(vemcontact, tmp_path):
    """A --quick reproduction writes the document with every section and its figures."""
    r = subprocess.run([sys.executable, "-m", "vctools.paper", "--quick", "--exe", vemcontact,
                        "--out", str(tmp_path / "doc"), "--work", str(tmp_path / "work")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "doc" / "paper-reproduction.md").read_text()
    for section in ("## Example 1", "(Fig. 4)", "### Table 1", "### Figs. 6-8", "## Example 3", "Fig. 10",
                    "## Example 4", "## Runs", "83.60", "82.21", "80.57", "227.11", "1/4.125", "--quick"):
        assert section in text, section
    assert "failed" not in text.split("## Runs")[1].replace("0 failed", "")
    figs = tmp_path / "doc" / "figures"
    for name in ("fig04_cantilever_distortion.png", "table1_iterations.png", "fig07_hertz_pressure.png",
                 "fig08_hertz_peak.png", "fig10a_interface_shapes.png"):
        f = figs / name
        assert f.read_bytes()[:8] == PNG and f.stat().st_size < 300_000, name
        assert f"figures/{name}" in text
    # example 1 at 2d/b = 0: the Q4 closed form 1/4.125 (pure bending, two 20 x 8 elements, nu = 0)
    row = next(line for line in text.splitlines() if line.startswith("| 0.0 |"))
    assert float(row.split("|")[3]) == pytest.approx(1 / 4.125, rel=1e-3)
    # the HARD and SURFACE TO SURFACE variants: sections, figures and the claims they rest on
    for section in ("### Example 2 with HARD contact", "### Example 3 node by node", "The exact reference"):
        assert section in text, section
    for name in ("fig07b_hertz_pressure_hard.png", "fig10c_interface_nts_sts.png"):
        assert (figs / name).read_bytes()[:8] == PNG and f"figures/{name}" in text
    work = tmp_path / "work"
    for kind in ("vem_nts", "vem_sts", "fem_nts"):
        h = reproduce.hertz_hard_stats(runs.read_contact(str(work / f"hard_hertz_389_{kind}")))
        assert h["overclosure"] < 1e-12, kind                      # HARD: no overclosure
        # STS sees the 389-element disc as its polygon (the block's nodes inserted on its
        # chords): +5.3 %, O(h) (docs/contact-formulation.md, "Curved faces")
        assert h["peak"] == pytest.approx(83.60, rel=0.06 if kind == "vem_sts" else 0.04), kind
        assert h["last_closed"] < h["first_open"]
    for m in ("quad", "voronoi_50"):
        # the contact patch test (top and bottom on rollers): STS exact to round-off, NTS not
        sts = reproduce.patch_stats(str(work / f"roller_{m}_sts"))
        nts = reproduce.patch_stats(str(work / f"roller_{m}_nts"))
        assert sts["cpress"] < 1e-8 and sts["stress_max"] < 1e-8 and sts["slip"] < 1e-10, (m, sts)
        assert sts["n"] > nts["n"]                                 # inserted nodes are slave nodes too
        assert nts["cpress"] > 0.01 and nts["stress_max"] > 0.01, (m, nts)
        # the clamped deck: STS keeps every slave node of the deck, NTS scatters about it
        nb = reproduce.node_by_node(runs.read_contact(str(work / f"interface_{m}")),
                                    runs.read_contact(str(work / f"interface_{m}_sts")))
        assert nb["n"] == nts["n"] and 0.01 < nb["max"] < 0.5, (m, nb)


def test_variant_deck(tmp_path):
    """Deck variants by text substitution: HARD drops the LINEAR data line, rollers free x but at one
    corner node per block, and a deck without what is to be replaced is an error, not a silent copy."""
    src = os.path.join(ROOT, "inputs", "interface_voronoi_50.inp")
    text = reproduce.variant_deck(src, "test", surface_to_surface=True, hard=True, rollers=True)
    assert "TYPE=SURFACE TO SURFACE" in text and "PRESSURE-OVERCLOSURE=HARD" in text
    assert "1.0e12" not in text and "LINEAR" not in text.split("*SURFACE BEHAVIOR")[1].split("\n")[0]
    bc = text.split("*BOUNDARY")[1].split("*STEP")[0].split()
    assert bc[0] == "BOTTOM," and "TOP," not in bc and len(bc) == 9     # BOTTOM, 2, 2 / n, 1, 1 / m, 1, 1
    assert "INPUT=" + os.path.join(ROOT, "inputs", "meshes") in text
    with pytest.raises(ResultError, match="no BOTTOM,1,2"):
        reproduce.variant_deck(os.path.join(ROOT, "inputs", "hertz_389_vem.inp"), "test", rollers=True)


def test_dam_joint_formulations(vemcontact, tmp_path):
    """Example 4's joint: NODE TO SURFACE (penalty) and SURFACE TO SURFACE (HARD) agree node by node
    on the matched joint (no node inserted), both steps; the slave node next to the tip carries its
    neighbours' pressure (the tip fix); CSLIP is read, zero after the geostatic step."""
    src = os.path.join(ROOT, "inputs", "dam_joint.inp")
    deck = tmp_path / "dam_sts.inp"
    deck.write_text(reproduce.variant_deck(src, "test", surface_to_surface=True, hard=True))
    for d, o in ((src, "nts"), (str(deck), "sts")):
        subprocess.run([vemcontact, "-q", "-o", str(tmp_path / o), d], check=True)
    for step in (1, 2):
        n, s = runs.read_contact(str(tmp_path / "nts"), step=step), runs.read_contact(str(tmp_path / "sts"), step=step)
        nb = reproduce.node_by_node(n, s)
        assert nb["extra"] == 0 and nb["n"] == len(n.node) and nb["max"] < 0.005, nb
        for c in (n, s):
            assert c.closed.all() and reproduce.tip_ratio(c) == pytest.approx(1.0, abs=0.1)
            assert c.cslip is not None and (step == 2 or (c.cslip == 0).all())
        assert s.copen.min() > -1e-15                                # HARD: no overclosure


def test_paper_bad_exe(tmp_path):
    r = subprocess.run([sys.executable, "-m", "vctools.paper", "--quick", "--exe", str(tmp_path / "nope"),
                        "--out", str(tmp_path)], capture_output=True, text=True, env=ENV)
    one_line_error(r, "nope", "no vemcontact executable")


def test_contact_command_draws_cpress_copen_cslip(hertz389, tmp_path):
    """`vc-curves contact` (the console script of pyproject.toml) draws CPRESS, COPEN and
    CSLIP along the pair; the Hertz overlay is the analytical pressure."""
    import tomllib
    from importlib import import_module
    scripts = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml").read_text())["project"]["scripts"]
    mod, fn = scripts["vc-curves"].split(":")
    assert getattr(import_module(mod), fn) is curves.main
    out = tmp_path / "c.png"
    r = run_curves("contact", str(hertz389), "--hertz", "200,10,1e3,0.3,1e6,0.3", "--units", "mm,MPa", "-o", str(out))
    assert r.returncode == 0, r.stderr
    assert out.read_bytes()[:8] == PNG and out.stat().st_size > 20000
    c = runs.read_contact(str(hertz389))
    assert c.cslip is not None and np.isfinite(c.cslip).all()
    # the slip of the symmetry-line node is zero by symmetry (both bodies are held in x
    # at x = 0) up to where its normal projection lands on the tilted, deformed master
    # side (measured 1.3e-6 of the largest slip); the slip grows away from it
    k0 = np.argmin(np.abs(c.x))
    assert abs(c.cslip[k0]) < 1e-4 * np.abs(c.cslip).max()
    assert np.abs(c.cslip[c.closed]).max() > 100 * abs(c.cslip[k0])
