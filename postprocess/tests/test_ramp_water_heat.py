"""Temperatures and the water in the joints follow the step's ramp (AMPLITUDE=RAMP,
the default of *STATIC, as CalculiX ramps temperatures): checked increment by
increment (FREQUENCY=1) against closed forms computed here.

- A bar held at both ends whose temperature rises in one step of four increments:
  S_xx = -E alpha dT(t) with dT(t) = t dT, t = 1/4 .. 1 (plane stress).
- A block resting on a rigid base through a frictionless HARD joint, water brought
  into the joint by *UPLIFT in a step of four increments: at step fraction t every
  slave node's CFLUIDP is t times the guideline pressure gamma_w (h(x) - y), and the
  joint carries N = W - t U (vertical equilibrium; the base is held horizontally).
- A step that raises the headwater of that uplift: the heads go linearly, so CFLUIDP
  goes linearly from the old distribution to the new one.
- AMPLITUDE=STEP applies the water at once.
"""
import h5py
import numpy as np
import pytest

from test_thermal import deck as thermal_deck, E, ALPHA, T0, T1, L
from test_uplift import RHO, G, GW, block_deck, run

B, HT = 5.0, 4.0
RECT = [(0, 0), (B, 0), (B, HT), (0, HT)]


def frames(h5, step):
    with h5py.File(h5) as f:
        g = f[f"increments/{step}"]
        return {k: float(g[k].attrs["time"]) for k in g}


def pair_at(h5, group):
    with h5py.File(h5) as f:
        g = f[f"{group}/contact/pair_1"]
        x = g["coordinates"][()]
        x = x if x.shape[-1] == 2 else x.T
        return x, g["CFLUIDP"][()], g["CPRESS"][()], g["CNAREA"][()]


def test_temperature_ramps_within_the_step(exe, tmp_path):
    def bc(x, y):
        out = [(1, 0.0)] if x in (0.0, L) else []
        return out + ([(2, 0.0)] if (x, y) == (0.0, 0.0) else [])
    text, _ = thermal_deck("CPS4", 1, bc, lambda x, y: T1, False)
    text = text.replace("*STATIC\n", "*STATIC, DIRECT\n0.25, 1.\n").replace("*EL FILE", "*EL FILE, FREQUENCY=1")
    (tmp_path / "bar.inp").write_text(text)
    h5, _ = run(exe, tmp_path / "bar.inp", tmp_path / "out")
    with h5py.File(h5) as f:
        names = sorted(f["increments/0001"])
        assert names == ["0001", "0002", "0003"]
        for k, name in enumerate(names, start=1):
            s = f[f"increments/0001/{name}/S_element"][()]
            # a uniform state: round-off of the solve, 1e-10
            np.testing.assert_allclose(s[:, 0], -E * ALPHA * (T1 - T0) * k / 4, rtol=1e-10)
        np.testing.assert_allclose(f["steps/0001/S_element"][()][:, 0], -E * ALPHA * (T1 - T0), rtol=1e-10)


def head_pressure(x, heel, toe):
    """gamma_w max(0, h - y), h linear from the heel's head to the toe's over the base."""
    h = heel + (toe - heel) * x[:, 0] / B
    return GW * np.maximum(0.0, h - x[:, 1])


def uplift_line(heel, toe):
    return (f"*UPLIFT, INTERACTION=JOINT, UNIT WEIGHT={float(GW)!r}\n"
            f"0., 0., {float(heel)!r}\n{float(B)!r}, 0., {float(toe)!r}")


@pytest.mark.parametrize("amplitude", ["RAMP", "STEP"])
def test_uplift_ramps_within_the_step(exe, tmp_path, amplitude):
    after = ("*STEP" + (", AMPLITUDE=STEP" if amplitude == "STEP" else "") + "\n*STATIC, DIRECT\n0.25, 1.\n"
             + uplift_line(2.0, 0.5) + "\n*CONTACT FILE, FREQUENCY=1\nCSTRESS, CDIS\n*END STEP")
    d = block_deck(tmp_path / "ramp.inp", RECT, 10, 4, hard=True, after=after)
    h5, _ = run(exe, d, tmp_path / "out")
    weight = RHO * G * B * HT
    full = None
    with h5py.File(h5) as f:
        names = sorted(f["increments/0002"]) + ["end"]
    for k, name in enumerate(names, start=1):
        group = "steps/0002" if name == "end" else f"increments/0002/{name}"
        x, cfluidp, cpress, cnarea = pair_at(h5, group)
        t = k / 4 if amplitude == "RAMP" else 1.0
        exact = t * head_pressure(x, 2.0, 0.5)
        # the guideline formula at the nodes: round-off
        np.testing.assert_allclose(cfluidp, exact, rtol=1e-12, atol=1e-12 * GW)
        # U = the integral of the nodal pressures with the tributary areas (exact for a
        # linear pressure); N = W - U: the HARD joint balances to the solve's round-off
        np.testing.assert_allclose(np.sum(cpress * cnarea), weight - np.sum(cfluidp * cnarea), rtol=1e-9)
        full = exact
    assert np.sum(full) > 0


def test_raised_headwater_goes_linearly(exe, tmp_path):
    after = ("*STEP\n*STATIC\n" + uplift_line(2.0, 0.5) + "\n*END STEP\n"
             "*STEP\n*STATIC, DIRECT\n0.25, 1.\n" + uplift_line(3.0, 1.0) +
             "\n*CONTACT FILE, FREQUENCY=1\nCSTRESS, CDIS\n*END STEP")
    d = block_deck(tmp_path / "raise.inp", RECT, 10, 4, hard=True, after=after)
    h5, _ = run(exe, d, tmp_path / "out")
    with h5py.File(h5) as f:
        names = sorted(f["increments/0003"])
    assert names == ["0001", "0002", "0003"]
    for k, name in enumerate(names + ["end"], start=1):
        group = "steps/0003" if name == "end" else f"increments/0003/{name}"
        x, cfluidp, _, _ = pair_at(h5, group)
        t = k / 4
        # the heads at t: 2 + t and 0.5 + 0.5 t; the pressure, affine in them where
        # positive, is (1 - t) p_old + t p_new there
        exact = head_pressure(x, 2.0 + t, 0.5 + 0.5 * t)
        np.testing.assert_allclose(cfluidp, exact, rtol=1e-12, atol=1e-12 * GW)
        old, new = head_pressure(x, 2.0, 0.5), head_pressure(x, 3.0, 1.0)
        np.testing.assert_allclose(cfluidp, (1 - t) * old + t * new, rtol=1e-12, atol=1e-12 * GW)
