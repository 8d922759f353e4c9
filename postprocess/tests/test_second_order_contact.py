"""NODE TO SURFACE contact on second-order sides (VPE2, CPE8): two blocks with
matching meshes, the upper one pressed onto the lower one by a uniform pressure p.

The exact solution is a uniform stress (syy = -p, sxx = sxy = 0, szz = -nu p in
plane strain), a linear displacement field that both element families reproduce
exactly.  The slave face's nodes (corners and side nodes) carry the consistent
tributary lengths l/6, 4l/6, l/6 of their sides, and each master side is split
into its two straight halves, so on matching meshes every slave node sits on a
master node and transmits the consistent share of p: CPRESS = p at every slave
node, side nodes included, to round-off.  The element widths differ (0.7, 1.3
and 0.5) so that a wrong weight (for example half the side to each corner,
nothing to the side node) would show."""
import subprocess

import h5py
import numpy as np
import pytest

E, NU, P = 1000.0, 0.3, 5.0
XS = [0.0, 0.7, 2.0, 2.5]


def block(y0, first_node, first_elem):
    """Nodes and second-order quads of [0, 2.5] x [y0, y0 + 1], one row of
    elements of widths 0.7, 1.3, 0.5: corners first, then the side nodes in
    Abaqus' order (bottom, right, top, left)."""
    nodes, nid = {}, first_node

    def node(x, y):
        nonlocal nid
        if (x, y) not in nodes:
            nodes[(x, y)] = nid
            nid += 1
        return nodes[(x, y)]

    elems = []
    for i in range(len(XS) - 1):
        xa, xb, ya, yb = XS[i], XS[i + 1], y0, y0 + 1.0
        xm, ym = 0.5 * (xa + xb), 0.5 * (ya + yb)
        c = [node(xa, ya), node(xb, ya), node(xb, yb), node(xa, yb)]
        m = [node(xm, ya), node(xb, ym), node(xm, yb), node(xa, ym)]
        elems.append((first_elem + i, c + m))
    return nodes, elems


def deck(etype, behavior, slave):
    lo_nodes, lo_elems = block(0.0, 1, 1)
    up_nodes, up_elems = block(1.0, 101, 11)
    lines = ["*NODE"]
    for nodes in (lo_nodes, up_nodes):
        lines += [f"{n}, {x!r}, {y!r}" for (x, y), n in nodes.items()]
    for name, elems in (("LOWER", lo_elems), ("UPPER", up_elems)):
        lines.append(f"*ELEMENT, TYPE={etype}, ELSET={name}")
        lines += [", ".join(str(v) for v in [e] + conn) for e, conn in elems]
    # master: top of the lower block (S3); slave: bottom of the upper block (S1),
    # as an element surface or as the node set of the face (corners and side nodes)
    lines.append("*SURFACE, NAME=MASTER")
    lines += [f"{e}, S3" for e, _ in lo_elems]
    if slave == "element":
        lines.append("*SURFACE, NAME=SLAVE")
        lines += [f"{e}, S1" for e, _ in up_elems]
    else:
        face = [n for (x, y), n in up_nodes.items() if y == 1.0]
        lines.append("*NSET, NSET=FACE")
        lines.append(", ".join(str(n) for n in face))
        lines.append("*SURFACE, NAME=SLAVE, TYPE=NODE")
        lines.append("FACE")
    left = [n for nodes in (lo_nodes, up_nodes) for (x, y), n in nodes.items() if x == 0.0]
    bottom = [n for (x, y), n in lo_nodes.items() if y == 0.0]
    lines += ["*NSET, NSET=LEFT", ", ".join(map(str, left)),
              "*NSET, NSET=BOTTOM", ", ".join(map(str, bottom)),
              "*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}",
              "*SOLID SECTION, ELSET=LOWER, MATERIAL=M", "1.0",
              "*SOLID SECTION, ELSET=UPPER, MATERIAL=M", "1.0",
              "*SURFACE INTERACTION, NAME=I"]
    if behavior == "HARD":
        lines.append("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD")
    else:
        lines += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.0e6"]
    lines += ["*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE", "SLAVE, MASTER",
              "*BOUNDARY", "LEFT, 1", "BOTTOM, 2",
              "*STEP", "*STATIC", "*DLOAD"]
    lines += [f"{e}, P3, {P}" for e, _ in up_elems]
    lines += ["*END STEP", ""]
    return "\n".join(lines)


@pytest.mark.parametrize("etype,behavior,slave", [
    ("VPE2", "LINEAR", "element"),
    ("VPE2", "HARD", "element"),
    ("VPE2", "LINEAR", "node"),
    ("CPE8", "LINEAR", "element"),
    ("CPE8", "HARD", "node"),
])
def test_uniform_pressure_through_second_order_sides(exe, tmp_path, etype, behavior, slave):
    inp = tmp_path / "k2c.inp"
    inp.write_text(deck(etype, behavior, slave))
    r = subprocess.run([exe, "-q", "-o", str(tmp_path), str(inp)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "k2c.h5") as f:
        c = f["steps/0001/contact/pair_1"]
        cpress = np.array(c["CPRESS"])
        cnarea = np.array(c["CNAREA"])
        ids = np.array(c["node_ids"]) if "node_ids" in c else None
        s = np.array(f["steps/0001/S_element"])
    # every node of the face is a slave node: 4 corners and 3 side nodes
    assert cpress.size == 7, ids
    # consistent tributary lengths: l/6 at a corner per side, 4l/6 at a side node
    w = np.diff(XS)
    expect = np.sort(np.concatenate([[w[0] / 6, (w[0] + w[1]) / 6, (w[1] + w[2]) / 6, w[2] / 6],
                                     4 * w / 6]))
    assert np.sort(cnarea) == pytest.approx(expect, rel=1e-14)
    # the uniform pressure is transmitted exactly (round-off of a penalty of 1e6
    # against E = 1e3: ~1e-12 relative; 1e-8 as the issue asks)
    assert np.abs(cpress - P).max() <= 1e-8 * P
    # element stresses exact in both blocks: syy = -p, szz = -nu p, sxx = sxy = 0
    assert np.abs(s[:, 1] + P).max() <= 1e-8 * P
    assert np.abs(s[:, 2] + NU * P).max() <= 1e-8 * P
    assert np.abs(s[:, [0, 3]]).max() <= 1e-8 * P

