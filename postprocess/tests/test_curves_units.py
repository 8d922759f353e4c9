"""vc-curves --units converts lengths and stresses from the deck's units (--model-units,
default m,Pa) as vc-plot does, instead of relabelling the axes: the numbers are read back
from the functions that draw (they return what they drew) and compared with the model's
values times the factors of vctools.plot.contour.unit_factors, which vc-plot uses."""
import numpy as np
import pytest

from vctools.paper import runs
from vctools.plot import curves

# a small SI contact table: 5 slave nodes along x, pressures of a few MPa in Pa
X = np.array([0.0, 0.01, 0.02, 0.03, 0.04])
CPRESS = np.array([3.0e6, 2.8e6, 2.1e6, 0.9e6, 0.0])
COPEN = np.array([-2.0e-6, -1.8e-6, -1.1e-6, -0.2e-6, 4.0e-6])
CSLIP = np.array([0.0, 1.0e-7, 2.0e-7, 3.0e-7, 3.5e-7])


def write_csv(folder):
    f = folder / "job_contact_pair1_0001.csv"
    rows = ["node,x,y,COPEN,CPRESS,STATUS,CSLIP"]
    for k in range(len(X)):
        status = "CLOSED" if CPRESS[k] > 0 else "OPEN"
        rows.append(f"{k + 1},{float(X[k])!r},0.0,{float(COPEN[k])!r},{float(CPRESS[k])!r},{status},"
                    f"{float(CSLIP[k])!r}")
    f.write_text("\n".join(rows) + "\n")
    return f


def test_convert_curve_scales_lengths_and_pressures(tmp_path):
    c = runs.read_contact(str(write_csv(tmp_path)))
    m = curves.convert_curve(c, 1e3, 1e-6)
    # exact decimal factors: the products round like any multiplication (1 ulp)
    assert np.allclose(m.x, X * 1e3, rtol=1e-15, atol=0)
    assert np.allclose(m.copen, COPEN * 1e3, rtol=1e-15, atol=0)
    assert np.allclose(m.cslip, CSLIP * 1e3, rtol=1e-15, atol=0)
    assert np.allclose(m.cpress, CPRESS * 1e-6, rtol=1e-15, atol=0)
    assert np.array_equal(m.closed, c.closed) and np.array_equal(m.node, c.node)


def test_plot_pressure_converts_to_mm_mpa(tmp_path):
    c = runs.read_contact(str(write_csv(tmp_path)))
    hz = (2.0e5, 0.5, 2.0e11, 0.3, 2.0e11, 0.3)   # P [N/m], R [m], E [Pa]: steel on steel
    a_m, p0_pa, _ = curves.hertz(*hz)
    info = curves.plot_pressure([c], str(tmp_path / "p.png"), hertz_args=hz, along="x", units="mm,MPa",
                                model_units="m,Pa")
    assert info["peak"][0] == pytest.approx(3.0, rel=1e-15)        # 3e6 Pa = 3 MPa
    assert info["x_peak"][0] == pytest.approx(0.0, abs=1e-15)
    assert info["a"] == pytest.approx(a_m * 1e3, rel=1e-15)
    assert info["p0"] == pytest.approx(p0_pa * 1e-6, rel=1e-15)
    # without --model-units the units only label the axes (the paper's figures)
    info = curves.plot_pressure([c], str(tmp_path / "q.png"), along="x", units="mm,MPa")
    assert info["peak"][0] == pytest.approx(3.0e6, rel=1e-15)


def test_units_factors_are_vc_plots():
    """One conversion for both commands: ft and psi from an SI deck."""
    from vctools.plot.contour import unit_factors
    lf, sf, lu, su = curves.shown_units("ft,psi", "m,Pa")
    assert (lf, sf) == unit_factors("ft,psi", "m,Pa")[:2]
    assert lf == pytest.approx(1 / 0.3048, rel=1e-15) and sf == pytest.approx(1 / 6894.757293168361, rel=1e-15)
    assert (lu, su) == (" [ft]", " [psi]")
    # a length alone: stresses stay in the model's unit, which labels them
    assert curves.shown_units("mm", "m,Pa") == (1e3, 1.0, " [mm]", " [Pa]")


def test_peak_and_iterations_convert(tmp_path):
    pts = [{"job": "a", "nelem": 10, "formulation": "VEM", "peak": 2.5e6, "x_peak": 0.02}]
    shown = curves.plot_peak(pts, str(tmp_path / "k.png"), exact=3.0e6, units="mm,MPa", model_units="m,Pa")
    assert shown[0]["peak"] == pytest.approx(2.5, rel=1e-15)
    assert shown[0]["x_peak"] == pytest.approx(20.0, rel=1e-15)
    series = [{"label": "K", "K": 1e12, "peaks": [9.0e6, 3.1e6, 3.0e6], "job": "a"}]
    shown = curves.plot_iterations(series, str(tmp_path / "i.png"), units="m,kPa", model_units="m,Pa")
    assert shown[0]["peaks"] == pytest.approx([9.0e3, 3.1e3, 3.0e3], rel=1e-15)
    assert series[0]["peaks"] == [9.0e6, 3.1e6, 3.0e6]   # the caller's series is left as it was


def test_cli_units_convert(tmp_path):
    f = write_csv(tmp_path)
    out = tmp_path / "c.png"
    assert curves.main(["contact", str(f), "--units", "mm,MPa", "-o", str(out)]) == 0
    assert out.stat().st_size > 0
    # an unknown unit is one error line and status 1, as in vc-plot
    assert curves.main(["contact", str(f), "--units", "furlong", "-o", str(out)]) == 1
