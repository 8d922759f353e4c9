"""Degenerate input gets a clear error, never a broken mesh."""
import pytest

from vctools.mesh import MeshError
from vctools.mesh.cli import main
from vctools.mesh.scene import build

import tomllib


def scene(text):
    return tomllib.loads(text)


BOX = """
[mesh]
lloyd = 3
[[body]]
name = "B"
polygon = [[0, 0], [4, 0], [4, 2], [0, 2]]
cells = 200
"""


@pytest.mark.parametrize("text,msg", [
    ("""[[body]]
name = "B"
polygon = [[0, 0], [2, 2], [2, 0], [0, 2]]
cells = 50""", "self-intersecting"),
    (BOX + """[[joint]]
name = "J"
polyline = [[1, 1], [5, 1]]""", "leaves its body"),
    (BOX + """[[joint]]
name = "J1"
polyline = [[1, 0.5], [3, 1.5]]
[[joint]]
name = "J2"
polyline = [[1, 1.5], [3, 0.5]]""", "cross"),
    ("""[[body]]
name = "B"
polygon = [[0, 0], [4, 0], [4, 2], [0, 2]]
cells = 4
[[joint]]
name = "J"
polyline = [[1, 1], [1.3, 1.2]]""", "too small"),
    ("""[[body]]
name = "B"
polygon = [[0, 0], [1, 0], [0, 0], [0, 1]]
cells = 10""", "self-intersecting|repeated vertex"),
    ("""[[body]]
name = "B"
polygon = [[0, 0], [1, 0], [1, 1]]
cells = 0""", "cells must be >= 1"),
    ("""[[body]]
name = "B"
polygon = [[0, 0], [1, 0], [1, 1]]
cells = 10
formulation = "fem"
""", "FEM elements are triangles and quads"),
    ("""[[body]]
name = "B"
polygon = [[0, 0], [1, 0], [1, 1]]
cells = 10
colour = "red"
""", "unknown keys"),
    (BOX + """[[selection]]
name = "S"
y = 7""", "matches no boundary node"),
    (BOX + """[[joint]]
name = "J"
polyline = [[0, 2], [4, 2]]""", "outer boundary"),
    ("""[[body]]
name = "A"
polygon = [[0, 0], [2, 0], [2, 2], [0, 2]]
cells = 20
group = "g"
[[body]]
name = "B"
polygon = [[1, 1], [3, 1], [3, 3], [1, 3]]
cells = 20
group = "g"
""", "overlap"),
])
def test_error(text, msg):
    with pytest.raises(MeshError, match=msg):
        build(scene(text))


def test_cli_reports_errors(tmp_path, capsys):
    p = tmp_path / "bad.toml"
    p.write_text("""[[body]]
name = "B"
polygon = [[0, 0], [2, 2], [2, 0], [0, 2]]
cells = 50
""")
    assert main(["scene", str(p)]) == 2
    assert "self-intersecting" in capsys.readouterr().err
    assert not (tmp_path / "bad.inp").exists()


def test_cli_help(capsys):
    with pytest.raises(SystemExit) as e:
        main(["--help"])
    assert e.value.code == 0
    assert "scene" in capsys.readouterr().out
