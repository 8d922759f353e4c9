"""*TIE of non-matching meshes: the left block [0, 1] x [0, 1] (nl x nl cells) and the
right block [1, 2] x [0, 1] (nr x nr cells, its own nodes on x = 1) bonded by a tie
(slave: the right block's left side; master: the left block's right side).

On virtual elements (VPE, VPE2) the tie inserts each face's nodes into the other face's
polygons (the insertion of TYPE=SURFACE TO SURFACE contact) and ties the coincident node
pairs: the two traces are then one field, and the patch tests are passed to round-off
for any two meshes (2 against 3 cells, Voronoi cells against quads, first and second
order).  With one face of FEM elements, its corners are inserted into the virtual face,
whose nodes are tied to the FEM face: exact too.  With FEM elements on both faces the tie
is CalculiX's: each slave node tied to the closest point of the master face; its traces
coincide, and the patch test is passed exactly, when every
master node of the interface is also a slave node (the slave side refines the master's);
on meshes whose interface nodes do not nest, a master node between two slave nodes is
not held, and the result is close to, not equal to, the exact field (measured below).
Patch tests: a linear displacement field prescribed on the outer boundary, and uniaxial
tension by a pressure on x = 2."""
import subprocess

import h5py
import numpy as np
import pytest

E, NU = 2000.0, 0.3


def block(x0, n, order, first_node, first_elem):
    step = 2 if order == 2 else 1
    m = n * step
    ids, nodes = {}, {}
    for j in range(m + 1):
        for i in range(m + 1):
            if order == 2 and i % 2 == 1 and j % 2 == 1:
                continue
            ids[i, j] = first_node + len(nodes)
            nodes[ids[i, j]] = (x0 + i / m, j / m)
    elems = {}
    for j in range(n):
        for i in range(n):
            a, b = i * step, j * step
            c = [ids[a, b], ids[a + step, b], ids[a + step, b + step], ids[a, b + step]]
            if order == 2:
                c += [ids[a + 1, b], ids[a + 2, b + 1], ids[a + 1, b + 2], ids[a, b + 1]]
            elems[first_elem + len(elems)] = (i, j, c)
    return nodes, elems


def deck(left, right, load):
    (tl, ol, nl), (tr, orr, nr) = left, right
    nodes_l, el_l = block(0.0, nl, ol, 1, 1)
    nodes_r, el_r = block(1.0, nr, orr, 1001, 1001)
    nodes = {**nodes_l, **nodes_r}
    lines = ["*NODE, NSET=ALL"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in nodes.items()]
    for t, els, name in ((tl, el_l, "L"), (tr, el_r, "R")):
        lines.append(f"*ELEMENT, TYPE={t}, ELSET={name}")
        lines += [", ".join(str(v) for v in [e] + c) for e, (_, _, c) in els.items()]
    lines += ["*SURFACE, NAME=MASTER"] + [f"{e}, S2" for e, (i, _, _) in el_l.items() if i == nl - 1]
    lines += ["*SURFACE, NAME=SLAVE"] + [f"{e}, S4" for e, (i, _, _) in el_r.items() if i == 0]
    lines += ["*TIE, NAME=GLUE", "SLAVE, MASTER",
              "*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}",
              "*SOLID SECTION, ELSET=L, MATERIAL=M", "*SOLID SECTION, ELSET=R, MATERIAL=M",
              "*BOUNDARY"]
    if load == "linear":
        for k, (x, y) in nodes.items():
            if x in (0.0, 2.0) or y in (0.0, 1.0):
                ux, uy = exact_linear(x, y)
                lines += [f"{k}, 1, 1, {ux!r}", f"{k}, 2, 2, {uy!r}"]
        lines += ["*STEP", "*STATIC"]
    else:
        lines += [f"{k}, 1" for k, (x, y) in nodes_l.items() if x == 0.0]
        lines += ["1, 2"]
        lines += ["*STEP", "*STATIC", "*DLOAD"]
        lines += [f"{e}, P2, -10." for e, (i, _, _) in el_r.items() if i == nr - 1]
    lines += ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    return "\n".join(lines) + "\n", nodes


def exact_linear(x, y):
    return 1e-3 * (1.0 + 2.0 * x - 3.0 * y), 1e-3 * (-0.5 + 1.5 * x + 0.7 * y)


