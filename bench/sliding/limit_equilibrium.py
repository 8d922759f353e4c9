"""Limit-equilibrium factors of safety for the sliding-safety scenes (docs/sliding-safety.md),
computed from the geometry alone, to set beside the strength-reduction factors of the runs.

  python bench/sliding/limit_equilibrium.py

- dam on a horizontal base joint (scene dam_base_joint.toml): gravity method, FS = (N' tan phi + c B)/H;
- rock block with a water-filled tension crack (scene rock_block.toml): Hoek & Bray,
  FS = [c A + (W cos psi - U - V sin psi) tan phi] / (W sin psi + V cos psi);
- two wedges under the dam (scene dam_two_wedge.toml): USACE's multi-wedge equation with the
  same F on every sliding base and horizontal interwedge forces (no interwedge shear).  Both
  wedges slide on the same seam (dip 1 in 5), so the common denominator of USACE's equation
  factors out and F is that of the seam as one plane: the interwedge force, with or without
  shear, cancels.  The back joint opens (the wedges move away from it along the seam) and
  carries the water only.

Water: unit weight 9.81 kN/m^3; the uplift on a joint is gamma_w max(0, head - y) with the head
linear in the projection s on the heel-daylight chord (as *UPLIFT computes it); the drained
variant puts tail + (head - tail)/3 at the drain point (USBR); penetration puts the headwater into
the open part from the heel (here: the back joint) and restarts the linear diagram at its end.
"""
from __future__ import annotations

import math

import numpy as np

GW = 9.81           # kN/m^3
GC = 24.0           # dam and rock of the dam scenes, kN/m^3


