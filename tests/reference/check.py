"""Physics checks of the reference results themselves (tests/reference/*.h5).

    PYTHONPATH=postprocess .venv/bin/python tests/reference/check.py [tests/reference]

The same checks run on fresh runs in the test suite (README.md in this folder
names each test); this script applies them to the stored files, so a
regenerated reference can be checked before it is committed.  Prints one line
per reference and exits 1 if a check fails.
"""
import glob
import os
import sys

import h5py
import numpy as np


def load(path):
    with h5py.File(path) as f:
        out = {"x": f["mesh/coordinates"][()], "ids": f["mesh/node_ids"][()],
               "off": f["mesh/element_offsets"][()], "conn": f["mesh/element_connectivity"][()], "steps": {}}
        for k in f["steps"]:
            g = f["steps"][k]
            s = {n: g[n][()] for n in ("U", "S_element", "S_node")}
            if "contact" in g:
                s["pairs"] = {p: {n: g["contact"][p][n][()] for n in g["contact"][p]} for p in g["contact"]}
            if "factor_of_safety" in g.attrs:
                s["factor_of_safety"] = float(g.attrs["factor_of_safety"])
            out["steps"][int(k)] = s
    return out


def cantilever(r):
    """Example 1, VEM, 2d/b = 1: tip deflection (mean u_y of the end nodes) over
    the exact 0.3 equals the ratio tests/unit/driver/test_cantilever.f90 computes
    on the same mesh (0.14568, printed by that test), and lies in (0, 1)."""
    u = r["steps"][1]["U"]
    tip = u[np.abs(r["x"][:, 0] - 40) < 1e-12, 1].mean() / 0.3
    return abs(tip - 0.14568) < 1e-5, f"tip deflection ratio {tip:.5f} (unit test: 0.14568 at 2d/b = 1)"


def hertz(r, tol, second_order=False):
    """Example 2: peak pressure against p0 = 83.60, total force 100 (1 %).  The
    force is the trapezoidal rule over the slave nodes; on second-order meshes,
    whose side nodes have 4/6 of their side as tributary length, the sum of
    CPRESS * CNAREA (the trapezoidal rule does not integrate those weights)."""
    c = r["steps"][1]["pairs"]["pair_1"]
    x, p = c["coordinates"][:, 0], c["CPRESS"]
    o = np.argsort(x)
    force = (p * c["CNAREA"]).sum() if second_order else np.trapz(p[o], x[o])
    err = p.max() / 83.60 - 1
    return abs(err) < tol and abs(force / 100 - 1) < 0.01, \
        f"peak pressure {p.max():.2f} ({err:+.2%} of 83.60, allowed {tol:.0%}), force {force:.2f}"


def interface(r, scatter):
    """Example 3: mean pressure for 1 < x < 3 between the laterally free and the
    confined plane-strain values, little scatter (non-matching meshes)."""
    c = r["steps"][1]["pairs"]["pair_1"]
    e, nu, eps = 1e9, 0.3, 0.05
    free, confined = e / (1 - nu**2) * eps, e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * eps
    mid = (c["coordinates"][:, 0] > 1) & (c["coordinates"][:, 0] < 3)
    p = c["CPRESS"][mid]
    ok = (c["STATUS"] == 1).all() and free < p.mean() < confined and p.std() / p.mean() < scatter
    return ok, (f"mean pressure {p.mean():.4e} in ({free:.4e}, {confined:.4e}), "
                f"scatter {p.std() / p.mean():.2%} (allowed {scatter:.0%})")


def dam(r):
    """Example 4: zero displacements after the geostatic step, the crest moves
    downstream under the reservoir, the joint carries pressure in both steps, and
    the slave node next to the joint tip (10, 4) reports the mean pressure of its
    three neighbours within 10 % (the pressure varies by about 1 % per node there;
    a missing half edge to the tip would double it)."""
    s1, s2 = r["steps"][1], r["steps"][2]
    crest = np.argmax(r["x"][:, 1])
    ratios = []
    for s in (s1, s2):
        c = s["pairs"]["pair_1"]
        near = np.argsort(np.hypot(c["coordinates"][:, 0] - 10.0, c["coordinates"][:, 1] - 4.0))
        ratios.append(c["CPRESS"][near[0]] / np.mean(c["CPRESS"][near[1:4]]))
    ok = (np.abs(s1["U"]).max() == 0 and s2["U"][crest, 0] > 0
          and s1["pairs"]["pair_1"]["CPRESS"].max() > 0 and s2["pairs"]["pair_1"]["CPRESS"].max() > 0
          and all(abs(q - 1) < 0.1 for q in ratios))
    return ok, (f"step 1 max|U| = {np.abs(s1['U']).max():g}, step 2 crest u_x = {s2['U'][crest, 0]:.4e}, "
                f"joint peak pressure {s1['pairs']['pair_1']['CPRESS'].max():.4e} / {s2['pairs']['pair_1']['CPRESS'].max():.4e}, "
                f"next to the tip {ratios[0]:.3f} / {ratios[1]:.3f} times its neighbours")


