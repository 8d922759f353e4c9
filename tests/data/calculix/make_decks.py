"""Writes the CalculiX-style decks of tests/data/calculix (run once; the decks are stored).

The decks are written as a CalculiX user writes them (heading, sets by GENERATE and by
name, *DSLOAD on element faces, output requests) and run unmodified in both CalculiX and
vemcontact (postprocess/tests/test_calculix_decks.py).

    python tests/data/calculix/make_decks.py
    # the stored CalculiX results (ccx 2.20, Debian package calculix-ccx):
    cd /tmp && for d in plate_hole_cpe4 plate_hole_cpe3 two_blocks_contact; do
      cp $OLDPWD/tests/data/calculix/$d.inp . && ccx -i $d; done
    python -c "import make_decks as m; m.write_reference('/tmp/D.dat', 'D.ccx.csv')"   # per deck D
    # the friction deck (two steps, contact results too):
    cd /tmp && cp $OLDPWD/tests/data/calculix/two_blocks_friction.inp . && ccx -i two_blocks_friction
    python -c "import make_decks as m; m.write_friction_reference('/tmp/two_blocks_friction.dat',
        'two_blocks_friction', m.deck_node_ids('two_blocks_friction.inp'))"
"""
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def plate_nodes(a=1.0, w=4.0, nt=8, ns=6):
    """Quarter plate [0, w]^2 with a hole of radius a at the origin: nt + 1 radial lines
    from the hole (s = 0) to the outer edges (s = 1), ns + 1 nodes on each, graded
    towards the hole.  Node id = 1 + j + (ns + 1) * i on radial line i, position j."""
    xy = []
    for i in range(nt + 1):
        t = 0.5 * np.pi * i / nt
        c = a * np.array([np.cos(t), np.sin(t)])
        if t <= np.pi / 4:
            o = np.array([w, w * np.tan(t)])
        else:
            o = np.array([w / np.tan(t), w])
        for j in range(ns + 1):
            s = (j / ns) ** 1.5
            xy.append((1 - s) * c + s * o)
    return np.array(xy)


def fmt(v):
    return f"{v:.12g}"


def plate_deck(kind, a=1.0, w=4.0, nt=8, ns=6, stress=100.0):
    xy = plate_nodes(a, w, nt, ns)
    nid = lambda i, j: 1 + j + (ns + 1) * i  # noqa: E731
    lines = ["*HEADING", f"Quarter plate with a hole, {kind}, remote tension {stress:g} in x",
             "** symmetric about x = 0 and y = 0; hole radius 1, plate half-width 4",
             "*NODE, NSET=NALL"]
    lines += [f"{k + 1}, {fmt(x)}, {fmt(y)}" for k, (x, y) in enumerate(xy)]
    # quads counter-clockwise: radial line i (lower angle) to i + 1
    quads = []
    for i in range(nt):
        for j in range(ns):
            quads.append((nid(i, j), nid(i, j + 1), nid(i + 1, j + 1), nid(i + 1, j)))
    right = []  # elements with a side on x = w, and that side's label
    if kind == "CPE4":
        lines.append("*ELEMENT, TYPE=CPE4, ELSET=EALL")
        for e, q in enumerate(quads):
            lines.append(f"{e + 1}, " + ", ".join(map(str, q)))
            i, j = divmod(e, ns)
            if j == ns - 1 and i < nt // 2:
                right.append((e + 1, "S2"))
    else:
        lines.append("*ELEMENT, TYPE=CPE3, ELSET=EALL")
        for e, (n1, n2, n3, n4) in enumerate(quads):
            lines.append(f"{2 * e + 1}, {n1}, {n2}, {n3}")
            lines.append(f"{2 * e + 2}, {n1}, {n3}, {n4}")
            i, j = divmod(e, ns)
            if j == ns - 1 and i < nt // 2:
                right.append((2 * e + 1, "S2"))
    # y = 0 is radial line 0, x = 0 radial line nt: generated sets
    lines += ["*NSET, NSET=YSYM, GENERATE", f"{nid(0, 0)}, {nid(0, ns)}, 1",
              "*NSET, NSET=XSYM, GENERATE", f"{nid(nt, 0)}, {nid(nt, ns)}",
              "*NSET, NSET=HOLE, GENERATE", f"{nid(0, 0)}, {nid(nt, 0)}, {ns + 1}",
              "*ELSET, ELSET=ERIGHT"]
    lines += [", ".join(str(e) for e, _ in right)]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL", "1.",
              "*SURFACE, NAME=SRIGHT, TYPE=ELEMENT", "ERIGHT, S2",
              "*BOUNDARY", "XSYM, 1", "YSYM, 2, 2", "*BOUNDARY", "NALL, 3, 3, 0.",
              "*STEP", "*STATIC",
              "*DSLOAD", f"SRIGHT, P, {fmt(-stress)}",
              "*NODE FILE", "U, RF", "*EL FILE", "S, E",
              "*NODE PRINT, NSET=NALL", "U", "*NODE PRINT, NSET=XSYM, TOTALS=YES", "RF",
              "*EL PRINT, ELSET=EALL", "S",
              "*END STEP"]
    return "\n".join(lines) + "\n"