# master (left) and slave (right) meshes: the slave's side is the finer, every master
# node on x = 1 is also a slave node (nested); the tie is then exact (see the module doc)
CASES = [(("VPE", 1, 2), ("VPE", 1, 4)), (("CPE4", 1, 2), ("CPE4", 1, 6)),
         (("CPE4", 1, 2), ("VPE", 1, 4)), (("CPE8", 2, 2), ("VPE2", 2, 4)),
         (("VPE2", 2, 1), ("CPE8R", 2, 2))]


def run(exe, tmp_path, text):
    (tmp_path / "tie.inp").write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), "tie.inp"], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    with h5py.File(tmp_path / "tie.h5") as f:
        return (dict(zip(f["mesh/node_ids"][...].tolist(), f["steps/0001/U"][...])),
                f["steps/0001/S_element"][...])


@pytest.mark.parametrize("left, right", CASES)
def test_tied_linear_field_is_exact(exe, tmp_path, left, right):
    text, nodes = deck(left, right, "linear")
    u, _ = run(exe, tmp_path, text)
    # a linear field on well-shaped elements: round-off, 1e-10 of the largest value
    for k, (x, y) in nodes.items():
        assert np.allclose(u[k], exact_linear(x, y), rtol=0, atol=1e-10 * 5e-3), k


@pytest.mark.parametrize("left, right", CASES)
def test_tied_tension_is_uniform(exe, tmp_path, left, right):
    """A pressure of -10 (tension) on x = 2: S_xx = 10, S_yy = S_xy = 0 in every element."""
    text, nodes = deck(left, right, "tension")
    u, s = run(exe, tmp_path, text)
    assert np.allclose(s[:, 0], 10.0, rtol=1e-9)
    assert np.allclose(s[:, [1, 3]], 0.0, atol=1e-9 * 10.0)
    # the interface does not open: both sides of x = 1 move alike (plane strain)
    exx = 10.0 * (1 - NU * NU) / E
    for k, (x, _) in nodes.items():
        assert np.isclose(u[k][0], exx * x, rtol=0, atol=1e-10), k


