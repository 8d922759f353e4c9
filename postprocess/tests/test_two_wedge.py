"""The dam on a two-wedge foundation (inputs/dam_two_wedge_dry.inp, scene
postprocess/scenes/dam_two_wedge.toml, docs/sliding-safety.md): strength reduction against
USACE's multi-wedge limit equilibrium, computed here from the geometry.

Both wedges rest on the same seam (dip 1 in 5), so with the same F on every base USACE's
equation sums to that of one plane and the interwedge force cancels, whatever its shear:
F = (N' tan phi) / T with N' and T the components, normal and along the seam, of the
weight of the dam and both wedges (24 kN/m^3) and the reservoir's thrust on the dam
(gamma_w 5^2 / 2).  Dry, the back joint opens (the wedges move away from it along the
seam), so it carries nothing.  Measured: 2.8887 against 2.8896 (-0.03 %); the target is
the issue's 1 % for a planar mechanism.
"""
import math
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def area(poly):
    P = np.asarray(poly, float)
    return 0.5 * abs(np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1]))


def test_two_wedges_dry(exe, tmp_path):
    text = open(os.path.join(ROOT, "inputs", "dam_two_wedge_dry.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    (tmp_path / "tw.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(tmp_path / "tw.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "tw.h5") as f:
        F = float(f["steps/0003"].attrs["factor_of_safety"])
    W = 24.0e3 * (area([(4, 10), (9, 10), (6, 15), (4, 15)])
                  + area([(4, 10), (5, 8), (9.5, 7.1), (9.5, 10), (9, 10)])
                  + area([(9.5, 7.1), (12, 6.6), (12, 10), (9.5, 10)]))
    R = np.array([0.5 * 9810.0 * 5.0**2, -W])
    t = np.array([7.0, -1.4]) / math.hypot(7.0, 1.4)
    n = np.array([-t[1], t[0]])
    fs = -(R @ n) * math.tan(math.radians(45.0)) / (R @ t)
    assert fs == pytest.approx(2.8896, abs=1e-4)
    assert F == pytest.approx(fs, rel=0.01), (F, fs)


GW = 9810.0
HEEL, DAYLIGHT = np.array([4.0, 10.0]), np.array([12.0, 6.6])


def chord(xy):
    """The projection s of points on the heel-daylight chord (0 at the heel, 1 at the
    daylight point): where *UPLIFT places a slave node of either seam pair."""
    d = DAYLIGHT - HEEL
    return (xy - HEEL) @ d / (d @ d)


def test_two_wedges_penetration_water(exe, tmp_path):
    """One *UPLIFT, PENETRATION over both seam pairs: the back joint opens from the heel and
    its open nodes carry the headwater, gamma_w (15 - y); every other node of both pairs the
    linear diagram restarted at the crack tip, head 15 at the tip's chord position to 6.6
    at the daylight point, pressure gamma_w max(0, head - y).  Computed here from the node
    coordinates; round-off."""
    text = open(os.path.join(ROOT, "inputs", "dam_two_wedge_penetration.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    (tmp_path / "tw.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(tmp_path / "tw.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "tw.h5") as f:
        pairs, entered = [], []
        for k in (1, 2):
            g = f[f"steps/0002/contact/pair_{k}"]
            xy = g["coordinates"][:]
            pairs.append((xy if xy.shape[-1] == 2 else xy.T, g["CFLUIDP"][:], g["STATUS"][:]))
            entered.append(float(g.attrs["water_entered"]))
    xy = np.vstack([p[0] for p in pairs])
    p = np.concatenate([p[1] for p in pairs])
    st = np.concatenate([p[2] for p in pairs])
    s = chord(xy)
    order = np.argsort(s)
    closed = st[order] != 0
    k = int(np.argmax(closed))
    assert k > 0, "the back joint opens from the heel"
    tip = s[order][k - 1]
    opened = order[:k]
    assert np.all(xy[opened, 0] < 5.0 + 1e-9), "the crack stays in the back joint"
    # the length the water entered, along the joint: heel to the first open node, then
    # node to node (the back joint is steeper than the heel-daylight chord, so this is
    # longer than the tip's projection on the chord), the same on both seam pairs
    path = np.vstack([HEEL, xy[opened]])
    arc = float(np.sum(np.hypot(*np.diff(path, axis=0).T)))
    assert arc > tip * np.hypot(*(DAYLIGHT - HEEL)) * (1 + 1e-3)
    assert entered == pytest.approx([arc, arc], rel=1e-12), (entered, arc)
    assert np.allclose(p[opened], GW * (15.0 - xy[opened, 1]), rtol=1e-12)
    rest = order[k:]
    head = 15.0 + (6.6 - 15.0) * (s[rest] - tip) / (1.0 - tip)
    assert np.allclose(p[rest], GW * np.maximum(0.0, head - xy[rest, 1]), rtol=1e-10, atol=1e-6)


@pytest.mark.parametrize("variant,rel", [("drained", 0.01), ("uplift", 0.015)])
def test_two_wedges_wet(exe, tmp_path, variant, rel):
    """The wet variants against USACE's multi-wedge limit equilibrium with the same water
    (bench/sliding/limit_equilibrium.py: the back joint open and full, the seam's
    diagram).  The water at the kink (5, 8) acts on the halves of its two sides, each
    along its own normal, so its resultant is the limit equilibrium's; what remains is
    resistance the limit equilibrium has not: the upstream wedge leans on the kink node,
    which stays closed and slipping (measured +0.20 % drained, +1.09 % uplift, where the
    water force at the kink along one segment's normal gave +0.4 % and +1.7 %).  So F
    lies above the limit equilibrium, within 1 % drained and 1.5 % with the full uplift."""
    sys.path.insert(0, os.path.join(ROOT, "bench", "sliding"))
    import limit_equilibrium as le
    fs = le.two_wedge(variant, 45.0)[0]
    text = open(os.path.join(ROOT, "inputs", f"dam_two_wedge_{variant}.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    (tmp_path / "tw.inp").write_text(text)
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(tmp_path / "tw.inp")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "tw.h5") as f:
        F = float(f["steps/0003"].attrs["factor_of_safety"])
    assert fs <= F <= fs * (1 + rel), (F, fs)
