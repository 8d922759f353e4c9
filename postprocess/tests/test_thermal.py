"""Thermal strains (*INITIAL CONDITIONS, TYPE=TEMPERATURE, *TEMPERATURE, *EXPANSION):
against closed-form thermal stresses (constrained bar and plate, plane stress and plane
strain), the stress-free patch test of a free plate under a linear temperature (exact
for the second-order elements, whose displacement is then the exact quadratic field),
and CalculiX run on the same deck (when ccx is installed)."""
import shutil
import subprocess

import h5py
import numpy as np
import pytest

E, NU, ALPHA, T0, T1 = 1000.0, 0.25, 1e-3, 20.0, 70.0
L, H, NX, NY = 3.0, 2.0, 3, 2


def grid(order):
    """Nodes {id: (x, y)} and elements (lists of node ids, corners then side nodes) of
    an NX x NY mesh of L x H; second order with a node in the middle of every side."""
    nodes, idx = {}, {}
    step = 2 if order == 2 else 1
    for j in range(NY * step + 1):
        for i in range(NX * step + 1):
            if order == 2 and i % 2 == 1 and j % 2 == 1:
                continue
            idx[i, j] = len(nodes) + 1
            nodes[idx[i, j]] = (L * i / (NX * step), H * j / (NY * step))
    elems = []
    for j in range(NY):
        for i in range(NX):
            a, b = i * step, j * step
            c = [idx[a, b], idx[a + step, b], idx[a + step, b + step], idx[a, b + step]]
            if order == 2:
                c += [idx[a + 1, b], idx[a + 2, b + 1], idx[a + 1, b + 2], idx[a, b + 1]]
            elems.append(c)
    return nodes, elems


def deck(etype, order, boundary, temperature, plane_strain):
    nodes, elems = grid(order)
    lines = ["*NODE, NSET=ALL"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in nodes.items()]
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=E")
    lines += [", ".join(str(v) for v in [e + 1] + c) for e, c in enumerate(elems)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}",
              "*SOLID SECTION, ELSET=E, MATERIAL=M", "0.5" if not plane_strain else "1.",
              "*INITIAL CONDITIONS, TYPE=TEMPERATURE", f"ALL, {T0}", "*BOUNDARY"]
    lines += [f"{k}, {d}, {d}, {v!r}" for k, (x, y) in nodes.items() for d, v in boundary(x, y)]
    lines += ["*STEP", "*STATIC", "*TEMPERATURE"]
    lines += [f"{k}, {temperature(x, y)!r}" for k, (x, y) in nodes.items()]
    lines += ["*NODE FILE", "U", "*EL FILE", "S, E", "*NODE PRINT, NSET=ALL", "U", "*END STEP"]
    return "\n".join(lines) + "\n", nodes


def run(exe, tmp_path, name, text):
    (tmp_path / f"{name}.inp").write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), f"{name}.inp"], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    with h5py.File(tmp_path / f"{name}.h5") as f:
        g = f["steps/0001"]
        return (dict(zip(f["mesh/node_ids"][...].tolist(), g["U"][...])), g["S_element"][...],
                g["S_node"][...], g["E_element"][...])


TYPES = [("VPS", 1, False), ("CPS4", 1, False), ("CPS8", 2, False), ("CPS8R", 2, False),
         ("VPS2", 2, False), ("VPE", 1, True), ("CPE4", 1, True), ("CPE8", 2, True),
         ("CPE8R", 2, True), ("VPE2", 2, True)]


@pytest.mark.parametrize("etype, order, pe", TYPES)
def test_constrained_bar(exe, tmp_path, etype, order, pe):
    """u_x = 0 at both ends, free in y (one node held): S_xx = -E alpha dT in plane
    stress, -E alpha dT / (1 - nu) in plane strain (eps_zz = 0, S_zz = S_xx there)."""
    dt = T1 - T0
    def bc(x, y):
        out = [(1, 0.0)] if x in (0.0, L) else []
        return out + ([(2, 0.0)] if (x, y) == (0.0, 0.0) else [])
    text, _ = deck(etype, order, bc, lambda x, y: T1, pe)
    _, s, sn, eps = run(exe, tmp_path, "bar", text)
    sxx = -E * ALPHA * dt / (1 - NU) if pe else -E * ALPHA * dt
    # a uniform state every element reproduces: round-off of the solve, 1e-10
    assert np.allclose(s[:, 0], sxx, rtol=1e-10)
    assert np.allclose(s[:, 1], 0, atol=1e-10 * abs(sxx))
    assert np.allclose(s[:, 2], sxx if pe else 0.0, rtol=1e-10, atol=1e-10 * abs(sxx))
    assert np.allclose(sn[:, 0], sxx, rtol=1e-10)
    # the total strain: eps_xx = 0; eps_yy from Hooke's law in 3D with S_yy = 0,
    # eps_yy = -nu (S_xx + S_zz) / E + alpha dT
    eyy = (-NU * sxx - NU * (sxx if pe else 0.0)) / E + ALPHA * dt
    assert np.allclose(eps[:, 0], 0, atol=1e-10 * abs(eyy))
    assert np.allclose(eps[:, 1], eyy, rtol=1e-10)


