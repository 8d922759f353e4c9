"""Robustness of finite-sliding node-to-segment contact (docs/contact-robustness.md):
a fine non-matching Voronoi interface under uniform compression converges in a few
iterations (the iteration on the pairing is a Newton iteration: the sliding part of
the tangent, solved by GMRES with the frozen-pairing factor), and a block slid by several segment lengths along a flat
surface keeps the exact pressure, with the load following it on the master."""
import os
import subprocess
import sys

import h5py
import numpy as np

from h5results import assert_rf_balanced, contact_iterations, factorizations
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PYTHON_ENV = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))




def run(exe, deck, out):
    """Run a deck; returns its results file JOB.h5."""
    r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert_rf_balanced(out / (deck.stem + ".h5"))
    return out / (deck.stem + ".h5")


def iterations(h5):
    return contact_iterations(h5)


def read_csv(path):
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)


# ------------------------------------------------ fine non-matching interface
INTERFACE_SCENE = """
[mesh]
title = "non-matching interface, about 2e4 unknowns"
seed = 3
lloyd = 40

[[body]]
name = "LOWER"
rectangle = [0.0, 0.0, 4.0, 1.0]
mesher = "voronoi"
cells = 2500

[[body]]
name = "UPPER"
rectangle = [0.0, 1.0, 4.0, 2.0]
mesher = "voronoi"
cells = 2500

[[selection]]
name = "BOTTOM"
y = 0.0

[[selection]]
name = "TOP"
y = 2.0

[[contact]]
name = "IFACE"
slave = "UPPER"
master = "LOWER"
y = 1.0
"""


def interface_deck(path, mesh, pair_options=""):
    """The interface example (inputs/interface_voronoi_*.inp) on the given mesh: E = 1e9,
    nu = 0.3, plane strain, bottom fixed, top moved by -0.1 and held in x, K = 1e12."""
    path.write_text("\n".join([
        "*HEADING", "fine non-matching interface", f"*INCLUDE, INPUT={mesh}",
        "*MATERIAL, NAME=ROCK", "*ELASTIC", "1.0e9, 0.3",
        "*SOLID SECTION, ELSET=LOWER, MATERIAL=ROCK", "1.0",
        "*SOLID SECTION, ELSET=UPPER, MATERIAL=ROCK", "1.0",
        "*SURFACE INTERACTION, NAME=INTERFACE", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.0e12",
        "*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=NODE TO SURFACE" + pair_options,
        "IFACE_SLAVE, IFACE_MASTER",
        "*BOUNDARY", "BOTTOM, 1, 2", "TOP, 1",
        "*STEP", "*STATIC", "*BOUNDARY", "TOP, 2, 2, -0.1", "*END STEP", ""]))


@pytest.fixture(scope="module")
def interface_mesh(tmp_path_factory):
    d = tmp_path_factory.mktemp("iface")
    (d / "scene.toml").write_text(INTERFACE_SCENE)
    r = subprocess.run([sys.executable, "-m", "vctools.mesh", "scene", str(d / "scene.toml"),
                        "-o", str(d / "mesh.inp"), "--processes", "1"],
                       capture_output=True, text=True, env=PYTHON_ENV)
    assert r.returncode == 0, r.stderr
    return d / "mesh.inp"


