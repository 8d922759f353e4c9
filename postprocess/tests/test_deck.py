"""Deck text: keywords, ids, continuation lines, surfaces; Gmsh import."""
import re
import numpy as np
import pytest
from pathlib import Path

from vctools.mesh.deck import write_deck
from vctools.mesh.gmsh import read_msh
from vctools.mesh.mesh import Mesh
from vctools.mesh.cli import main

SCENES = Path(__file__).resolve().parents[1] / "scenes"


def parse(text):
    """A minimal reader of what we write: blocks by keyword, data lines joined on commas."""
    blocks, cur = [], None
    pending = ""
    for line in text.splitlines():
        assert len(line) < 200
        if line.startswith("**"):
            continue
        if line.startswith("*"):
            cur = [line, []]
            blocks.append(cur)
            continue
        pending += line
        if line.rstrip().endswith(","):
            continue
        cur[1].append([t.strip() for t in pending.split(",")])
        pending = ""
    return blocks


def test_big_cell_continues_lines_and_ids(tmp_path):
    n = 40
    ang = 2 * np.pi * np.arange(n) / n
    nodes = np.column_stack([np.cos(ang), np.sin(ang)])
    m = Mesh(nodes, np.array([0, n]), np.arange(n), np.zeros(1, int), [("P", "VPE")])
    m.nsets["ALL"] = np.arange(n)
    m.esurfaces["RIM"] = (np.zeros(n, int), np.arange(1, n + 1))
    text = write_deck(m, tmp_path / "p.inp", ["hello"])
    assert text.endswith("\n") and text.startswith("** hello\n")
    blocks = parse(text)
    assert blocks[0][0] == "*NODE, NSET=NALL"
    assert [float(x) for x in blocks[0][1][3][1:]] == list(nodes[3])     # full precision
    assert blocks[1][0] == "*ELEMENT, TYPE=VPE, ELSET=P"
    assert blocks[1][1][0] == ["1"] + [str(i) for i in range(1, n + 1)]
    assert [len(r) for r in blocks[2][1]] == [16, 16, 8]
    assert blocks[3][1][-1] == ["1", f"S{n}"]


def test_paper_scenes_write_consistent_decks(tmp_path):
    assert main(["paper", "--scenes", str(SCENES), "-o", str(tmp_path)]) == 0
    files = sorted(tmp_path.glob("*.inp"))
    assert len(files) == 18 + 18 + 6 + 2 + 7 + 1    # examples 1 and 2: first and second order
    total = 0
    for f in files:
        text = f.read_text()
        total += len(text)
        assert len(text) < 1_000_000 and text.endswith("\n")
        blocks = parse(text)
        nodes = {int(r[0]) for b in blocks if b[0].startswith("*NODE") for r in b[1]}
        elems = {}
        for b in blocks:
            if b[0].startswith("*ELEMENT"):
                for r in b[1]:
                    assert int(r[0]) not in elems
                    elems[int(r[0])] = [int(x) for x in r[1:]]
                    assert set(elems[int(r[0])]) <= nodes
        assert sorted(nodes) == list(range(1, len(nodes) + 1))
        for b in blocks:
            if b[0].startswith("*SURFACE") and "TYPE=ELEMENT" in b[0]:
                for eid, side in b[1]:
                    k = int(side[1:])
                    assert 1 <= k <= len(elems[int(eid)])
            if b[0].startswith("*NSET"):
                for r in b[1]:
                    assert {int(x) for x in r} <= nodes
            if "TYPE=NODE" in b[0]:
                # one node or one node set per line, as CalculiX (and vemcontact) read it
                nsets = {bb[0].split("NSET=")[1].strip() for bb in blocks if bb[0].startswith("*NSET")}
                for r in b[1]:
                    assert len(r) == 1
                    assert r[0] in nsets or int(r[0]) in nodes
        if "fem2" in f.name or "vem2" in f.name:
            types = re.findall(r"TYPE=(\w+), ELSET", text)
            assert set(types) == ({"CPE8"} if "fem2" in f.name else {"VPE2"})
        elif "fem" in f.name or "quad" in f.name or "tri" in f.name:
            types = re.findall(r"TYPE=(\w+), ELSET", text)
            assert set(types) <= ({"CPE4", "CPE3"} if "fem" in f.name else {"VPE"})
    assert total < 5_000_000