def block(x0, y0, wx, hy, nx, ny, nfirst, efirst):
    """Structured CPE4 block: node and element ids from nfirst and efirst."""
    nodes, elems = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            nodes.append((nfirst + i + (nx + 1) * j, x0 + wx * i / nx, y0 + hy * j / ny))
    for j in range(ny):
        for i in range(nx):
            n1 = nfirst + i + (nx + 1) * j
            elems.append((efirst + i + nx * j, n1, n1 + 1, n1 + nx + 2, n1 + nx + 1))
    return nodes, elems


def blocks_deck(pressure=0.1, k=1.0e6, sigma_inf=2.5e-4):
    """A lower block 2 x 1 fixed at its bottom and an upper block 1 x 1 on it (4 x 4
    elements, the upper mesh not matching the lower), pressed down by a pressure on
    its top; the upper block is held in x at its left edge only.  The load keeps the
    displacements at 1e-4 of the block size: ccx measures its contact areas and gaps in
    the current configuration, vemcontact in the undeformed one (docs/calculix-comparison.md),
    which at a 100 times larger load differ by 1e-3 of the displacements.  sigma_inf is
    the manual's 0.25 % of the largest stress."""
    lo_n, lo_e = block(0.0, 0.0, 2.0, 1.0, 8, 4, 1, 1)
    up_n, up_e = block(0.5, 1.0, 1.0, 1.0, 5, 4, 101, 101)
    lines = ["*HEADING", "Two blocks in contact: an upper block pressed onto a lower block",
             "*NODE, NSET=NLOWER"]
    lines += [f"{n}, {fmt(x)}, {fmt(y)}" for n, x, y in lo_n]
    lines += ["*NODE, NSET=NUPPER"]
    lines += [f"{n}, {fmt(x)}, {fmt(y)}" for n, x, y in up_n]
    lines += ["*ELEMENT, TYPE=CPE4, ELSET=ELOWER"]
    lines += [", ".join(map(str, e)) for e in lo_e]
    lines += ["*ELEMENT, TYPE=CPE4, ELSET=EUPPER"]
    lines += [", ".join(map(str, e)) for e in up_e]
    lines += ["*ELSET, ELSET=EALL", "ELOWER, EUPPER",
              "*NSET, NSET=BOTTOM, GENERATE", "1, 9",
              "*NSET, NSET=UPLEFT, GENERATE", "101, 125, 6",
              "*ELSET, ELSET=LOWTOP, GENERATE", "25, 32",
              "*ELSET, ELSET=UPBOT, GENERATE", "101, 105",
              "*ELSET, ELSET=UPTOP, GENERATE", "116, 120",
              "*MATERIAL, NAME=SOFT", "*ELASTIC", "1000., 0.3",
              "*MATERIAL, NAME=HARD", "*ELASTIC", "5000., 0.25",
              "*SOLID SECTION, ELSET=ELOWER, MATERIAL=HARD", "1.",
              "*SOLID SECTION, ELSET=EUPPER, MATERIAL=SOFT", "1.",
              "*SURFACE, NAME=SLAVE", "UPBOT, S1",
              "*SURFACE, NAME=MASTER", "LOWTOP, S3",
              "*SURFACE, NAME=TOP", "UPTOP, S3",
              "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{k:g}, {sigma_inf:g}, 1e-3",
              "*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE", "SLAVE, MASTER",
              "*BOUNDARY", "BOTTOM, 1, 2", "UPLEFT, 1", "*BOUNDARY", "NLOWER, 3", "NUPPER, 3",
              "*STEP", "*STATIC",
              "*DSLOAD", f"TOP, P, {fmt(pressure)}",
              "*NODE FILE", "U", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR",
              "*NODE PRINT, NSET=NUPPER", "U", "*NODE PRINT, NSET=NLOWER", "U",
              "*CONTACT PRINT", "CSTR, CDIS",
              "*END STEP"]
    return "\n".join(lines) + "\n"