def test_tie_beyond_tolerance_is_an_error(exe, tmp_path):
    text, _ = deck(("VPE", 1, 2), ("VPE", 1, 3), "tension")
    text = text.replace("*TIE, NAME=GLUE", "*TIE, NAME=GLUE, POSITION TOLERANCE=1e-9").replace(
        "1001, 1.0, 0.0", "1001, 1.01, 0.0")
    (tmp_path / "bad.inp").write_text(text)
    r = subprocess.run([exe, "-o", str(tmp_path), "bad.inp"], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode != 0
    assert "beyond the position tolerance" in r.stdout + r.stderr


# interfaces whose nodes do not nest: 2 cells against 3 (and 3 against 2), first and
# second order; virtual elements on both sides, so the tie is node to node
NON_NESTED = [(("VPE", 1, 2), ("VPE", 1, 3)), (("VPE", 1, 3), ("VPE", 1, 2)),
              (("VPE2", 2, 2), ("VPE2", 2, 3))]


def mesh(tmp_path):
    with h5py.File(tmp_path / "tie.h5") as f:
        return f["mesh/coordinates"][...], f["steps/0001/U"][...], f["steps/0001/S_element"][...]


@pytest.mark.parametrize("left, right", NON_NESTED)
def test_non_nested_vem_tie_is_exact(exe, tmp_path, left, right):
    """The linear field at every node, the deck's and the inserted ones (which lie on the
    interface, where the exact field is as defined as anywhere): 1e-10 of the largest
    displacement (round-off: measured 2e-16 to 1.2e-15).  The closest-point tie missed by
    2.1 % on the 2-against-3 interface."""
    text, nodes = deck(left, right, "linear")
    run(exe, tmp_path, text)
    x, u, _ = mesh(tmp_path)
    assert len(x) > len(nodes)          # nodes were inserted into both faces
    ex = np.array([exact_linear(*p) for p in x])
    assert np.abs(u - ex).max() <= 1e-10 * np.abs(ex).max()


@pytest.mark.parametrize("left, right", NON_NESTED)
def test_non_nested_vem_tie_tension_is_uniform(exe, tmp_path, left, right):
    """S_xx = 10, S_yy = S_xy = 0 in every element to 1e-10 of the load (measured 5e-14)."""
    text, _ = deck(left, right, "tension")
    run(exe, tmp_path, text)
    _, _, s = mesh(tmp_path)
    assert np.abs(s[:, 0] - 10.0).max() <= 1e-10 * 10.0
    assert np.abs(s[:, [1, 3]]).max() <= 1e-10 * 10.0


# one face of FEM elements, one of virtual elements, non-nested, either of them the
# master: the FEM face's corners are inserted into the virtual face, whose nodes are
# then tied to the FEM face (its trace becomes the FEM face's)
FEM_VEM = [(("CPE4", 1, 2), ("VPE", 1, 3)), (("VPE", 1, 2), ("CPE4", 1, 3)), (("VPE", 1, 3), ("CPE4", 1, 2)),
           (("CPE8", 2, 2), ("VPE2", 2, 3)), (("VPE2", 2, 2), ("CPE8", 2, 3)), (("VPE2", 2, 3), ("CPE8R", 2, 2))]


@pytest.mark.parametrize("left, right", FEM_VEM)
@pytest.mark.parametrize("load", ["linear", "tension"])
def test_fem_vem_tie_is_exact(exe, tmp_path, left, right, load):
    """The linear field at every node and uniform tension in every element, to 1e-10
    (round-off: measured 2e-16 to 5e-14).  With the virtual face as the master, the FEM
    slave block is held only through the tie's equations (its nodes are their
    independent side): the support check counts the equations as couplings."""
    text, nodes = deck(left, right, load)
    run(exe, tmp_path, text)
    x, u, s = mesh(tmp_path)
    assert len(x) > len(nodes)
    if load == "linear":
        ex = np.array([exact_linear(*p) for p in x])
        assert np.abs(u - ex).max() <= 1e-10 * np.abs(ex).max()
    else:
        assert np.abs(s[:, 0] - 10.0).max() <= 1e-10 * 10.0
        assert np.abs(s[:, [1, 3]]).max() <= 1e-10 * 10.0


def test_non_nested_fem_tie_is_close(exe, tmp_path):
    """With FEM elements on both faces (no insertion) the tie is CalculiX's closest-point one: 2 master
    against 3 slave cells leave the master's middle node between slave nodes, unheld.
    Measured error of the linear patch: 2.3 % of the largest displacement (bounded by
    5 %), and no node is added."""
    text, nodes = deck(("CPE4", 1, 2), ("CPE4", 1, 3), "linear")
    u, _ = run(exe, tmp_path, text)
    assert len(u) == len(nodes)
    err = max(np.hypot(*(u[k] - exact_linear(x, y))) for k, (x, y) in nodes.items())
    umax = max(np.hypot(*exact_linear(x, y)) for x, y in nodes.values())
    assert 0.005 * umax < err < 0.05 * umax


VORONOI_SCENE = """
[mesh]
seed = 3
lloyd = 10
order = {order}

[[body]]
name = "LOWER"
rectangle = [0.0, 0.0, 1.0, 1.0]
mesher = "voronoi"
cells = 40

[[body]]
name = "UPPER"
rectangle = [0.0, 1.0, 1.0, 2.0]
mesher = "quad"
divisions = [3, 3]

[[contact]]
name = "IFACE"
slave = "{slave}"
master = "{master}"
y = 1.0
"""


@pytest.mark.parametrize("quads", ["vem", "fem"])
@pytest.mark.parametrize("order, slave", [(1, "UPPER"), (1, "LOWER"), (2, "UPPER"), (2, "LOWER")])
def test_voronoi_tied_to_quads_is_exact(exe, tmp_path, order, slave, quads):
    """Voronoi cells (VPE or VPE2) tied to 3 x 3 quads (VPE/VPE2, or CPE4/CPE8) along
    y = 1, the interfaces meshed independently; either side the slave (a node surface,
    IFACE_SLAVE).  The linear field prescribed at every boundary node is reproduced at
    every node, and each element's stress is the field's constant stress (plane
    strain), to 1e-10 (round-off, measured 1e-14).  With FEM quads as the slave, the
    closest-point tie missed by 8.7 % (k = 1) and 6.1 % (k = 2): the Voronoi master's
    nodes between the quads' were free."""
    from vctools.mesh.scene import mesh_scene_file
    master = "LOWER" if slave == "UPPER" else "UPPER"
    scene = tmp_path / "blocks.toml"
    text = VORONOI_SCENE.format(order=order, slave=slave, master=master)
    if quads == "fem":
        text = text.replace('mesher = "quad"', 'mesher = "quad"\nformulation = "fem"')
    scene.write_text(text)
    (path, m), = mesh_scene_file(scene, out=tmp_path / "blocks.inp", echo=None)
    lines = [f"*INCLUDE, INPUT={path}", "*TIE, NAME=GLUE", "IFACE_SLAVE, IFACE_MASTER",
             "*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}",
             "*SOLID SECTION, ELSET=LOWER, MATERIAL=M", "*SOLID SECTION, ELSET=UPPER, MATERIAL=M",
             "*BOUNDARY"]
    for k, (x, y) in enumerate(m.nodes[:, :2]):
        if min(abs(x), abs(x - 1.0), abs(y), abs(y - 2.0)) < 1e-12:
            ux, uy = exact_linear(x, y)
            lines += [f"{k + 1}, 1, 1, {float(ux)!r}", f"{k + 1}, 2, 2, {float(uy)!r}"]
    lines += ["*STEP", "*STATIC", "*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    run(exe, tmp_path, "\n".join(lines) + "\n")
    x, u, s = mesh(tmp_path)
    assert len(x) > len(m.nodes)
    ex = np.array([exact_linear(*p) for p in x])
    assert np.abs(u - ex).max() <= 1e-10 * np.abs(ex).max()
    # the constant stress of the linear field: strains (2, 0.7, -1.5) e-3, plane strain
    exx, eyy, gxy = 2e-3, 0.7e-3, -1.5e-3
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    want = [lam * (exx + eyy) + 2 * mu * exx, lam * (exx + eyy) + 2 * mu * eyy, lam * (exx + eyy), mu * gxy]
    assert np.abs(s - want).max() <= 1e-10 * np.abs(want).max()


ALPHA, T0, TX, TY = 1e-5, 100.0, 30.0, 50.0


def free_expansion(x, y):
    """The stress-free displacement of the temperature T = T0 + TX x + TY y (plane strain:
    in-plane strains (1 + nu) alpha T, compatible for a linear T)."""
    k = (1 + NU) * ALPHA
    return (k * (T0 * x + TX * x * x / 2 + TY * x * y - TX * y * y / 2),
            k * (T0 * y + TX * x * y + TY * y * y / 2 - TY * x * x / 2))


@pytest.mark.parametrize("left, right", [(("VPE", 1, 2), ("VPE", 1, 3)), (("VPE2", 2, 2), ("VPE2", 2, 3)),
                                         (("VPE2", 2, 3), ("VPE2", 2, 2))])
def test_tied_free_thermal_expansion(exe, tmp_path, left, right):
    """A temperature linear in x and y at every deck node, the outer corners held at the
    free expansion: no in-plane stress anywhere.  The nodes inserted into the faces take
    their temperature from the ends of the side they split (linear along it), as do the
    side nodes of a split second-order side; with T = T0 there, the polygons around them
    had in-plane stresses of 14 % of E alpha T (measured on the 2-against-3 VPE patch
    under a uniform T).  First order: the uniform part only (a linear T needs a
    quadratic displacement); second order: the whole linear T.  Tolerance 1e-10 of
    E alpha T (round-off: measured 2e-15 to 2e-14)."""
    lin = left[0] == "VPE2"
    text, nodes = deck(left, right, "tension")
    text = text[:text.index("*BOUNDARY")].replace(f"*ELASTIC\n{E}, {NU}\n", f"*ELASTIC\n{E}, {NU}\n*EXPANSION\n{ALPHA}\n")
    lines = ["*BOUNDARY"]
    for k, (x, y) in nodes.items():
        if x in (0.0, 2.0) and y in (0.0, 1.0):
            if lin:
                ux, uy = free_expansion(x, y)
            else:
                ux, uy = (1 + NU) * ALPHA * T0 * x, (1 + NU) * ALPHA * T0 * y
            lines += [f"{k}, 1, 1, {float(ux)!r}", f"{k}, 2, 2, {float(uy)!r}"]
    lines += ["*STEP", "*STATIC", "*TEMPERATURE"]
    lines += [f"{k}, {float(T0 + (TX * x + TY * y if lin else 0.0))!r}" for k, (x, y) in nodes.items()]
    lines += ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    run(exe, tmp_path, text + "\n".join(lines) + "\n")
    x, u, s = mesh(tmp_path)
    assert len(x) > len(nodes)
    scale = E * ALPHA * (T0 + TX + TY)
    assert np.abs(s[:, [0, 1, 3]]).max() <= 1e-10 * scale


def grid_block(x0, y0, w, h, n, m, first_node, first_elem):
    ids, nodes, elems = {}, {}, {}
    for j in range(m + 1):
        for i in range(n + 1):
            ids[i, j] = first_node + len(nodes)
            nodes[ids[i, j]] = (x0 + w * i / n, y0 + h * j / m)
    for j in range(m):
        for i in range(n):
            elems[first_elem + len(elems)] = (i, j, [ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]])
    return nodes, elems


@pytest.mark.parametrize("top", ["tie", "contact"])
def test_two_ties_meet(exe, tmp_path, top):
    """Three VEM blocks: A [0,1]^2 (2 x 2) and B [1,2] x [0,1] (3 x 3) tied along x = 1, and
    C [0,2] x [1,2] (5 x 4) on top of both, tied to A's and B's tops (one master surface)
    or in HARD SURFACE TO SURFACE contact with them.  The nodes at (1, 1) are in both
    interfaces (B's is a slave of the first tie and a master node of the second: the
    equations chain).  A linear field (tie) or uniform compression (contact, no shear)
    prescribed on the outer boundary: every node to 1e-10 (measured 3e-16 and 9e-16)."""
    a, b, c = grid_block(0, 0, 1, 1, 2, 2, 1, 1), grid_block(1, 0, 1, 1, 3, 3, 101, 101), \
        grid_block(0, 1, 2, 1, 5, 4, 201, 201)
    nodes = {**a[0], **b[0], **c[0]}
    field = exact_linear if top == "tie" else (lambda x, y: (0.0, -1e-3 * y))
    lines = ["*NODE"] + [f"{k}, {float(x)!r}, {float(y)!r}" for k, (x, y) in nodes.items()]
    for (_, els), name in ((a, "A"), (b, "B"), (c, "C")):
        lines += [f"*ELEMENT, TYPE=VPE, ELSET={name}"] + [", ".join(map(str, [e] + q)) for e, (_, _, q) in els.items()]
    lines += ["*SURFACE, NAME=AR"] + [f"{e}, S2" for e, (i, _, _) in a[1].items() if i == 1]
    lines += ["*SURFACE, NAME=BL"] + [f"{e}, S4" for e, (i, _, _) in b[1].items() if i == 0]
    lines += ["*SURFACE, NAME=ABTOP"] + [f"{e}, S3" for e, (_, j, _) in a[1].items() if j == 1]
    lines += [f"{e}, S3" for e, (_, j, _) in b[1].items() if j == 2]
    lines += ["*SURFACE, NAME=CBOT"] + [f"{e}, S1" for e, (_, j, _) in c[1].items() if j == 0]
    lines += ["*TIE, NAME=T1", "BL, AR"]
    if top == "tie":
        lines += ["*TIE, NAME=T2", "CBOT, ABTOP"]
    else:
        lines += ["*SURFACE INTERACTION, NAME=I", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD",
                  "*CONTACT PAIR, INTERACTION=I, TYPE=SURFACE TO SURFACE", "CBOT, ABTOP"]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}"]
    lines += [f"*SOLID SECTION, ELSET={n}, MATERIAL=M" for n in "ABC"] + ["*BOUNDARY"]
    for k, (x, y) in nodes.items():
        if min(abs(x), abs(x - 2), abs(y), abs(y - 2)) < 1e-12:
            ux, uy = field(x, y)
            lines += [f"{k}, 1, 1, {float(ux)!r}", f"{k}, 2, 2, {float(uy)!r}"]
    lines += ["*STEP", "*STATIC", "*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    run(exe, tmp_path, "\n".join(lines) + "\n")
    x, u, _ = mesh(tmp_path)
    assert len(x) == len(nodes) + 11     # 3 nodes inserted at x = 1, 8 at y = 1
    ex = np.array([field(*p) for p in x])
    assert np.abs(u - ex).max() <= 1e-10 * np.abs(ex).max()