def test_fine_nonmatching_interface_converges_fast(exe, tmp_path, interface_mesh):
    """About 2e4 unknowns, 95 slave nodes on independently meshed Voronoi blocks.  The
    blocks expand sideways under the load, so the slave nodes slide along the master and
    the pairing moves with every solve.  With the reference normal and the sliding part
    of the tangent the iteration on the pairing is a Newton iteration: 1 solve at the
    undeformed pairing, then quadratic convergence; the re-paired matrices are solved with
    the first factor (GMRES), so one numeric factorization in all.  Measured: 3 iterations
    (the frozen-pairing fixed point took 6; session 2's geometric stiffness with the
    current normal 4, 7 before it), 1 factorization."""
    interface_deck(tmp_path / "fs.inp", interface_mesh)
    h5 = run(exe, tmp_path / "fs.inp", tmp_path)
    its = iterations(h5)
    print("finite sliding iterations", its, "factorizations", factorizations(h5))
    assert len(its) == 1 and its[0] <= 4
    assert factorizations(h5) == [1]
    fs = read_csv(tmp_path / "fs_contact_pair1_0001.csv")
    assert (fs["STATUS"] == "CLOSED").all()
    # the same interface with the pairing frozen (SMALL SLIDING, one solve): the two
    # pairings differ by the relative sliding and the tilt of the master normals only,
    # so the force (tributary-weighted mean pressure) agrees closely (measured 2e-5)
    interface_deck(tmp_path / "ss.inp", interface_mesh, ", SMALL SLIDING")
    assert iterations(run(exe, tmp_path / "ss.inp", tmp_path)) == [1]
    ss = read_csv(tmp_path / "ss_contact_pair1_0001.csv")
    o = np.argsort(fs["x"])
    x = fs["x"][o]
    trib = np.diff(np.concatenate([[x[0]], (x[1:] + x[:-1]) / 2, [x[-1]]]))
    mean_fs = np.sum(fs["CPRESS"][o] * trib) / np.sum(trib)
    o = np.argsort(ss["x"])
    mean_ss = np.sum(ss["CPRESS"][o] * trib) / np.sum(trib)
    print(f"mean pressure: finite sliding {mean_fs:.6e}, small sliding {mean_ss:.6e}")
    assert abs(mean_fs / mean_ss - 1) < 1e-3


def test_fine_nonmatching_interface_hard(exe, tmp_path, interface_mesh):
    """The same interface with PRESSURE-OVERCLOSURE=HARD: the multiplier updates and the
    Newton steps on the pairing run in the same iterations (the robustness target of
    issue 10: at most 10 per increment).  Measured: 7 iterations, 2 factorizations (the
    soft search, the stiffened springs; the re-paired matrices and the updates are
    solved with them).  No overclosure beyond 1e-10 of the element size (about 0.03)."""
    interface_deck(tmp_path / "hard.inp", interface_mesh)
    text = (tmp_path / "hard.inp").read_text()
    text = text.replace("PRESSURE-OVERCLOSURE=LINEAR\n1.0e12", "PRESSURE-OVERCLOSURE=HARD")
    (tmp_path / "hard.inp").write_text(text)
    h5 = run(exe, tmp_path / "hard.inp", tmp_path)
    its = iterations(h5)
    print("HARD finite sliding iterations", its, "factorizations", factorizations(h5))
    assert len(its) == 1 and its[0] <= 10
    assert factorizations(h5)[0] <= 3
    hard = read_csv(tmp_path / "hard_contact_pair1_0001.csv")
    assert (hard["STATUS"] == "CLOSED").all()
    assert hard["COPEN"].min() > -1e-10 * 0.03


# ------------------------------------------------ a block sliding along a flat surface
def grid(nx, ny, x0, y0, lx, ly, first_node, first_elem):
    """Quads of [x0, x0+lx] x [y0, y0+ly] as VPS polygons."""
    nodes, elems, ids = [], [], {}
    n = first_node
    for j in range(ny + 1):
        for i in range(nx + 1):
            ids[i, j] = n
            nodes.append(f"{n}, {x0 + lx * i / nx!r}, {y0 + ly * j / ny!r}")
            n += 1
    e = first_elem
    bottom, top, centre = [], [], {}
    for j in range(ny):
        for i in range(nx):
            elems.append(f"{e}, {ids[i, j]}, {ids[i + 1, j]}, {ids[i + 1, j + 1]}, {ids[i, j + 1]}")
            if j == 0:
                bottom.append(f"{e}, S1")
            if j == ny - 1:
                top.append(f"{e}, S3")
            centre[e] = (x0 + lx * (i + 0.5) / nx, j == ny - 1)
            e += 1
    return nodes, elems, bottom, top, [ids[i, 0] for i in range(nx + 1)], \
        [ids[i, ny] for i in range(nx + 1)], n, e, centre


SLIDE_E, SLIDE_DELTA, SLIDE_H, SLIDE_K = 1.0e3, 0.005, 0.5, 1.0e6
SLIDES = [0.0, 0.5, 1.0, 1.5, 2.0]