def friction_blocks_deck(pressure=0.1, k=1.0e6, sigma_inf=2.5e-4, mu=0.2, slope=1.0e4, push=2.0e-4):
    """The two blocks of blocks_deck with Coulomb friction (mu, stick slope): step 1
    presses the upper block down as there (its left edge held in x); step 2 keeps the
    pressure and moves the upper block's left edge by `push` along x in 5 fixed
    increments, dragging it along the lower block: the elastic slip allowed by the
    stick slope (mu p / slope = 2e-6 at p = 0.1) is a hundredth of the push, so the
    joint slips (|CSHEAR| = mu CPRESS) where it is pressed and the push is small
    enough (1e-4 of the block size) for ccx's current configuration to stay the
    undeformed one to 1e-4."""
    text = blocks_deck(pressure, k, sigma_inf)
    text = text.replace("Two blocks in contact: an upper block pressed onto a lower block",
                        "Two blocks in contact with Coulomb friction: pressed, then dragged along x")
    text = text.replace(f"{k:g}, {sigma_inf:g}, 1e-3\n",
                        f"{k:g}, {sigma_inf:g}, 1e-3\n*FRICTION\n{fmt(mu)}, {fmt(slope)}\n")
    # vemcontact combines friction with the pairing of the undeformed state only
    text = text.replace("TYPE=NODE TO SURFACE\n", "TYPE=NODE TO SURFACE, SMALL SLIDING\n")
    text = text.replace("*CONTACT PRINT\nCSTR, CDIS\n*END STEP\n", "*CONTACT PRINT\nCSTR, CDIS\n*END STEP\n"
                        "*STEP\n*STATIC, DIRECT\n0.2, 1.\n*BOUNDARY\n"
                        f"UPLEFT, 1, 1, {fmt(push)}\n*END STEP\n")
    return text


def ccx_displacements(dat):
    """{node id: (ux, uy)} from the *NODE PRINT blocks of a ccx .dat file."""
    out, on = {}, False
    for line in Path(dat).read_text().splitlines():
        t = line.split()
        if line.strip().startswith("displacements"):
            on = True
        elif len(t) == 4 and on and t[0].isdigit():
            out[int(t[0])] = (float(t[1]), float(t[2]))
        elif t:
            on = False
    return out


def ccx_tables(dat):
    """Every table of a ccx .dat file as (title, time, {id: values}), in file order."""
    out = []
    for line in Path(dat).read_text().splitlines():
        t = line.split()
        if " time " in line and not t[0].replace(".", "").isdigit():
            out.append((line.split("(")[0].strip(), float(t[-1]), {}))
        elif t and out and t[0].isdigit():
            out[-1][2][int(t[0])] = tuple(float(v) for v in t[1:])
    return out