MSH = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
1 1 "bottom"
2 2 "plate"
0 3 "corner"
$EndPhysicalNames
$Entities
1 1 1 0
1 0 0 0 1 3
1 0 0 0 2 0 0 1 1 2 1 -2
1 0 0 0 2 1 0 1 2 1 1
$EndEntities
$Nodes
3 6 1 6
0 1 0 1
1
0 0 0
1 1 0 2
2
3
1 0 0
2 0 0
2 1 0 3
4
5
6
2 1 0
1 1 0
0 1 0
$EndNodes
$Elements
4 6 1 6
0 1 15 1
1 1
1 1 1 2
2 1 2
3 2 3
2 1 3 1
4 1 2 5 6
2 1 2 2
5 2 3 4
6 2 4 5
$EndElements
"""


def test_gmsh_import(tmp_path):
    p = tmp_path / "m.msh"
    p.write_text(MSH)
    m = read_msh(p)
    assert m.ncell == 3 and [b[0] for b in m.bodies] == ["plate"]
    assert (m.cell_areas() > 0).all() and abs(m.cell_areas().sum() - 2.0) < 1e-14
    assert np.allclose(m.nodes[m.nsets["bottom"], 1], 0) and len(m.nsets["bottom"]) == 3
    cells, sides = m.esurfaces["bottom"]
    assert len(cells) == 2
    for c, s in zip(cells, sides):
        cc = m.cell(c)
        assert np.allclose(m.nodes[[cc[s - 1], cc[s % len(cc)]], 1], 0)
    assert np.allclose(m.nodes[m.nsets["corner"]], [[0, 0]])
    assert main(["gmsh", str(p), "-o", str(tmp_path / "m.inp"), "--formulation", "fem"]) == 0
    text = (tmp_path / "m.inp").read_text()
    assert "*ELEMENT, TYPE=CPE4, ELSET=plate" in text and "*ELEMENT, TYPE=CPE3, ELSET=plate" in text


def _meshio_two_cell_types():
    """A quad and two triangles in separate entities, a physical curve and point."""
    import meshio
    pts = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [0, 1, 0]], float)
    cells = [("line", np.array([[0, 1], [1, 2]])), ("quad", np.array([[0, 1, 4, 5]])),
             ("triangle", np.array([[1, 2, 3], [1, 3, 4]])), ("vertex", np.array([[0]]))]
    cd = {"gmsh:physical": [np.array([1, 1]), np.array([2]), np.array([2, 2]), np.array([3])],
          "gmsh:geometrical": [np.array([1, 1]), np.array([1]), np.array([2, 2]), np.array([1])]}
    fd = {"bottom": np.array([1, 1]), "plate": np.array([2, 2]), "corner": np.array([3, 0])}
    dim_tags = np.array([[0, 1], [1, 1], [1, 1], [2, 2], [2, 2], [2, 1]])
    return meshio.Mesh(pts, cells, cell_data=cd, field_data=fd, point_data={"gmsh:dim_tags": dim_tags})


@pytest.mark.parametrize("fmt,binary", [("gmsh22", False), ("gmsh22", True), ("gmsh", False), ("gmsh", True)])
def test_gmsh_formats(tmp_path, fmt, binary):
    """Gmsh 2.2 and 4.1, ASCII and binary (written by meshio), read the same."""
    import meshio
    p = tmp_path / "m.msh"
    meshio.write(p, _meshio_two_cell_types(), file_format=fmt, binary=binary)
    m = read_msh(p)
    assert m.ncell == 3 and [b[0] for b in m.bodies] == ["plate"]
    assert (m.cell_areas() > 0).all() and abs(m.cell_areas().sum() - 2.0) < 1e-14
    assert np.allclose(m.nodes[m.nsets["bottom"], 1], 0) and len(m.nsets["bottom"]) == 3
    assert len(m.esurfaces["bottom"][0]) == 2
    assert np.allclose(m.nodes[m.nsets["corner"]], [[0, 0]])


def test_gmsh_errors_are_messages(tmp_path, capsys):
    """A missing, empty or garbage file is one error line naming it, never a traceback."""
    assert main(["gmsh", str(tmp_path / "missing.msh")]) == 2
    assert "missing.msh: no such file" in capsys.readouterr().err
    for name, data in [("bad.msh", b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00garbage"),
                       ("empty.msh", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")]:
        (tmp_path / name).write_bytes(data)
        assert main(["gmsh", str(tmp_path / name)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"vc-mesh: error: {tmp_path / name}: ") and err.count("\n") == 1


def test_selection_missing_its_face_is_an_error(tmp_path):
    """A selection that matches boundary nodes but no side, or a segment only partly on the
    boundary, is an error at meshing time that names the selection."""
    from vctools.mesh.errors import MeshError
    from vctools.mesh.select import add_selection
    from vctools.mesh.structured import rectangle
    def mesh():
        return rectangle("B", (0, 0, 2, 1), (4, 2))
    with pytest.raises(MeshError, match="selection 'TOUCH'.*no element side"):
        add_selection(mesh(), "TOUCH", {"segment": [[-1, 0.5], [0, 0.5]]}, 1e-9)
    with pytest.raises(MeshError, match="selection 'HALF'.*cover a length 1 of the segment's 2"):
        add_selection(mesh(), "HALF", {"segment": [[0, 0], [0, 2]]}, 1e-9)
    m = add_selection(mesh(), "LEFT", {"x": 0.0}, 1e-9)
    assert len(m.esurfaces["LEFT"][0]) == 2


MSH2 = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "plate"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 2 0 0 1 1 0
1 0 0 0 2 1 0 1 2 0
$EndEntities
$Nodes
1 8 1 8
2 1 0 8
1
2
3
4
5
6
7
8
0 0 0
2 0 0
2 1 0
0 1 0
1 0 0
2 0.5 0
1 1 0
0 0.5 0
$EndNodes
$Elements
2 2 1 2
1 1 8 1
1 1 2 5
2 1 16 1
2 CELL
$EndElements
"""


