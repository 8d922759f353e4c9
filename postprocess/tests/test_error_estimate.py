"""The a posteriori error estimate (src/post/estimate.f90, docs/error-estimate.md) against
the true energy-norm error on cases with known answers: the effectivity index (estimate /
true error) must lie in [0.5, 3].  Observed (docs/error-estimate.md): 0.93-1.22 over the
manufactured solution, the Timoshenko cantilever and the Lame cylinder on Voronoi cells,
VEM quads and CST triangles; these tests run the smallest meshes of
bench/accuracy (their decks and exact fields) in a few seconds."""
import math
import os
import subprocess
import sys

import h5py
import meshio
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "accuracy"))
import cases  # noqa: E402
import fields  # noqa: E402


def true_energy_error(res, case):
    """sqrt(sum_e int_e (s_h - s)^T C^-1 (s_h - s)), exact for the polynomial stresses
    (fields.energy_error's quadrature, not divided by the norm of s)."""
    elem, A, B, Cc, area = fields._fan(res["x"], res["off"], res["conn"])
    S = fields.compliance(case.E, case.nu, case.plane)
    sh = res["Se"][:, [0, 1, 3]][elem]
    num = 0.0
    for q in ((A + B) / 2, (B + Cc) / 2, (Cc + A) / 2):
        d = sh - case.sigma(q[:, 0], q[:, 1])
        num += (area / 3 * np.einsum("ij,jk,ik->i", d, S, d)).sum()
    return math.sqrt(num)


def _runs(tmp_path, exe, name, family, levels):
    work = str(tmp_path)
    os.makedirs(work + "/decks", exist_ok=True)
    for run in cases.CASES[name](work, quick=True, families=(family,)):
        if run.family != family or run.level not in levels:
            continue
        deck = f"{work}/decks/{name}_{family}_{run.level}.inp"
        with open(deck, "w") as f:
            f.write(run.deck)
        r = subprocess.run([exe, "-q", deck, "-o", work + "/out"], capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
        yield run, f"{work}/out/{name}_{family}_{run.level}"


@pytest.mark.parametrize("name,family,levels", [
    ("manufactured", "vem-voronoi", (8, 16)),
    ("manufactured", "fem-tri", (8,)),
    ("timoshenko", "vem-voronoi", (4, 8)),
    ("timoshenko", "vem-quad", (4,)),
])
def test_effectivity(tmp_path, exe, name, family, levels):
    case = {"manufactured": fields.Manufactured, "timoshenko": fields.Timoshenko}[name]()
    seen = 0
    for run, base in _runs(tmp_path, exe, name, family, levels):
        res = fields.read_result(base + ".h5")
        with h5py.File(base + ".h5") as f:
            step = f["steps/0001"]
            eta = step["ERROR_INDICATOR"][...]
            est, energy = step.attrs["error_estimate"], step.attrs["energy_norm"]
        assert eta.shape == (len(res["off"]) - 1,)
        assert (eta >= 0).all()
        # the estimate is the root of the sum of the squared indicators (round-off only)
        assert est == pytest.approx(math.sqrt((eta ** 2).sum()), rel=1e-12)
        # the energy norm of the discrete stress: sum of area * s_h^T C^-1 s_h, independent here
        elem, A, B, Cc, area = fields._fan(res["x"], res["off"], res["conn"])
        ea = np.bincount(elem, area)
        sh = res["Se"][:, [0, 1, 3]]
        S = fields.compliance(case.E, case.nu, case.plane)
        assert energy == pytest.approx(math.sqrt((ea * np.einsum("ij,jk,ik->i", sh, S, sh)).sum()), rel=1e-10)
        eff = est / true_energy_error(res, case)
        assert 0.5 <= eff <= 3.0, f"{name} {family} {run.level}: effectivity {eff:.3f}"
        # the VTU carries the same indicator as cell data
        m = meshio.read(base + "_0001.vtu")
        # meshio splits the polygons into blocks of equal node count, in file order
        np.testing.assert_array_equal(np.concatenate(m.cell_data["ERROR_INDICATOR"]), eta)
        seen += 1
    assert seen == len(levels)


def test_effectivity_on_graded_mesh(tmp_path, exe):
    """The manufactured case on a strongly graded Voronoi mesh (cells 10 times smaller at a
    corner than far from it, as adapted meshes are; area ratio about 100): effectivity in [0.5, 3] (observed 0.999)."""
    import meshes
    case = fields.Manufactured()
    text = ('[mesh]\nseed = 7\nlloyd = 20\nformulation = "vem"\nplane = "strain"\n\n[[body]]\nname = "B"\n'
            'rectangle = [0.0, 0.0, 1.0, 1.0]\nmesher = "voronoi"\ncells = 300\n'
            'grading = [ { point = [0.0, 0.0], ratio = 0.1, radius = 0.8 } ]\n')
    mp = meshes.mesher(text, "graded", str(tmp_path))
    m = meshes.read_inp(mp)
    b = case.body_force()
    g, d = float(np.linalg.norm(b)), b / np.linalg.norm(b)
    u = case.u(m.xy[:, 0], m.xy[:, 1])
    lines = [f"*INCLUDE, INPUT={mp}", "*MATERIAL, NAME=M", "*ELASTIC", f"{float(case.E)!r}, {float(case.nu)!r}", "*DENSITY", "1.0",
             "*SOLID SECTION, ELSET=B, MATERIAL=M", "1.0", "*BOUNDARY"]
    for k, i in enumerate(m.ids):
        x, y = m.xy[k]
        if min(x, y, 1 - x, 1 - y) < 1e-9:
            lines += [f"{i}, 1, 1, {float(u[k, 0])!r}", f"{i}, 2, 2, {float(u[k, 1])!r}"]
    lines += ["*STEP", "*STATIC", "*DLOAD", f"B, GRAV, {float(g)!r}, {float(d[0])!r}, {float(d[1])!r}", "*END STEP"]
    deck = tmp_path / "graded_deck.inp"
    deck.write_text("\n".join(lines) + "\n")
    r = subprocess.run([exe, "-q", str(deck), "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    res = fields.read_result(str(tmp_path / "out" / "graded_deck.h5"))
    _, _, _, _, area = fields._fan(res["x"], res["off"], res["conn"])
    elem = fields._fan(res["x"], res["off"], res["conn"])[0]
    ea = np.bincount(elem, area)
    assert ea.max() / ea.min() > 30                      # graded indeed (about 100 in area)
    with h5py.File(tmp_path / "out" / "graded_deck.h5") as f:
        est = f["steps/0001"].attrs["error_estimate"]
    eff = est / true_energy_error(res, case)
    print(f"graded: {len(ea)} cells, area ratio {ea.max() / ea.min():.0f}, effectivity {eff:.3f}")
    assert 0.5 <= eff <= 3.0, eff