def block(r):
    """Self-weight block: mean sigma_yy across horizontal cuts = -rho g depth (1 %)."""
    x, off, conn, s = r["x"], r["off"], r["conn"], r["steps"][1]["S_element"]
    worst = 0.0
    for cut in (0.3, 0.5, 0.7):
        num = den = ycen = 0.0
        for e in range(len(off) - 1):
            p = x[conn[off[e]:off[e + 1]]]
            cr = p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]
            a = 0.5 * cr.sum()
            cy = np.sum((p[:, 1] + np.roll(p[:, 1], -1)) * cr) / (6 * a)
            if abs(cy - cut) < 0.05:
                num, den, ycen = num + a * s[e, 1], den + a, ycen + a * cy
        expected = -2400 * 9.81 * (1.0 - ycen / den)
        worst = max(worst, abs(num / den / expected - 1))
    return worst < 0.01, f"section equilibrium at y = 0.3, 0.5, 0.7 within {worst:.3%}"


def dam_base(r, job):
    """Dam on a horizontal base joint (inputs/dam_base_*.inp), step 2 (full reservoir): the
    dam's equilibrium with what the joint reports, N + U = W and the moment of
    (CPRESS + CFLUIDP) * CNAREA about the heel = W (x_c - 4) + H h/3 (the shear, friction
    or the horizontal hold of the penetration variant, acts along the joint: no moment
    about the heel), both within 1e-6 (measured 8e-9); U the guideline's formula evaluated
    at the slave nodes (the uplift variants); every node closed (STATUS closed, stick or
    slip), as the gravity method finds (heel effective stress +50.7 kPa), so the
    penetration variant equals the linear one.  With friction (phi = 35 deg, c = 0) and a
    strength reduction step 3: its factor_of_safety within 0.5 % of (W - U) tan(phi) / H,
    U = sum(CFLUIDP * CNAREA) of step 3."""
    c = r["steps"][2]["pairs"]["pair_1"]
    xy = c["coordinates"] if c["coordinates"].shape[-1] == 2 else c["coordinates"].T
    x = xy[:, 0]
    a = c["CNAREA"]
    uplift = c.get("CFLUIDP", np.zeros_like(a))
    W, xc, H = 24000.0 * 17.5, 4.0 + 13.0 / 7.0, 0.5 * 9810.0 * 25.0   # x_c of the dam polygon
    N, U = np.sum(c["CPRESS"] * a), np.sum(uplift * a)
    M = np.sum((c["CPRESS"] + uplift) * a * (x - 4.0))
    s = np.clip((x - 4.0) / 5.0, 0.0, 1.0)
    if job.endswith("drained"):
        hd = 10.0 + 5.0 / 3.0
        head = np.where(s <= 0.2, 15.0 + (hd - 15.0) * s / 0.2, hd + (10.0 - hd) * (s - 0.2) / 0.8)
    elif job.endswith("dry"):
        head = np.full_like(s, 10.0)
    else:
        head = 15.0 - 5.0 * s
    formula = np.sum(9810.0 * (head - 10.0) * a)
    ok = (abs(N + U - W) < 1e-6 * W and abs(M / (W * (xc - 4.0) + H * 5.0 / 3.0) - 1) < 1e-6
          and abs(U - formula) <= 1e-12 * W and np.isin(c["STATUS"], (1, 3, 4)).all())
    text = (f"N = {N:.6g}, U = {U:.6g} (formula {formula:.6g}), N + U - W = {N + U - W:.3g}, "
            f"moment {M / (W * (xc - 4.0) + H * 5.0 / 3.0) - 1:.2g} relative, "
            f"{int(np.sum(np.isin(c['STATUS'], (1, 3, 4))))} of {len(a)} nodes closed")
    if 3 in r["steps"] and "factor_of_safety" in r["steps"][3]:
        c3 = r["steps"][3]["pairs"]["pair_1"]
        U3 = np.sum(c3.get("CFLUIDP", np.zeros_like(c3["CNAREA"])) * c3["CNAREA"])
        want = (W - U3) * np.tan(np.radians(35.0)) / H
        fs = r["steps"][3]["factor_of_safety"]
        ok = ok and abs(fs / want - 1) <= 5e-3
        text += f"; factor of safety {fs:.6g} against (W - U) tan 35 / H = {want:.6g} ({fs / want - 1:+.1e})"
    return ok, text