def test_gmsh_second_order_import(tmp_path):
    """8-node quads and 3-node lines: corners in conn, side nodes in side_nodes (at
    the middles here), a clockwise cell reversed with its side nodes re-paired, the
    bottom node set with its side node, and CPE8 in the deck."""
    for cell in ("1 2 3 4 5 6 7 8", "1 4 3 2 8 7 6 5"):      # counter-clockwise, clockwise
        p = tmp_path / "q8.msh"
        p.write_text(MSH2.replace("CELL", cell))
        m = read_msh(p)
        assert m.ncell == 1 and m.side_nodes is not None and m.cell_areas()[0] == 2.0
        a, b, _, _ = m.edges()
        assert np.allclose(m.nodes[m.side_nodes], 0.5 * (m.nodes[a] + m.nodes[b]))
        assert np.allclose(m.nodes[m.nsets["bottom"], 1], 0) and len(m.nsets["bottom"]) == 3
        assert main(["gmsh", str(p), "-o", str(tmp_path / "q8.inp"), "--formulation", "fem"]) == 0
        text = (tmp_path / "q8.inp").read_text()
        assert "*ELEMENT, TYPE=CPE8, ELSET=plate" in text
        line = text.split("*ELEMENT, TYPE=CPE8, ELSET=plate\n")[1].splitlines()[0]
        assert len(line.split(",")) == 9       # id, 4 corners, 4 side nodes


@pytest.mark.parametrize("fmt,binary", [("gmsh22", False), ("gmsh22", True), ("gmsh", False), ("gmsh", True)])
def test_gmsh_second_order_formats(tmp_path, fmt, binary):
    """6-node triangles and 3-node lines written by meshio in every Gmsh format: corners
    in conn, side nodes at the middles of their sides, a clockwise cell reversed with its
    side nodes re-paired, the physical curve's node set with its middle node, and CPE6
    in the deck."""
    import meshio
    pts = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0],
                    [1, 0, 0], [2, 0.5, 0], [1, 0.5, 0], [1, 1, 0], [0, 0.5, 0]], float)
    tri6 = np.array([[0, 1, 2, 4, 5, 6], [0, 3, 2, 8, 7, 6]])    # counter-clockwise, clockwise
    cells = [("line3", np.array([[0, 1, 4]])), ("triangle6", tri6)]
    cd = {"gmsh:physical": [np.array([1]), np.array([2, 2])],
          "gmsh:geometrical": [np.array([1]), np.array([1, 1])]}
    fd = {"bottom": np.array([1, 1]), "plate": np.array([2, 2])}
    mesh = meshio.Mesh(pts, cells, cell_data=cd, field_data=fd)
    if fmt == "gmsh":
        mesh.point_data["gmsh:dim_tags"] = np.array([[0, 1], [0, 2], [0, 3], [0, 4],
                                                     [1, 1], [2, 1], [2, 1], [2, 1], [2, 1]])
    p = tmp_path / "t6.msh"
    meshio.write(p, mesh, file_format=fmt, binary=binary)
    m = read_msh(p)
    assert m.ncell == 2 and m.side_nodes is not None and np.allclose(m.cell_areas(), [1.0, 1.0])
    a, b, _, _ = m.edges()
    assert np.allclose(m.nodes[m.side_nodes], 0.5 * (m.nodes[a] + m.nodes[b]))
    assert np.allclose(m.nodes[m.nsets["bottom"], 1], 0) and len(m.nsets["bottom"]) == 3
    assert len(m.esurfaces["bottom"][0]) == 1
    assert main(["gmsh", str(p), "-o", str(tmp_path / "t6.inp"), "--formulation", "fem"]) == 0
    text = (tmp_path / "t6.inp").read_text()
    line = text.split("*ELEMENT, TYPE=CPE6, ELSET=plate\n")[1].splitlines()[0]
    assert len(line.split(",")) == 7       # id, 3 corners, 3 side nodes
