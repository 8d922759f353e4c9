#!/usr/bin/env python3
"""Write the CalculiX deck of the Hertz comparison from vemcontact's Hertz deck.

    make_hertz.py DECK.inp OUTDIR [--sigma-inf S] [--c0 C] [--finite-sliding]

DECK is one of inputs/hertz_*_fem.inp (disc R = 10 on a block, half model, CPE4,
K = 1e5, P = 100 on the half disc).  Written: OUTDIR/ccx.inp and OUTDIR/mesh.inp
(the deck's mesh file, copied: CalculiX resolves *INCLUDE against the working
directory, vemcontact against the including file).  The model lines are those of
the vemcontact deck, with these changes, all needed by CalculiX:

* the slave: vemcontact's deck uses the node surface HERTZ_SLAVE; CalculiX's
  node-to-face spring takes its force area from the slave's element faces (for a
  node surface it falls back to the master face area), so the CalculiX deck gets
  the element surface HERTZ_SLAVE_FACES: the boundary sides of DISC elements with
  both end nodes in the node set.  These are exactly the edges from which
  vemcontact computes the tributary lengths of a node surface
  (docs/contact-formulation.md), so both codes load the same areas.
* *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR: K, sigma_inf, c0.  CalculiX's
  node-to-face law is the smoothed ramp p = K h (1/2 + atan(h/eps)/pi) with
  eps = pi sigma_inf / K (springforc_n2f.f): p -> K h - sigma_inf for h >> eps and
  a tension sigma_inf at large clearance.  sigma_inf <= 0 is replaced by a default;
  here sigma_inf = 1e-5 (1.2e-7 of the peak pressure 83.6), eps = 3e-10, 4e-7 of
  the peak overclosure (Newton still converges in 5 iterations).  c0: a spring is
  generated only for clearances below c0 sqrt(slave area) (default 1e-3); c0 = 10
  gives every slave node a spring from the start, like vemcontact's candidates.
* *CONTACT PAIR gets SMALL SLIDING: CalculiX then pairs the slave nodes and
  computes their areas once per increment, from the configuration at its start
  (gencontelem_n2f.f: co + vold); with the single increment of the step below
  these are the undeformed areas, as vemcontact's (which accepts and ignores
  SMALL SLIDING).  Without it the areas are recomputed every iteration on the
  deformed surface, a large-deformation effect: the disc's contact faces shrink
  laterally by about 3 % and the peak pressure rises by as much (86.95 against
  84.49 on the 389 mesh).  --finite-sliding leaves SMALL SLIDING out, for that
  comparison.
* FORMULATION=FEM (a vemcontact parameter) is dropped from *SOLID SECTION.
* the step is nonlinear in CalculiX (contact springs): *STATIC with automatic
  increments (initial 1, period 1), INC=1000, no NLGEOM (small strains as in
  vemcontact).  The spring's clearance is still measured between current
  positions (springforc_n2f.f), where vemcontact linearises the gap about the
  undeformed pairing: the slave nodes slide up to 0.03 along the (slightly
  deflected) master, which shows at the edge of the contact zone.
* output: *CONTACT PRINT, CSTR (pressure per slave spring element) and
  *NODE PRINT, U of the slave nodes.
"""
import argparse
import pathlib
import re
import shutil


def read_mesh(path):
    """Node sets and DISC elements (id -> nodes) from a vctools mesh file."""
    nsets, elems = {}, {}
    key, name, elset = None, None, None
    for raw in path.read_text().splitlines():
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            up = line.upper().replace(" ", "")
            key = up.split(",")[0]
            m = re.search(r"NSET=([^,]+)", up)
            name = m.group(1) if key == "*NSET" and m else None
            m = re.search(r"ELSET=([^,]+)", up)
            elset = m.group(1) if key == "*ELEMENT" and m else None
            if name is not None:
                nsets.setdefault(name, [])
            continue
        f = [t.strip() for t in line.split(",") if t.strip()]
        if key == "*NSET" and name:
            nsets[name] += [int(t) for t in f]
        elif key == "*ELEMENT" and elset == "DISC":
            elems[int(f[0])] = [int(t) for t in f[1:]]
    return nsets, elems


def slave_faces(nsets, elems):
    """Boundary sides (used once) of the disc with both nodes in HERTZ_SLAVE."""
    s = set(nsets["HERTZ_SLAVE"])
    count = {}
    for e, nodes in elems.items():
        for k in range(len(nodes)):
            a, b = nodes[k], nodes[(k + 1) % len(nodes)]
            count[frozenset((a, b))] = count.get(frozenset((a, b)), 0) + 1
    out = []
    for e, nodes in sorted(elems.items()):
        for k in range(len(nodes)):
            a, b = nodes[k], nodes[(k + 1) % len(nodes)]
            if a in s and b in s and count[frozenset((a, b))] == 1:
                out.append((e, k + 1))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("deck", type=pathlib.Path)
    ap.add_argument("outdir", type=pathlib.Path)
    ap.add_argument("--sigma-inf", type=float, default=1e-5)
    ap.add_argument("--c0", type=float, default=10.0)
    ap.add_argument("--finite-sliding", action="store_true")
    a = ap.parse_args()
    a.outdir.mkdir(parents=True, exist_ok=True)
    text = a.deck.read_text()
    inc = re.search(r"^\*INCLUDE,\s*INPUT=(\S+)", text, re.M | re.I)
    mesh = (a.deck.parent / inc.group(1)).resolve()
    shutil.copy(mesh, a.outdir / "mesh.inp")
    nsets, elems = read_mesh(mesh)
    faces = slave_faces(nsets, elems)
    out = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        up = line.upper().replace(" ", "")
        if up.startswith("*INCLUDE"):
            out.append("*INCLUDE, INPUT=mesh.inp")
            out.append("*SURFACE, NAME=HERTZ_SLAVE_FACES, TYPE=ELEMENT")
            out += [f"{e}, S{k}" for e, k in faces]
        elif up.startswith("*SOLIDSECTION"):
            out.append(re.sub(r",\s*FORMULATION=\w+", "", line, flags=re.I))
        elif up.startswith("*SURFACEBEHAVIOR"):
            out.append(line)
            i += 1
            k = lines[i].split(",")[0].strip()
            out.append(f"{k}, {float(a.sigma_inf)!r}, {float(a.c0)!r}")
        elif up.startswith("*CONTACTPAIR"):
            out.append(line.rstrip() + ("" if a.finite_sliding else ", SMALL SLIDING"))
            i += 1
            slave, master = [t.strip() for t in lines[i].split(",")]
            assert slave.upper() == "HERTZ_SLAVE", slave
            out.append(f"HERTZ_SLAVE_FACES, {master}")
        elif up.startswith("*STATIC"):
            out += ["*STATIC", "1.0, 1.0"]
        elif up.startswith("*ENDSTEP"):
            out += ["*NODE PRINT, NSET=HERTZ_SLAVE", "U", "*CONTACT PRINT", "CSTR", line]
        elif up.startswith("*STEP"):
            out.append("*STEP, INC=1000")
        else:
            out.append(line)
        i += 1
    (a.outdir / "ccx.inp").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
