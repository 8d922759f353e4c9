"""Abaqus/CAE-style decks (tests/data/abaqus_cae: *PREPRINT, *PART, *ASSEMBLY, *INSTANCE
with translation and rotation, instance-qualified set names, *RESTART, *EQUATION between
instances) run, and equal the same models written flat (no parts), which this file builds
on its own: the instance's translation and rotation applied here with numpy, the tied
nodes of two instances merged.  Compared node by node at equal coordinates."""
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

DATA = Path(__file__).resolve().parents[2] / "tests" / "data" / "abaqus_cae"


def run(exe, path, out):
    r = subprocess.run([exe, "-o", str(out), path.name], cwd=path.parent, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    return r


def by_coordinates(h5):
    """{(x, y) rounded: U} (tied coincident nodes have the same U)."""
    with h5py.File(h5) as f:
        x = f["mesh/coordinates"][...]
        u = f["steps/0001/U"][...]
    return {tuple(np.round(c, 9)): v for c, v in zip(x, u)}


def flat_deck(nodes, elements, rest):
    lines = ["*NODE"] + [f"{i}, {float(x)!r}, {float(y)!r}" for i, (x, y) in nodes.items()]
    for etype, elset, conn in elements:
        lines.append(f"*ELEMENT, TYPE={etype}, ELSET={elset}")
        lines += [", ".join(str(v) for v in c) for c in conn]
    return "\n".join(lines) + "\n" + rest


def compare(tmp_path, exe, name, flat_text):
    (tmp_path / "cae").mkdir()
    (tmp_path / "flat").mkdir()
    r = run(exe, DATA / f"{name}.inp", tmp_path / "cae")
    log = r.stdout + r.stderr
    assert "*PREPRINT is accepted and ignored" in log and "*RESTART is accepted and ignored" in log
    flat = tmp_path / "flat" / f"{name}.inp"
    flat.write_text(flat_text)
    run(exe, flat, tmp_path / "flat")
    a = by_coordinates(tmp_path / "cae" / f"{name}.h5")
    b = by_coordinates(tmp_path / "flat" / f"{name}.h5")
    assert set(a) == set(b)
    scale = max(np.abs(v).max() for v in b.values())
    assert scale > 0
    # the same equations in another dof order (instances renumber the nodes, *EQUATION
    # instead of merged nodes): round-off of a well-conditioned system
    for k in b:
        assert np.allclose(a[k], b[k], rtol=0, atol=1e-11 * scale), k


def test_cae_plate(exe, tmp_path):
    nodes = {i + 1: (float(i % 4), float(i // 4)) for i in range(8)}
    rest = """*NSET, NSET=FIX
1, 5
*NSET, NSET=TIP
4, 8
*ELSET, ELSET=ALL, GENERATE
1, 3, 1
*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL
0.5
*STEP
*STATIC
*BOUNDARY
FIX, 1, 2
*CLOAD
TIP, 2, -5.
8, 1, 2.
*END STEP
"""
    compare(tmp_path, exe, "cae_plate", flat_deck(
        nodes, [("CPS4", "ALL", [[1, 1, 2, 6, 5], [2, 2, 3, 7, 6], [3, 3, 4, 8, 7]])], rest))


def test_cae_rotated(exe, tmp_path):
    """Beam-1 is the part translated by (10, 5), then turned by 90 degrees about the z axis
    through (10, 5): local (x, y) -> (10 - y, 5 + x)."""
    local = {1: (0, 0), 2: (2, 0), 3: (4, 0), 4: (6, 0), 5: (0, 1), 6: (2, 1), 7: (4, 1), 8: (6, 1)}
    t = np.array([10.0, 5.0])
    c, s = np.cos(np.pi / 2), np.sin(np.pi / 2)
    rot = np.array([[c, -s], [s, c]])
    nodes = {i: tuple(rot @ (np.array(p, float) + t - t) + t) for i, p in local.items()}
    assert np.allclose(nodes[4], (10.0, 11.0)) and np.allclose(nodes[5], (9.0, 5.0))
    # counter-clockwise order is kept by a rotation
    rest = """*MATERIAL, NAME=C
*ELASTIC
30000., 0.2
*SOLID SECTION, ELSET=B, MATERIAL=C
1.
*STEP
*STATIC
*BOUNDARY
1, 1, 2
5, 1, 2
*CLOAD
4, 1, 10.
8, 1, 10.
*END STEP
"""
    compare(tmp_path, exe, "cae_rotated", flat_deck(
        nodes, [("CPE4", "B", [[1, 1, 2, 6, 5], [2, 2, 3, 7, 6], [3, 3, 4, 8, 7]])], rest))


def test_cae_two_parts_tied_equal_merged(exe, tmp_path):
    """Left (two CPE4) and Right (one CPE8R, translated by 1 in x) tied by six *EQUATION
    lines equal one mesh in which the coincident nodes are shared."""
    nodes = {1: (0, 0), 2: (1, 0), 3: (0, 1), 4: (1, 1), 5: (0, 2), 6: (1, 2),
             # Right's nodes 2, 4, 5, 6, 7 (its 1, 3, 8 are Left's 2, 6, 4)
             12: (3, 0), 14: (3, 2), 15: (2, 0), 16: (3, 1), 17: (2, 2)}
    nodes = {i: (float(x), float(y)) for i, (x, y) in nodes.items()}
    rest = """*MATERIAL, NAME=R
*ELASTIC
5000., 0.25
*SOLID SECTION, ELSET=L, MATERIAL=R
*SOLID SECTION, ELSET=RR, MATERIAL=R
*STEP
*STATIC
*BOUNDARY
1, 1, 2
2, 1, 2
15, 2
12, 2
*CLOAD
14, 1, -4.
16, 1, -4.
*END STEP
"""
    compare(tmp_path, exe, "cae_two_parts", flat_deck(
        nodes, [("CPE4", "L", [[1, 1, 2, 4, 3], [2, 3, 4, 6, 5]]),
                ("CPE8R", "RR", [[3, 2, 12, 14, 6, 15, 16, 17, 4]])], rest))


@pytest.mark.parametrize("change, phrase", [
    ("*Instance, name=Plate-1, part=Plate\n", "part PLATE has no *INSTANCE"),
    ("part=Plate", "undefined part NOPART"),
])
def test_cae_errors(exe, tmp_path, change, phrase):
    text = (DATA / "cae_plate.inp").read_text()
    if change.startswith("*Instance"):
        text = text.replace(change, "").replace("*End Instance\n", "").replace(
            "*Nset, nset=TopTip, instance=Plate-1\n 8,\n", "").replace("TopTip, 1, 2.\n", "")
    else:
        text = text.replace(change, "part=NoPart")
    p = tmp_path / "bad.inp"
    p.write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), p.name], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode != 0
    assert phrase in r.stdout + r.stderr
    assert "Traceback" not in r.stderr