def ccx_step_results(dat, times, node_ids):
    """Per step end time: {node: (ux, uy)} and {slave node: (press, tang1, slip1)} of
    a 2D deck.  ccx prints contact results at the nodes of its expanded 3D mesh: the
    node with the k-th smallest id of the deck (k from 0) becomes nodes m + 3k + 1,
    m + 3k + 2, m + 3k + 3 (m the largest id; the first and last on the faces z = -t/2
    and t/2, which carry the contact); the two face values are averaged (they differ
    at the surface's ends, where ccx's 3D contact is not uniform through the
    thickness: up to 1.4 % here)."""
    ids = sorted(node_ids)
    m = ids[-1]
    res = []
    for time in times:
        tabs = {title: vals for title, tt, vals in ccx_tables(dat) if abs(tt - time) < 1e-9}
        u = {}
        for title, vals in tabs.items():
            if title.startswith("displacements"):
                u.update({n: v[:2] for n, v in vals.items()})
        stress, slip = tabs["contact stress"], tabs["relative contact displacement"]
        contact = {}
        for e in stress:
            k, r = divmod(e - m - 1, 3)
            if r == 0:
                other = e + 2
                press = 0.5 * (stress[e][0] + stress[other][0])
                tang = 0.5 * (stress[e][1] + stress[other][1])
                s1 = 0.5 * (slip[e][1] + slip[other][1])
                contact[ids[k]] = (press, tang, s1)
        res.append((u, contact))
    return res


def write_friction_reference(dat, stem, node_ids, times=(1.0, 2.0)):
    """The ccx results of the friction deck: STEM.ccx.csv (step,node,ux,uy) and
    STEM.ccx_contact.csv (step,node,CPRESS,CSHEAR,CSLIP: ccx's press, tang1 and the
    relative tangential displacement tang1)."""
    rows_u, rows_c = ["step,node,ux,uy"], ["step,node,CPRESS,CSHEAR,CSLIP"]
    for step, (u, contact) in enumerate(ccx_step_results(dat, times, node_ids), start=1):
        rows_u += [f"{step},{n},{u[n][0]:.6E},{u[n][1]:.6E}" for n in sorted(u)]
        rows_c += [f"{step},{n},{v[0]:.6E},{v[1]:.6E},{v[2]:.6E}" for n, v in sorted(contact.items())]
    Path(f"{stem}.ccx.csv").write_text("\n".join(rows_u) + "\n")
    Path(f"{stem}.ccx_contact.csv").write_text("\n".join(rows_c) + "\n")


def deck_node_ids(inp):
    """The node ids of a deck's *NODE blocks."""
    ids, on = [], False
    for line in Path(inp).read_text().splitlines():
        if line.startswith("*"):
            on = line.upper().startswith("*NODE") and not line.upper().startswith(("*NODE FILE", "*NODE PRINT"))
        elif on and line.strip():
            ids.append(int(line.split(",")[0]))
    return ids


def write_reference(dat, csv):
    """The ccx displacements as node,ux,uy (the stored reference when ccx is absent)."""
    u = ccx_displacements(dat)
    rows = ["node,ux,uy"] + [f"{n},{u[n][0]:.6E},{u[n][1]:.6E}" for n in sorted(u)]
    Path(csv).write_text("\n".join(rows) + "\n")


if __name__ == "__main__":
    (HERE / "plate_hole_cpe4.inp").write_text(plate_deck("CPE4"))
    (HERE / "plate_hole_cpe3.inp").write_text(plate_deck("CPE3"))
    (HERE / "two_blocks_contact.inp").write_text(blocks_deck())
    (HERE / "two_blocks_friction.inp").write_text(friction_blocks_deck())