def rock_block(r, job):
    """Rock block with a water-filled tension crack (inputs/rock_block_*.inp): the factor
    of safety of step 3 within 1 % of Hoek & Bray's formula, and the joint's resultants
    at F = 1 (the last step before it) equal to the formula's N' and T within 1e-9
    (test_rock_block.py, measured 1e-14)."""
    zw = {"dry": 0.0, "crack3": 3.0, "crack6": 6.0}[job.rsplit("_", 1)[1]]
    xc, xt = 20.0 / np.tan(np.radians(50.0)), 14.0 * np.sqrt(3.0)
    P = np.array([(0.0, 0.0), (xc, 20.0), (xt, 20.0), (xt, 14.0)])
    W = 25000.0 * 0.5 * abs(np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1]))
    V, U = 0.5 * 9810.0 * zw**2, 0.5 * 9810.0 * zw * 28.0
    N, T = W * np.cos(np.pi / 6) - U - V * 0.5, W * 0.5 + V * np.cos(np.pi / 6)
    fs = (20000.0 * 28.0 + N * np.tan(np.radians(35.0))) / T
    last = max(r["steps"])
    F = r["steps"][last]["factor_of_safety"]
    c = r["steps"][last - 1]["pairs"]["pair_1"]
    n_fe, t_fe = np.sum(c["CPRESS"] * c["CNAREA"]), abs(np.sum(c["CSHEAR"] * c["CNAREA"]))
    ok = abs(F / fs - 1) < 0.01 and abs(n_fe / N - 1) < 1e-9 and abs(t_fe / T - 1) < 1e-9
    return ok, f"factor of safety {F:.5f} (Hoek & Bray {fs:.5f}), N' {n_fe / N - 1:.1e}, T {t_fe / T - 1:.1e} relative"


def two_wedge(r, job):
    """Dam on two wedges (inputs/dam_two_wedge_*.inp): the factor of safety against USACE's
    multi-wedge equation on the seam (bench/sliding/limit_equilibrium.py, values copied
    here): dry within 1 % (test_two_wedge.py, measured -0.03 %); wet within 4 %, the
    differences docs/sliding-safety.md explains (water at the kink, the wedge leaning on
    the back joint, how far the water entered; measured +1.7, +0.4 and +3.1 %)."""
    le = {"dry": 2.8896, "uplift": 1.5519, "drained": 2.1724, "penetration": 1.3250}[job.rsplit("_", 1)[1]]
    F = r["steps"][max(r["steps"])]["factor_of_safety"]
    tol = 0.01 if job.endswith("_dry") else 0.04
    return abs(F / le - 1) < tol, f"factor of safety {F:.5f} (USACE multi-wedge {le:.4f}, {F / le - 1:+.2%})"


def check(path):
    job = os.path.basename(path)[:-3]
    r = load(path)
    if job == "example1_cantilever":
        return cantilever(r)
    if job.startswith("hertz_"):
        # 1 % on 1155 elements (test_contact.py::test_hertz_1155); the coarser meshes
        # are not held to a published accuracy: 5 % (they converge towards it)
        # second order (hertz_329_*2): CPE8 and the k = 2 VEM (curved arc sides)
        # within 1 % (test_second_order_contact.py)
        if job.endswith("vem2") or job.endswith("fem2"):
            return hertz(r, 0.01, second_order=True)
        return hertz(r, 0.01 if "_1155_" in job else 0.05)
    if job.startswith("interface_"):
        # 5 % as test_inputs.py asks of the 200-cell mesh; 10 % on the coarsest (50 cells)
        return interface(r, 0.10 if job.endswith("_50") else 0.05)
    if job == "dam_joint":
        return dam(r)
    if job == "block_selfweight":
        return block(r)
    if job.startswith("dam_base_"):
        return dam_base(r, job)
    if job.startswith("rock_block_"):
        return rock_block(r, job)
    if job.startswith("dam_two_wedge_"):
        return two_wedge(r, job)
    return False, "no check known for this deck: add one"


def main(argv):
    folder = argv[1] if len(argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    failed = 0
    for path in sorted(glob.glob(os.path.join(folder, "*.h5"))):
        ok, text = check(path)
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {os.path.basename(path)}: {text}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
