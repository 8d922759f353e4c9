import os

import numpy as np
import pytest
import shapely

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def _executable():
    """The vemcontact under test: VEMCONTACT_EXE (CTest sets it), else a build in the tree."""
    exe = os.environ.get("VEMCONTACT_EXE")
    if not exe:
        for cand in ("build-debug/vemcontact", "build/vemcontact"):
            if os.path.exists(os.path.join(ROOT, cand)):
                exe = os.path.join(ROOT, cand)
                break
    if not exe or not os.path.exists(exe):
        pytest.fail("vemcontact executable not found: set VEMCONTACT_EXE or build first")
    return exe


@pytest.fixture(scope="session")
def exe():
    """Path of the vemcontact executable under test."""
    return _executable()


@pytest.fixture(scope="session")
def vemcontact():
    """The same as `exe` (the name the plot and paper tests use)."""
    return _executable()


def edges_of(m):
    a, b, cell, side = m.edges()
    return a, b, cell, side


def assert_valid_cells(m):
    """Every cell simple, counter-clockwise, without repeated nodes."""
    area = m.cell_areas()
    assert (area > 0).all(), "clockwise or degenerate cell"
    for i in range(m.ncell):
        c = m.cell(i)
        assert len(set(c.tolist())) == len(c), f"cell {i} repeats a node"
        ring = shapely.LinearRing(m.nodes[c])
        assert ring.is_simple, f"cell {i} is not simple"


def assert_conforming(m, domain_boundary, extra_lines=()):
    """Interior edges are shared by two cells in opposite directions; edges used once lie
    on the outer boundary or on a joint."""
    a, b, cell, side = m.edges()
    fwd = set(zip(a.tolist(), b.tolist()))
    assert len(fwd) == len(a), "an edge appears twice in the same direction"
    lines = [domain_boundary] + [shapely.LineString(x) for x in extra_lines]
    tol = 1e-9 * max(np.ptp(m.nodes[:, 0]), np.ptp(m.nodes[:, 1]))
    for u, v in zip(a.tolist(), b.tolist()):
        if (v, u) not in fwd:
            mid = shapely.Point(0.5 * (m.nodes[u] + m.nodes[v]))
            assert min(g.distance(mid) for g in lines) <= tol, f"open edge {u}-{v} inside the domain"


@pytest.fixture
def tmp_scene(tmp_path):
    def write(text, name="scene.toml"):
        p = tmp_path / name
        p.write_text(text)
        return p
    return write
