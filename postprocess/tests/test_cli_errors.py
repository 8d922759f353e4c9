"""Every vctools command line ends a failure with one line on stderr and a non-zero
status (vctools/cli.py), and the mesher never writes a cell vemcontact would refuse
(vctools.mesh.mesh.check_cells)."""
import os
import subprocess
import sys

import numpy as np
import pytest

from vctools.cli import entry
from vctools.mesh import structured
from vctools.mesh.deck import write_deck
from vctools.mesh.errors import MeshError
from vctools.mesh.mesh import Mesh, check_cells

ENV = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(__file__), ".."))
ENV.pop("VCTOOLS_TRACEBACK", None)
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def run_module(module, *args, cwd=None):
    return subprocess.run([sys.executable, "-m", module, *args], capture_output=True, text=True, env=ENV,
                          cwd=cwd, check=False)


def assert_one_line(r, status, *words):
    assert r.returncode == status, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert "Traceback" not in r.stderr
    for w in words:
        assert w in lines[0], lines[0]


def test_adapt_missing_scene(tmp_path):
    r = run_module("vctools.adapt", os.path.join(ROOT, "inputs", "block_selfweight.inp"),
                   "--scene", str(tmp_path / "missing.toml"))
    assert_one_line(r, 1, "vc-adapt: error:", "missing.toml")


def test_mesh_malformed_and_missing_scene(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[mesh\nseed = 1\n")
    assert_one_line(run_module("vctools.mesh", "scene", str(bad)), 2, "vc-mesh: error:", "bad.toml")
    assert_one_line(run_module("vctools.mesh", "scene", str(tmp_path / "none.toml")), 1, "vc-mesh: error:", "none.toml")


def test_mesh_negative_height(tmp_path):
    scene = tmp_path / "beam.toml"
    scene.write_text('[mesh]\ntitle = "beam"\n\n[[body]]\nname = "BEAM"\nmesher = "quad"\n'
                     'cantilever = { length = 40.0, height = -8.0 }\n')
    r = run_module("vctools.mesh", "scene", str(scene), "-o", str(tmp_path / "beam.inp"))
    assert_one_line(r, 2, "vc-mesh: error:", "height")
    assert not (tmp_path / "beam.inp").exists()
    with pytest.raises(MeshError, match="height > 0"):
        structured.cantilever("B", 40.0, -8.0)


@pytest.mark.parametrize("step", ["0", "-1", "two"])
def test_plot_step_must_be_positive(tmp_path, step):
    """--step 0 once drew the last step silently: now a usage error (status 2)."""
    r = run_module("vctools.plot", str(tmp_path / "x.pvd"), "--step", step)
    assert r.returncode == 2
    assert "--step" in r.stderr and "Traceback" not in r.stderr


def test_internal_error_is_one_line(capsys, monkeypatch):
    monkeypatch.delenv("VCTOOLS_TRACEBACK", raising=False)

    @entry("vc-test")
    def broken(argv=None):
        raise ZeroDivisionError("division\nby zero")

    assert broken([]) == 5
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["vc-test: internal error: ZeroDivisionError: division by zero (VCTOOLS_TRACEBACK=1 shows where)"]


def _mesh(cells, nodes):
    ptr = np.cumsum([0] + [len(c) for c in cells])
    return Mesh(np.asarray(nodes, float), ptr, np.concatenate(cells).astype(np.int64),
                np.zeros(len(cells), np.int64), [("BODY", "VPE")])


def test_check_cells_refuses_invalid_cells(tmp_path):
    nodes = [[0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [2, 1]]
    good = _mesh([[0, 1, 2, 3], [1, 4, 5, 2]], nodes)
    check_cells(good)
    # side 4 crosses side 1 (area +6.5 > 0: a positive signed area is no proof of a simple cell)
    bowtie = _mesh([[0, 1, 2, 3, 4]], [[0, 0], [4, 0], [4, 4], [0, 4], [2, -1]])
    with pytest.raises(MeshError, match="self-intersecting"):
        check_cells(bowtie)
    with pytest.raises(MeshError, match="clockwise"):
        check_cells(_mesh([[0, 3, 2, 1]], nodes))
    with pytest.raises(MeshError, match="node twice"):
        check_cells(_mesh([[0, 1, 2, 1, 4, 5, 3]], nodes))
    # a non-convex but simple cell passes
    check_cells(_mesh([[0, 4, 5, 6, 3]], nodes + [[1, 0.5]]))
    with pytest.raises(MeshError):
        write_deck(bowtie, str(tmp_path / "bowtie.inp"))
    assert not (tmp_path / "bowtie.inp").exists()