@pytest.mark.parametrize("etype, order, pe", [t for t in TYPES if t[2]])
def test_fully_constrained_plane_strain(exe, tmp_path, etype, order, pe):
    """Every node held: S_xx = S_yy = S_zz = -E alpha dT / (1 - 2 nu), the 3D result."""
    text, _ = deck(etype, order, lambda x, y: [(1, 0.0), (2, 0.0)], lambda x, y: T1, pe)
    _, s, _, _ = run(exe, tmp_path, "plate", text)
    ref = -E * ALPHA * (T1 - T0) / (1 - 2 * NU)
    assert np.allclose(s[:, :3], ref, rtol=1e-10)


@pytest.mark.parametrize("etype", ["CPS8", "VPS2", "CPS8R"])
def test_free_plate_linear_temperature_is_stress_free(exe, tmp_path, etype):
    """dT = a + b x + c y on a free plate (plane stress) strains it without stress;
    u = alpha (a x + b (x^2 - y^2)/2 + c x y), v = alpha (a y + c (y^2 - x^2)/2 + b x y)
    is quadratic, so the second-order elements reproduce it exactly.  Supports: the
    exact field at (0, 0) (zero) and at (L, 0) in y."""
    a, b, c = 30.0, 12.0, -7.0
    def temp(x, y):
        return T0 + a + b * x + c * y
    def exact(x, y):
        return (ALPHA * (a * x + b * (x * x - y * y) / 2 + c * x * y),
                ALPHA * (a * y + c * (y * y - x * x) / 2 + b * x * y))
    def bc(x, y):
        if (x, y) == (0.0, 0.0):
            return [(1, 0.0), (2, 0.0)]
        if (x, y) == (L, 0.0):
            return [(2, exact(x, y)[1])]
        return []
    text, nodes = deck(etype, 2, bc, temp, False)
    u, s, sn, _ = run(exe, tmp_path, "free", text)
    umax = max(np.hypot(*exact(x, y)) for x, y in nodes.values())
    smax = E * ALPHA * max(abs(temp(x, y) - T0) for x, y in nodes.values())
    # 1e-9 of the stress a constrained plate would carry, 1e-10 of the largest displacement
    assert np.abs(s).max() < 1e-9 * smax
    assert np.abs(sn).max() < 1e-9 * smax
    for k, (x, y) in nodes.items():
        assert np.allclose(u[k], exact(x, y), rtol=0, atol=1e-10 * umax), k


def ccx_displacements(dat):
    out, block = {}, False
    for line in dat.read_text().splitlines():
        if line.startswith(" displacements"):
            block, out = True, {}
        elif line.strip() and block:
            w = line.split()
            out[int(w[0])] = (float(w[1]), float(w[2]))
    return out


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) is not installed")
@pytest.mark.parametrize("etype, order", [("CPE4", 1), ("CPE8", 2), ("CPS4", 1), ("CPS8", 2)])
def test_against_calculix(exe, tmp_path, etype, order):
    """A plate held on x = 0, under dT linear in x and y.  Plane strain: ccx (which
    expands plane elements into one-layer bricks held in z) and vemcontact agree to
    ccx's printed digits (7: 5e-7 relative, 2e-6 allowed), CPE4 with the element's mean
    temperature as ccx's linear elements take it, CPE8 with the linear field.  Plane
    stress: ccx's brick has a free out-of-plane displacement that the in-plane
    temperature gradient makes vary in x and y, which adds transverse shear the 2D
    element does not have (the formulation difference of planestress3, docs/
    calculix-comparison.md): measured 5.9e-3 (CPS4) and 2.4e-3 (CPS8), bounded by 1e-2."""
    pe = etype.startswith("CPE")
    def bc(x, y):
        return [(1, 0.0), (2, 0.0)] if x == 0.0 else []
    text, nodes = deck(etype, order, bc, lambda x, y: T0 + 40.0 + 15.0 * x - 10.0 * y, pe)
    ours, _, _, _ = run(exe, tmp_path, "th", text)
    work = tmp_path / "ccx"
    work.mkdir()
    (work / "th.inp").write_text(text)
    r = subprocess.run(["ccx", "-i", "th"], cwd=work, capture_output=True, text=True,
                       env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
    assert r.returncode == 0, r.stdout[-2000:]
    ref = ccx_displacements(work / "th.dat")
    keys = sorted(ref)
    a = np.array([ref[k] for k in keys])
    b = np.array([ours[k] for k in keys])
    tol = 2e-6 if pe else 1e-2
    assert np.abs(a - b).max() <= tol * np.abs(a).max()
