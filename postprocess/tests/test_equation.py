"""*EQUATION (linear multi-point constraints, CalculiX's meaning: the first term's dof
is dependent and eliminated).  Independent check: two blocks whose interface nodes are
duplicated and tied by u_a - u_b = 0 in both directions give the displacements of the
same model with the nodes merged, to round-off; a non-unit coefficient gives the
prescribed ratio; bad equations are refused with file:line."""
import subprocess

import h5py
import numpy as np

HEAD = """*NODE
1, 0., 0.
2, 1., 0.
3, 1., 1.
4, 0., 1.
5, 2., 0.
6, 2., 1.
"""
# block 2's left nodes are 12, 13 at the same places as 2, 3 (tied) or 2, 3 (merged)
TIED_NODES = "12, 1., 0.\n13, 1., 1.\n"


def deck(tied, elem2="VPE", extra=""):
    b = "12, 5, 6, 13" if tied else "2, 5, 6, 3"
    text = HEAD + (TIED_NODES if tied else "")
    text += f"""*ELEMENT, TYPE=CPE4, ELSET=E1
1, 1, 2, 3, 4
*ELEMENT, TYPE={elem2}, ELSET=E2
2, {b}
*MATERIAL, NAME=M
*ELASTIC
1000., 0.3
*SOLID SECTION, ELSET=E1, MATERIAL=M
*SOLID SECTION, ELSET=E2, MATERIAL=M
"""
    if tied:
        # CalculiX's format: number of terms, then node, dof, coefficient triples
        text += "*EQUATION\n2\n12, 1, 1., 2, 1, -1.\n2\n12, 2, 1., 2, 2, -1.\n"
        text += "2\n13, 1, 1.\n3, 1, -1.\n2\n13, 2, 1., 3, 2, -1.\n"
    text += extra
    text += """*BOUNDARY
1, 1, 2
4, 1
*STEP
*STATIC
*CLOAD
5, 1, 3.
6, 1, 1.
6, 2, -2.
*NODE FILE
U, RF
*END STEP
"""
    return text


def run(exe, tmp_path, name, text):
    p = tmp_path / f"{name}.inp"
    p.write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), p.name], cwd=tmp_path, capture_output=True, text=True)
    return r


def displacements(tmp_path, name):
    with h5py.File(tmp_path / f"{name}.h5") as f:
        ids = f["mesh/node_ids"][...].tolist()
        u = f["steps/0001/U"][...]
        rf = f["steps/0001/RF"][...]
    return dict(zip(ids, u)), dict(zip(ids, rf))


def test_tied_nodes_equal_merged_nodes(exe, tmp_path):
    for elem2 in ("VPE", "CPE4"):
        r1 = run(exe, tmp_path, f"merged_{elem2}", deck(False, elem2))
        r2 = run(exe, tmp_path, f"tied_{elem2}", deck(True, elem2))
        assert r1.returncode == 0, r1.stdout + r1.stderr
        assert r2.returncode == 0, r2.stdout + r2.stderr
        um, rm = displacements(tmp_path, f"merged_{elem2}")
        ut, rt = displacements(tmp_path, f"tied_{elem2}")
        scale = max(np.abs(v).max() for v in um.values())
        # the same equations solved by Cholesky in a different order: round-off,
        # 1e-12 of the largest displacement (condition number of the tiny system ~1e2)
        for n in um:
            assert np.allclose(ut[n], um[n], rtol=0, atol=1e-12 * scale), n
        assert np.allclose(ut[12], ut[2], rtol=0, atol=1e-14 * scale)
        assert np.allclose(ut[13], ut[3], rtol=0, atol=1e-14 * scale)
        # the support reactions balance the loads (3 + 1 in x, -2 in y) in both
        for rf in (rm, rt):
            total = sum(rf.values())
            assert np.allclose(total, [-4.0, 2.0], rtol=1e-12)


def test_coefficient_gives_the_ratio(exe, tmp_path):
    """2 u6y + u5y = 0 (dependent 6y): node 6 moves half as much as 5, the other way."""
    extra = "*EQUATION\n2\n6, 2, 2., 5, 2, 1.\n"
    r = run(exe, tmp_path, "ratio", deck(False, "CPE4", extra))
    assert r.returncode == 0, r.stdout + r.stderr
    u, _ = displacements(tmp_path, "ratio")
    assert abs(u[5][1]) > 0
    assert np.isclose(u[6][1], -0.5 * u[5][1], rtol=1e-13)


def test_bad_equations_are_refused(exe, tmp_path):
    cases = {
        "dof3": ("*EQUATION\n2\n6, 3, 1., 5, 3, -1.\n", "a 2D model has dofs 1 (x) and 2 (y)"),
        "zero": ("*EQUATION\n2\n6, 2, 0., 5, 2, -1.\n", "needs a non-zero coefficient"),
        "short": ("*EQUATION\n3\n6, 2, 1., 5, 2, -1.\n", "the equation has 3 terms, found 2"),
        "fixed": ("*EQUATION\n2\n1, 1, 1., 5, 1, -1.\n", "is also prescribed by *BOUNDARY"),
        "twice": ("*EQUATION\n2\n6, 2, 1., 5, 2, -1.\n2\n6, 2, 1., 2, 2, -1.\n",
                  "is dependent in two equations"),
        "undefined": ("*EQUATION\n2\n6, 2, 1., 99, 2, -1.\n", "undefined node 99"),
    }
    for name, (extra, phrase) in cases.items():
        r = run(exe, tmp_path, name, deck(False, "CPE4", extra))
        assert r.returncode != 0, name
        out = r.stdout + r.stderr
        assert phrase in out, (name, out)
        assert f"{name}.inp:" in out and "Traceback" not in out