def polygon(P):
    P = np.asarray(P, float)
    x, y = P[:, 0], P[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    A = 0.5 * cr.sum()
    return abs(A), ((x + x1) * cr).sum() / (6 * A), ((y + y1) * cr).sum() / (6 * A)


# ---------------------------------------------------------------- dam on a horizontal base (F7)
def dam_base(phi=35.0, c=0.0, variant="dry"):
    A, _, _ = polygon([(4, 10), (9, 10), (6, 15), (4, 15)])
    W = GC * A
    H = 0.5 * GW * 5.0 ** 2
    B = 5.0
    p_heel = GW * 5.0
    U = {"dry": 0.0, "uplift": 0.5 * p_heel * B,
         "drained": 0.5 * (p_heel + p_heel / 3) * 1.0 + 0.5 * (p_heel / 3) * (B - 1.0)}[variant]
    return (c * B + (W - U) * math.tan(math.radians(phi))) / H


# ---------------------------------------------------------------- rock block (F8)
ROCK = {"H": 20.0, "face": 50.0, "dip": 30.0, "z": 6.0, "gamma": 25.0}


def rock_block(zw, c=20.0, phi=35.0):
    r = ROCK
    xc = r["H"] / math.tan(math.radians(r["face"]))
    xt = (r["H"] - r["z"]) / math.tan(math.radians(r["dip"]))
    A, _, _ = polygon([(0, 0), (xc, r["H"]), (xt, r["H"]), (xt, r["H"] - r["z"])])
    W = r["gamma"] * A
    Lj = math.hypot(xt, r["H"] - r["z"])
    psi = math.radians(r["dip"])
    V = 0.5 * GW * zw ** 2
    U = 0.5 * GW * zw * Lj
    N = W * math.cos(psi) - U - V * math.sin(psi)
    return (c * Lj + N * math.tan(math.radians(phi))) / (W * math.sin(psi) + V * math.cos(psi))


# ---------------------------------------------------------------- two wedges (issue 24 item 3)
HEEL, KINK, SPLIT, DAYLIGHT = np.array([4.0, 10.0]), np.array([5.0, 8.0]), np.array([9.5, 7.1]), np.array([12.0, 6.6])
HEAD, TAIL = 15.0, 6.6


def _s(x):
    d = DAYLIGHT - HEEL
    return float(np.dot(x - HEEL, d) / np.dot(d, d))


def _water_force(a, b, head_of, n=4000):
    """Force of the water pressure gamma_w max(0, head(x) - y) along the segment a-b on the
    body lying to the left of a->b (the pressure pushes into it); midpoint rule, n cells."""
    t = (b - a) / np.linalg.norm(b - a)
    nin = np.array([-t[1], t[0]])                     # left normal: into the body on the left
    L = np.linalg.norm(b - a)
    xi = (np.arange(n) + 0.5) / n                      # midpoint rule, n cells
    pts = a[None, :] + xi[:, None] * (b - a)[None, :]
    p = GW * np.maximum(0.0, np.array([head_of(q) for q in pts]) - pts[:, 1])
    return p.sum() * L / n * nin


def _arc(x):
    """Arc length from the heel along the back joint and the seam of the point x on them."""
    lb = float(np.linalg.norm(KINK - HEEL))
    if _s(x) <= _s(KINK):
        return float(np.linalg.norm(x - HEEL))
    return lb + float(np.linalg.norm(x - KINK))


def two_wedge(variant="dry", phi=45.0, c=0.0, crack=None):
    """F of the dam + both wedges sliding on the seam (back joint open, water in it).
    `crack`: for the penetration variant, the length from the heel (arc length) that
    carries the headwater (default: the back joint, sqrt 5)."""
    Ad, _, _ = polygon([(4, 10), (9, 10), (6, 15), (4, 15)])
    Au, _, _ = polygon([HEEL, KINK, SPLIT, (9.5, 10.0), (9.0, 10.0)])
    Ab, _, _ = polygon([SPLIT, DAYLIGHT, (12.0, 10.0), (9.5, 10.0)])
    W = GC * (Ad + Au + Ab)
    R = np.array([0.5 * GW * 5.0 ** 2, -W])         # reservoir on the upstream face, weight
    lin = lambda x: HEAD + (TAIL - HEAD) * _s(x)      # noqa: E731
    if variant == "drained":
        sd, hd = _s(KINK), TAIL + (HEAD - TAIL) / 3.0

        def head(x):
            s = _s(x)
            return HEAD + (hd - HEAD) * s / sd if s <= sd else hd + (TAIL - hd) * (s - sd) / (1.0 - sd)
    elif variant == "penetration":
        a = float(np.linalg.norm(KINK - HEEL)) if crack is None else crack
        lb = float(np.linalg.norm(KINK - HEEL))
        tip = HEEL + (KINK - HEEL) * a / lb if a <= lb else KINK + (DAYLIGHT - KINK) * (a - lb) / np.linalg.norm(
            DAYLIGHT - KINK)
        sk = _s(tip)

        def head(x):
            s = _s(x)
            return HEAD if _arc(x) <= a else HEAD + (TAIL - HEAD) * (s - sk) / (1.0 - sk)
    else:
        head = lin
    if variant != "dry":
        # walking the joint from the heel to the daylight, the wedges lie on the left
        R = R + _water_force(HEEL, KINK, head) + _water_force(KINK, DAYLIGHT, head)
    t = (DAYLIGHT - KINK) / np.linalg.norm(DAYLIGHT - KINK)       # down-dip, downstream
    n = np.array([-t[1], t[0]])                                     # out of the seam, into the wedges
    N = -float(R @ n)
    T = float(R @ t)
    Ls = float(np.linalg.norm(DAYLIGHT - KINK))
    return (c * Ls + N * math.tan(math.radians(phi))) / T, {"W": W, "N": N, "T": T}


def main():
    print("dam on a horizontal base joint, phi 35 (gravity method):")
    for v in ("dry", "uplift", "drained"):
        print(f"  {v:12s} c = 0: {dam_base(variant=v):.4f}   c = 100 kPa: {dam_base(c=100.0, variant=v):.4f}")
    print("rock block, phi 35:")
    for zw in (0.0, 3.0, 6.0):
        print(f"  zw = {zw:3.1f}  c = 20 kPa: {rock_block(zw):.4f}   c = 0: {rock_block(zw, c=0.0):.4f}")
    for phi in (45.0, 35.0):
        print(f"two wedges on the seam, phi {phi:g}, c = 0 (USACE multi-wedge, same F on every base):")
        for v in ("dry", "uplift", "drained", "penetration"):
            F, d = two_wedge(v, phi)
            print(f"  {v:12s} F = {F:.4f}   (W = {d['W']:.2f} kN, N' = {d['N']:.2f} kN, T = {d['T']:.2f} kN)")
        # the run's crack: its last open node lies 2.0942 m along the back joint from the
        # heel (the log's "water entered 1.59462" is that node's projection on the chord)
        F, d = two_wedge("penetration", phi, crack=2.0942)
        print(f"  penetration, headwater over the run's 2.094 m from the heel: F = {F:.4f} (N' = {d['N']:.2f} kN)")


if __name__ == "__main__":
    main()
