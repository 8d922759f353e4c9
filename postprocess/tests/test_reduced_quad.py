"""CPE8R/CPS8R (reduced 2 x 2 integration of the 8-node quad) against CalculiX run on the
same deck: a cantilever of 6 x 2 elements under an end shear, a stress field that is far
from uniform (bending), where reduced and full integration differ.  ccx expands the
element into a one-layer C3D20R brick with the same in-plane rule, so in plane strain
the displacements agree to ccx's printed digits; the full-integration CPE8 is stiffer,
which the test checks too (reduced integration is softer in bending)."""
import shutil
import subprocess

import h5py
import numpy as np
import pytest

NX, NY, L, H = 6, 2, 6.0, 1.0


def deck(etype):
    ids, nodes = {}, {}
    for j in range(2 * NY + 1):
        for i in range(2 * NX + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            ids[i, j] = len(nodes) + 1
            nodes[ids[i, j]] = (L * i / (2 * NX), H * j / (2 * NY))
    lines = ["*NODE, NSET=ALL"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in nodes.items()]
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=E")
    e = 0
    for j in range(NY):
        for i in range(NX):
            a, b = 2 * i, 2 * j
            c = [ids[a, b], ids[a + 2, b], ids[a + 2, b + 2], ids[a, b + 2],
                 ids[a + 1, b], ids[a + 2, b + 1], ids[a + 1, b + 2], ids[a, b + 1]]
            e += 1
            lines.append(", ".join(str(v) for v in [e] + c))
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", "1000., 0.3", "*SOLID SECTION, ELSET=E, MATERIAL=M", "1.",
              "*BOUNDARY"]
    lines += [f"{k}, 1, 2" for k, (x, y) in nodes.items() if x == 0.0]
    lines += ["*STEP", "*STATIC", "*CLOAD"]
    # end shear -1 as consistent loads of a quadratic side (1/6, 4/6, 1/6 per element side)
    tip = sorted((y, k) for k, (x, y) in nodes.items() if x == L)
    for n, (_, k) in enumerate(tip):
        w = (1 / 6 if n in (0, len(tip) - 1) else (2 / 6 if n % 2 == 0 else 4 / 6)) / NY
        lines.append(f"{k}, 2, {-w!r}")
    lines += ["*NODE PRINT, NSET=ALL", "U", "*NODE FILE", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def ours(exe, tmp_path, etype):
    (tmp_path / f"{etype}.inp").write_text(deck(etype))
    r = subprocess.run([exe, "-o", str(tmp_path), f"{etype}.inp"], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    with h5py.File(tmp_path / f"{etype}.h5") as f:
        return dict(zip(f["mesh/node_ids"][...].tolist(), f["steps/0001/U"][...]))


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) is not installed")
def test_cpe8r_equals_calculix(exe, tmp_path):
    u = ours(exe, tmp_path, "CPE8R")
    work = tmp_path / "ccx"
    work.mkdir()
    (work / "c.inp").write_text(deck("CPE8R"))
    r = subprocess.run(["ccx", "-i", "c"], cwd=work, capture_output=True, text=True,
                       env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
    assert r.returncode == 0, r.stdout[-2000:]
    ref, block = {}, False
    for line in (work / "c.dat").read_text().splitlines():
        if line.startswith(" displacements"):
            block = True
        elif block and line.strip():
            w = line.split()
            ref[int(w[0])] = (float(w[1]), float(w[2]))
    keys = sorted(ref)
    a = np.array([ref[k] for k in keys])
    b = np.array([u[k] for k in keys])
    # ccx prints 7 significant digits: 5e-7 of a value, 2e-6 allowed (measured 6.2e-8)
    assert np.abs(a - b).max() <= 2e-6 * np.abs(a).max()


def test_reduced_is_softer_than_full(exe, tmp_path):
    """The tip deflection of CPE8R exceeds CPE8's (fewer constraints on bending modes):
    measured by 0.46 % on this mesh; both within 10 % of each other."""
    ur = ours(exe, tmp_path, "CPE8R")
    uf = ours(exe, tmp_path, "CPE8")
    tip = max(ur, key=lambda k: abs(ur[k][1]))
    assert abs(ur[tip][1]) > abs(uf[tip][1])
    assert abs(ur[tip][1]) < 1.1 * abs(uf[tip][1])