def test_block_slides_several_segments(exe, tmp_path):
    """A block [1, 2] x [1, 1.5] (E = 1e3, nu = 0, 5 x 3 quads) is pressed by 0.005 on a
    long stiff block [0, 6] x [0, 1] (E = 1e6, 24 x 4 quads: master segments of 0.25,
    slave segments of 0.2, non-matching), then its top is moved sideways in steps of
    0.5 up to 2.0: eight master segments, every slave node crossing master vertices.
    Frictionless with nu = 0, the block translates and stays in uniaxial stress, so
    every slave node keeps p = delta / (H/E + 1/K) (the stiff base adds about 0.2 % of
    compliance: 1 % asked) at every position, and the load on the master follows the
    block: the compression in the base's top row is centred under the block (within
    0.05 of 1.5 + slide; its elements are 0.25 wide).  A pairing frozen at the start
    (SMALL SLIDING) would leave it at 1.5."""
    ln, le, lb, lt, lbn, ltn, n, e, lc = grid(24, 4, 0.0, 0.0, 6.0, 1.0, 1, 1)
    un, ue, ub, ut, ubn, utn, _, _, _ = grid(5, 3, 1.0, 1.0, 1.0, SLIDE_H, n, e)
    text = ["*NODE", *ln, *un,
            "*ELEMENT, TYPE=VPS, ELSET=BASE", *le, "*ELEMENT, TYPE=VPS, ELSET=SLIDER", *ue,
            "*NSET, NSET=BOTTOM", ", ".join(map(str, lbn)), "*NSET, NSET=TOP", ", ".join(map(str, utn)),
            "*SURFACE, NAME=BASE_TOP", *lt, "*SURFACE, NAME=SLIDER_BOTTOM", *ub,
            "*MATERIAL, NAME=SOFT", "*ELASTIC", f"{SLIDE_E!r}, 0.0",
            "*MATERIAL, NAME=STIFF", "*ELASTIC", f"{1e3 * SLIDE_E!r}, 0.0",
            "*SOLID SECTION, ELSET=BASE, MATERIAL=STIFF", "1.0",
            "*SOLID SECTION, ELSET=SLIDER, MATERIAL=SOFT", "1.0",
            "*SURFACE INTERACTION, NAME=I", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{SLIDE_K!r}",
            "*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE", "SLIDER_BOTTOM, BASE_TOP",
            "*BOUNDARY", "BOTTOM, 1, 2"]
    for s in SLIDES:
        text += ["*STEP", "*STATIC", "*BOUNDARY", f"TOP, 1, 1, {s!r}", f"TOP, 2, 2, {-SLIDE_DELTA!r}",
                 "*END STEP"]
    deck = tmp_path / "slide.inp"
    deck.write_text("\n".join(text) + "\n")
    h5 = run(exe, deck, tmp_path)
    its = iterations(h5)
    print("iterations per step", its)
    assert len(its) == len(SLIDES) and max(its) <= 8
    p = SLIDE_DELTA / (SLIDE_H / SLIDE_E + 1 / SLIDE_K)
    nbase = len(le)
    with h5py.File(tmp_path / "slide.h5") as f:
        for k, s in enumerate(SLIDES, start=1):
            d = read_csv(tmp_path / f"slide_contact_pair1_{k:04d}.csv")
            assert (d["STATUS"] == "CLOSED").all(), f"step {k}: a slave node opened"
            err = np.max(np.abs(d["CPRESS"] / p - 1))
            st = f[f"steps/{k:04d}"]
            u = st["U"][()]
            slave = np.array(ubn) - 1
            # the slave nodes translate with the top (uniaxial stress, nu = 0; the
            # base's small non-uniform compliance spreads them by 2e-4 delta)
            assert np.allclose(u[slave, 0], s, atol=1e-2 * SLIDE_DELTA), f"step {k}"
            sy = st["S_element"][()][:nbase, 1]
            top_row = [i for i in range(nbase) if lc[i + 1][1]]
            xs = np.array([lc[i + 1][0] for i in top_row])
            w = -sy[top_row]
            centroid = np.sum(w * xs) / np.sum(w)
            print(f"slide {s}: pressure error {err:.2e}, base compression centred at {centroid:.4f}")
            assert err < 1e-2, f"step {k}"
            assert abs(centroid - (1.5 + s)) < 0.05, f"step {k}"
