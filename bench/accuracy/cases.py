"""The five cases: their mesh sequences per family, the decks, and the measured errors.

A case yields runs: (family, level label, mesh file, deck text, metrics function).
Families: vem-voronoi (VEM on the mesher's Voronoi cells), vem-quad (VEM on structured
quads), fem-quad (bilinear quads, 2x2 Gauss), fem-tri (constant-strain triangles: the
same quads split).  The section's FORMULATION picks VEM or FEM on the same VPE/VPS mesh.
"""
from __future__ import annotations

import math
import os

import numpy as np

import fields
import meshes

FAMILIES = ("vem-voronoi", "vem-quad", "fem-quad", "fem-tri")
# second-order families (issue 13): k = 2 VEM (VPE2/VPS2) on the same Voronoi cells and
# quads, serendipity quads (CPE8/CPS8) and 6-node triangles (CPE6/CPS6); the meshes are
# the mesher's `order = 2` ones (a node in the middle of every side)
FAMILIES2 = ("vem2-voronoi", "vem2-quad", "fem-q8", "fem-t6")
LINEAR_FAMILIES = FAMILIES + FAMILIES2
FORMULATION = {"vem-voronoi": "VEM", "vem-quad": "VEM", "fem-quad": "FEM", "fem-tri": "FEM",
               "vem2-voronoi": "VEM", "vem2-quad": "VEM", "fem-q8": "FEM", "fem-t6": "FEM"}
SHAPE = {"vem-voronoi": "voronoi", "vem-quad": "quad", "fem-quad": "quad", "fem-tri": "tri",
         "vem2-voronoi": "voronoi", "vem2-quad": "quad", "fem-q8": "quad", "fem-t6": "tri"}
ORDER = {f: (2 if f in FAMILIES2 else 1) for f in FORMULATION}


def _mesh_args(fam):
    """Mesh-file tag suffix and the mesher's formulation/order for a family: first-order
    meshes are VPE/VPS whatever the FEM/VEM choice (the section decides); second-order
    FEM meshes are written as CPE8/CPE6 (the mesher's FEM types)."""
    if ORDER[fam] == 1:
        return "", "vem", 1
    return ("_v2" if FORMULATION[fam] == "VEM" else "_f2"), FORMULATION[fam].lower(), 2

# Contact formulations of the contact cases (Hertz, interface): a family "base+variant"
# runs the base family's mesh with that formulation; the plain base family is the
# node-to-segment penalty of the paper (LINEAR, the deck's K).
#   nts-hard  TYPE=NODE TO SURFACE, PRESSURE-OVERCLOSURE=HARD (augmented Lagrangian)
#   s2s-hard  TYPE=SURFACE TO SURFACE (interface nodes inserted, VEM only), HARD
CONTACT_VARIANTS = {"": ("NODE TO SURFACE", "LINEAR"), "nts-hard": ("NODE TO SURFACE", "HARD"),
                    "s2s-hard": ("SURFACE TO SURFACE", "HARD")}


def split_family(fam):
    """'vem-quad+s2s-hard' -> ('vem-quad', 's2s-hard'); 'vem-quad' -> ('vem-quad', '')."""
    base, _, var = fam.partition("+")
    return base, var


def contact_deck(deck, variant):
    """The deck with the contact formulation of `variant` (the penalty deck unchanged for
    ''): the pair's TYPE, and HARD without the data line of LINEAR."""
    if not variant:
        return deck
    ctype, behavior = CONTACT_VARIANTS[variant]
    deck = deck.replace("TYPE=NODE TO SURFACE", f"TYPE={ctype}")
    if behavior == "HARD":
        lines = deck.split("\n")
        i = next(k for k, ln in enumerate(lines) if ln.upper().startswith("*SURFACE BEHAVIOR"))
        lines[i] = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"
        del lines[i + 1]                                      # the LINEAR slope K
        deck = "\n".join(lines)
    return deck


class Run:
    def __init__(self, case, family, level, mesh_desc, deck, metrics, elements=None):
        self.case, self.family, self.level = case, family, level
        self.mesh_desc, self.deck, self.metrics, self.elements = mesh_desc, deck, metrics, elements


def _rel_include(deck_dir, mesh_path):
    return os.path.relpath(mesh_path, deck_dir)


def _header(title, mesh_rel, E, nu, formulation, density=False):
    s = (f"** accuracy study (bench/accuracy): {title}\n*HEADING\n{title}\n"
         f"*INCLUDE, INPUT={mesh_rel}\n*MATERIAL, NAME=M\n*ELASTIC\n{E!r}, {nu!r}\n")
    if density:
        s += "*DENSITY\n1.0\n"
    s += f"*SOLID SECTION, ELSET=B, MATERIAL=M, FORMULATION={formulation}\n1.0\n"
    return s


def _boundary_nodes(m, pred):
    return [int(i) for i, (x, y) in zip(m.ids, m.xy) if pred(x, y)]


# ----------------------------------------------------------------- manufactured
def manufactured(work, quick=False, families=LINEAR_FAMILIES):
    case = fields.Manufactured()
    fields.check_exact(case)
    ns = [8, 16, 32, 64, 128, 256] if not quick else [8, 16, 32]
    # second order: the quadratic field is in the discrete space (exact up to round-off
    # on every mesh), so three coarse levels show it
    ns2 = [4, 8, 16] if not quick else [4, 8]
    b = case.body_force()
    g, d = float(np.linalg.norm(b)), b / np.linalg.norm(b)
    for fam in families:
        levels = list(ns if ORDER[fam] == 1 else ns2)
        if fam == "fem-tri" and not quick:
            levels.append(512)             # the cheapest element per unknown: one more level
        sfx, mform, order = _mesh_args(fam)
        for n in levels:
            shape = SHAPE[fam]
            if shape == "voronoi":
                mp = meshes.rectangle(work + "/meshes", f"ms_vor{sfx}_{n * n}", (0, 0, 1, 1), "voronoi", n * n,
                                      lloyd=20 if n <= 128 else 10, formulation=mform, order=order)
                desc = f"{n * n} Voronoi cells"
            else:
                mp = meshes.rectangle(work + "/meshes", f"ms_{shape}{sfx}_{n}", (0, 0, 1, 1), shape, (n, n),
                                      formulation=mform, order=order)
                desc = f"{n}x{n} {'quads' if shape == 'quad' else 'quads split in 2 triangles'}"
            m = meshes.read_inp(mp)
            deck = _header("manufactured quadratic solution", _rel_include(work + "/decks", mp),
                           case.E, case.nu, FORMULATION[fam], density=True)
            tol = 1e-9
            bn = _boundary_nodes(m, lambda x, y: min(x, y, 1 - x, 1 - y) < tol)
            u = case.u(m.xy[:, 0], m.xy[:, 1])
            lines = ["*BOUNDARY"]
            for i in bn:
                k = m.index[i]
                lines += [f"{i}, 1, 1, {u[k, 0]!r}", f"{i}, 2, 2, {u[k, 1]!r}"]
            deck += "\n".join(lines) + f"\n*STEP\n*STATIC\n*DLOAD\nB, GRAV, {g!r}, {d[0]!r}, {d[1]!r}\n*END STEP\n"

            def metrics(res, case=case, order=order):
                return dict(energy=fields.energy_error(res, case, order), u_l2=fields.u_l2_error(res, case, order))
            yield Run("manufactured", fam, n, desc, deck, metrics, len(m.elems))


# ----------------------------------------------------------------- Timoshenko
def _edge_forces(ys, traction, order=1):
    """Consistent nodal forces of a traction t(y) on the edge nodes at heights ys
    (sorted): int t N_i dy with linear N_i, by 3-point Gauss (exact for t quadratic).
    order 2: the nodes alternate corner, side middle, corner (each side has its middle
    node) and N_i are the quadratic shape functions of a side (3-point Gauss is exact
    for degree 5 >= 2 + 2)."""
    gp = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
    gw = np.array([5, 8, 5]) / 9
    f = np.zeros(len(ys))
    if order == 2:
        for k in range(0, len(ys) - 2, 2):
            y0, y1 = ys[k], ys[k + 2]
            h = y1 - y0
            s = (gp + 1) / 2
            t = traction(y0 + s * h)
            for j, N in enumerate(((1 - s) * (1 - 2 * s), 4 * s * (1 - s), s * (2 * s - 1))):
                f[k + j] += (gw * t * N).sum() * h / 2
        return f
    for k in range(len(ys) - 1):
        y0, y1 = ys[k], ys[k + 1]
        h = y1 - y0
        s = (gp + 1) / 2                     # 0..1
        t = traction(y0 + s * h)
        f[k] += (gw * t * (1 - s)).sum() * h / 2
        f[k + 1] += (gw * t * s).sum() * h / 2
    return f


def timoshenko(work, quick=False, families=LINEAR_FAMILIES):
    case = fields.Timoshenko()
    fields.check_exact(case, pts=[(5.0, 1.0), (20.0, -3.0), (40.0, 4.5)])
    ks = [2, 4, 8, 16, 32, 64] if not quick else [2, 4, 8]    # ny = k, nx = 4k
    ks2 = [1, 2, 4, 8, 16, 32] if not quick else [1, 2, 4]
    L, D = case.L, case.D
    for fam in families:
        levels = list(ks if ORDER[fam] == 1 else ks2)
        if fam == "fem-tri" and not quick:
            levels.append(128)
        sfx, mform, order = _mesh_args(fam)
        for k in levels:
            shape = SHAPE[fam]
            box = (0.0, -D / 2, L, D / 2)
            if shape == "voronoi":
                cells = 4 * k * k
                mp = meshes.rectangle(work + "/meshes", f"tc_vor{sfx}_{cells}", box, "voronoi", cells,
                                      plane="stress", lloyd=20 if cells <= 20000 else 10,
                                      formulation=mform, order=order)
                desc = f"{cells} Voronoi cells"
            else:
                mp = meshes.rectangle(work + "/meshes", f"tc_{shape}{sfx}_{k}", box, shape, (4 * k, k),
                                      plane="stress", formulation=mform, order=order)
                desc = f"{4 * k}x{k} {'quads' if shape == 'quad' else 'quads split in 2 triangles'}"
            m = meshes.read_inp(mp)
            deck = _header("Timoshenko cantilever, parabolic end shear", _rel_include(work + "/decks", mp),
                           case.E, case.nu, FORMULATION[fam])
            tol = 1e-9 * L
            clamp = _boundary_nodes(m, lambda x, y: x < tol)
            tip = [i for i in _boundary_nodes(m, lambda x, y: x > L - tol)]
            tip.sort(key=lambda i: m.xy[m.index[i], 1])
            ys = np.array([m.xy[m.index[i], 1] for i in tip])
            f = _edge_forces(ys, lambda y: case.P / (2 * case.I) * (D * D / 4 - y * y), order)
            u = case.u(m.xy[:, 0], m.xy[:, 1])
            lines = ["*BOUNDARY"]
            for i in clamp:
                kk = m.index[i]
                lines += [f"{i}, 1, 1, {u[kk, 0]!r}", f"{i}, 2, 2, {u[kk, 1]!r}"]
            lines += ["*STEP", "*STATIC", "*CLOAD"]
            lines += [f"{i}, 2, {fi!r}" for i, fi in zip(tip, f) if fi != 0.0]
            deck += "\n".join(lines) + "\n*END STEP\n"

            def metrics(res, case=case, tipy=ys, L=L, order=order):
                x = res["x"]
                on = np.abs(x[:, 0] - L) < 1e-9 * L
                srt = np.argsort(x[on, 1])
                uy = np.interp(0.0, x[on, 1][srt], res["U"][on, 1][srt])
                return dict(tip=abs(uy - case.tip()) / abs(case.tip()),
                            energy=fields.energy_error(res, case, order), u_l2=fields.u_l2_error(res, case, order))
            yield Run("timoshenko", fam, k, desc, deck, metrics, len(m.elems))


# ----------------------------------------------------------------- Lame
def lame(work, quick=False, families=LINEAR_FAMILIES):
    case = fields.Lame()
    fields.check_exact(case, pts=[(1.2, 0.3), (0.5, 1.5), (1.0, 1.0)])
    nrs = [4, 8, 16, 32, 64, 128] if not quick else [4, 8, 16]
    nrs2 = [2, 4, 8, 16, 32] if not quick else [2, 4, 8]
    a, b = case.a, case.b
    for fam in families:
        levels = list(nrs if ORDER[fam] == 1 else nrs2)
        if fam == "fem-tri" and not quick:
            levels.append(256)
        sfx, mform, order = _mesh_args(fam)
        for nr in levels:
            shape = SHAPE[fam]
            nt = int(round(math.pi / 2 * (a + b) / 2 * nr / (b - a)))      # square cells at mid radius
            if shape == "voronoi":
                cells = nr * nt
                mp = meshes.annulus_voronoi(work + "/meshes", f"lc_vor{sfx}_{cells}", a, b, cells,
                                            lloyd=20 if cells <= 20000 else 10, formulation=mform, order=order)
                desc = f"{cells} Voronoi cells"
            else:
                mp = meshes.annulus_polar(work + "/meshes", f"lc_{shape}{sfx}_{nr}", a, b, nr, nt, shape,
                                          formulation=mform, order=order)
                desc = f"{nr}x{nt} {'quads' if shape == 'quad' else 'quads split in 2 triangles'} (r x theta)"
            m = meshes.read_inp(mp)
            deck = _header("Lame thick cylinder, internal pressure", _rel_include(work + "/decks", mp),
                           case.E, case.nu, FORMULATION[fam])
            tol = 1e-9
            r = np.hypot(m.xy[:, 0], m.xy[:, 1])
            # sides on the inner boundary: boundary sides (in one element only) whose
            # midpoint is nearer the bore than the outer arc, not on the symmetry lines
            # (Voronoi cells split the polygon's chords, so their nodes need not be on r = a)
            corners = [(e, c[:len(c) // order]) for e, c in m.elems]     # second order: corners first
            count = {}
            for e, c in corners:
                for s in range(len(c)):
                    key = frozenset((c[s], c[(s + 1) % len(c)]))
                    count[key] = count.get(key, 0) + 1
            lines = ["*BOUNDARY"]
            lines += [f"{i}, 1" for i in _boundary_nodes(m, lambda x, y: abs(x) < tol)]
            lines += [f"{i}, 2" for i in _boundary_nodes(m, lambda x, y: abs(y) < tol)]
            lines += ["*STEP", "*STATIC", "*DLOAD"]
            for e, c in corners:
                for s in range(len(c)):
                    n1, n2 = c[s], c[(s + 1) % len(c)]
                    if count[frozenset((n1, n2))] != 1:
                        continue
                    p1, p2 = m.xy[m.index[n1]], m.xy[m.index[n2]]
                    mid = (p1 + p2) / 2
                    on_sym = (p1[0] < tol and p2[0] < tol) or (p1[1] < tol and p2[1] < tol)
                    if not on_sym and math.hypot(*mid) < (a + b) / 2:
                        lines.append(f"{e}, P{s + 1}, {case.p!r}")
            deck += "\n".join(lines) + "\n*END STEP\n"

            def metrics(res, case=case, order=order):
                x = res["x"]
                rr = np.hypot(x[:, 0], x[:, 1])
                at = np.abs(rr - case.a) < 1e-9
                c, s = x[at, 0] / rr[at], x[at, 1] / rr[at]
                Sn = res["Sn"][at]
                stt = Sn[:, 0] * s * s + Sn[:, 1] * c * c - 2 * Sn[:, 3] * s * c
                ex = case.polar_stress(case.a)[1]
                ur = res["U"][:, 0] * x[:, 0] / rr + res["U"][:, 1] * x[:, 1] / rr
                w = fields.nodal_weights(res, order)
                ure = case.ur(rr)
                return dict(u_l2=math.sqrt((w * (ur - ure) ** 2).sum() / (w * ure ** 2).sum()),
                            energy=fields.energy_error(res, case, order),
                            hoop=float(np.abs(stt - ex).mean() / ex))
            yield Run("lame", fam, nr, desc, deck, metrics, len(m.elems))


# ----------------------------------------------------------------- Hertz
HERTZ_P0, HERTZ_A = 83.60, 1.523
HERTZ_FAMILIES = ("vem-quad", "vem-quad+nts-hard", "vem-quad+s2s-hard", "fem-quad", "fem-quad+nts-hard", "fem-tri",
                  "vem2-quad", "vem2-quad+nts-hard", "fem-q8", "fem-q8+nts-hard")
HERTZ_SCENE = open(os.path.join(meshes.ROOT, "postprocess/scenes/ex2_hertz.toml")).read().split("[[variant]]")[0]


def hertz(work, quick=False, families=HERTZ_FAMILIES, only=None):
    """The paper's Hertz half model (inputs/hertz_*: materials, K = 1e5, load 100 at the
    top) on its mesh family (postprocess/scenes/ex2_hertz.toml, same gradings): the
    paper's 389, 600 and 1155-element meshes, then the divisions of the 600-element mesh
    times 2, 4 and 8 (bench/hertz_refined.toml's h20k and h100k are close to x3.3 and x7.5).
    Second order (k = 2 VEM, Q8; SURFACE TO SURFACE is refused on second-order sides): the
    same meshes with `order = 2`, the disc's arc side nodes on the circle (curved sides),
    up to x4 (about 3 times the unknowns of the first-order mesh).  `only`: the level
    names to make (all by default; the tests take the smallest)."""
    base_disc, base_block = (12, 12, 6), (16, 15)
    levels = [("389", (10, 10, 4), (13, 13)), ("600", base_disc, base_block),
              ("1155", (15, 15, 10), (24, 20))]
    for s in (2, 4, 8):
        levels.append((f"600x{s}", tuple(s * v for v in base_disc), tuple(s * v for v in base_block)))
    if quick:
        levels = levels[:3]
    if only is not None:
        levels = [lv for lv in levels if lv[0] in only]
    deck_text = open(os.path.join(meshes.ROOT, "inputs/hertz_1155_vem.inp")).read()
    for fam in families:
        base, variant = split_family(fam)
        shape = SHAPE[base]
        sfx, mform, order = _mesh_args(base)
        for name, dd, bd in (levels if order == 1 else [lv for lv in levels if lv[0] != "600x8"]):
            toml = HERTZ_SCENE.replace('mesher = "quad"', f'mesher = "{shape}"')
            toml = toml.replace("divisions = [12, 12, 6]", f"divisions = {list(dd)}")
            toml = toml.replace("divisions = [16, 15]", f"divisions = {list(bd)}")
            if order == 2:
                toml = toml.replace('formulation = "vem"', f'formulation = "{mform}"\norder = 2')
            mp = meshes.mesher(toml, f"hz_{shape}{sfx}_{name}", work + "/meshes")
            m = meshes.read_inp(mp)
            deck = deck_text.replace("meshes/ex2_hertz_1155_vem.inp", _rel_include(work + "/decks", mp))
            deck = deck.replace("FORMULATION=VEM", f"FORMULATION={FORMULATION[base]}")
            deck = contact_deck(deck, variant)
            desc = f"disc {dd}, block {bd[0]}x{bd[1]} {'quads' if shape == 'quad' else 'split quads'}"

            def metrics(res):
                c = res["contact"]
                p, xs = c["CPRESS"], c["coordinates"][:, 0]
                pmax = float(p.max())
                sel = p > 0.3 * pmax          # fit p^2 = p0^2 (1 - x^2/a^2) away from the edge
                a = float("nan")
                if sel.sum() >= 2:
                    slope, icpt = np.polyfit(xs[sel] ** 2, p[sel] ** 2, 1)
                    if slope < 0 < icpt:
                        a = math.sqrt(-icpt / slope)
                return dict(peak=abs(pmax - HERTZ_P0) / HERTZ_P0, halfwidth=abs(a - HERTZ_A) / HERTZ_A,
                            peak_value=pmax, halfwidth_value=a)
            yield Run("hertz", fam, name, desc, deck, metrics, len(m.elems))


# ----------------------------------------------------------------- interface
IF_E, IF_NU, IF_K, IF_D = 1.0e9, 0.3, 1.0e12, 0.1


IF_FAMILIES = ("vem-voronoi", "vem-voronoi+nts-hard", "vem-voronoi+s2s-hard", "vem-quad", "vem-quad+nts-hard",
               "vem-quad+s2s-hard", "fem-quad", "fem-quad+nts-hard", "fem-tri",
               "vem2-voronoi", "vem2-quad", "vem2-quad+nts-hard", "fem-q8")


def interface_exact(hard=False):
    """Both blocks in uniaxial strain (rollers on the sides): sigma_yy = -p with
    2 p/E' + p/K = 0.1, E' = E(1-nu)/((1+nu)(1-2nu)); sigma_xx = sigma_zz = nu/(1-nu) sigma_yy.
    HARD contact has no overclosure: 1/K = 0."""
    Ep = IF_E * (1 - IF_NU) / ((1 + IF_NU) * (1 - 2 * IF_NU))
    return IF_D / (2 / Ep + (0.0 if hard else 1 / IF_K))


def interface(work, quick=False, families=IF_FAMILIES, only=None):
    """The paper's interface (inputs/interface_*: two blocks [0,4]x[0,1] and [0,4]x[1,2]
    meshed independently, E = 1e9, nu = 0.3, K = 1e12, top moved by -0.1) with rollers
    on the sides (u_x = 0 on LEFT and RIGHT) so that the answer is known: a uniform
    pressure p = 0.1/(2/E' + 1/K).  The paper's decks clamp the top and bottom in x
    and leave the sides free, which has end effects and no closed form.  `only`: the
    refinement factors to make (all by default)."""
    scene = open(os.path.join(meshes.ROOT, "postprocess/scenes/ex3_interface.toml")).read().split("[[variant]]")[0]
    ks = [1, 2, 4, 8, 16] if not quick else [1, 2]
    if only is not None:
        ks = [k for k in ks if k in only]
    for fam in families:
        base, variant = split_family(fam)
        shape = SHAPE[base]
        sfx, mform, order = _mesh_args(base)
        p = interface_exact(hard=CONTACT_VARIANTS[variant][1] == "HARD")
        for k in ks:
            toml = scene
            if order == 2:      # second order: the mesher's order = 2 mesh (VPE2, or CPE8 for FEM)
                toml = toml.replace("lloyd = 40\n", f'lloyd = 40\nformulation = "{mform}"\norder = 2\n')
            if shape == "voronoi":
                cells = 100 * k * k                   # per block; the paper's 200 at k = 1
                toml = toml.replace("cells = 100", f"cells = {cells}")
                if cells > 20000:
                    toml = toml.replace("lloyd = 40", "lloyd = 10")
                desc = f"2 x {cells} Voronoi cells"
            else:
                toml = toml.replace('mesher = "voronoi"', f'mesher = "{shape}"')
                toml = toml.replace("divisions = [24, 6]", f"divisions = [{24 * k}, {6 * k}]")
                toml = toml.replace("divisions = [20, 5]", f"divisions = [{20 * k}, {5 * k}]")
                desc = f"{24 * k}x{6 * k} below, {20 * k}x{5 * k} above {'quads' if shape == 'quad' else 'split quads'}"
            mp = meshes.mesher(toml, f"if_{shape}{sfx}_{k}", work + "/meshes")
            m = meshes.read_inp(mp)
            deck = (f"** accuracy study (bench/accuracy): interface under uniform compression, rollers\n"
                    f"*HEADING\ninterface, uniaxial strain\n*INCLUDE, INPUT={_rel_include(work + '/decks', mp)}\n"
                    f"*MATERIAL, NAME=ROCK\n*ELASTIC\n{IF_E!r}, {IF_NU!r}\n"
                    f"*SOLID SECTION, ELSET=LOWER, MATERIAL=ROCK, FORMULATION={FORMULATION[base]}\n1.0\n"
                    f"*SOLID SECTION, ELSET=UPPER, MATERIAL=ROCK, FORMULATION={FORMULATION[base]}\n1.0\n"
                    f"*SURFACE INTERACTION, NAME=INTERFACE\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                    f"{IF_K!r}\n*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=NODE TO SURFACE\n"
                    f"IFACE_SLAVE, IFACE_MASTER\n*BOUNDARY\nBOTTOM, 1, 2\nTOP, 1\nLEFT, 1\nRIGHT, 1\n"
                    f"*STEP, NAME=COMPRESSION\n*STATIC\n*BOUNDARY\nTOP, 2, 2, {-IF_D!r}\n*END STEP\n")
            deck = contact_deck(deck, variant)

            def metrics(res, p=p, order=order):
                c = res["contact"]
                cp = c["CPRESS"]
                syy = -res["Se"][:, 1]
                xs = c["coordinates"][:, 0]
                o = np.argsort(xs)
                xo = xs[o]
                trib = np.zeros(len(xo))               # tributary lengths along the slave side
                trib[1:] += np.diff(xo) / 2
                trib[:-1] += np.diff(xo) / 2
                resultant = float((cp[o] * trib).sum())
                if order == 2:
                    # second order: the slave nodes' own weights (l/6, 4l/6, l/6 per side;
                    # thickness 1), not the half edges between neighbouring nodes
                    resultant = float((cp * c["CNAREA"]).sum())
                return dict(pressure=float(np.abs(cp - p).max() / p),
                            pressure_rms=float(math.sqrt(((cp - p) ** 2).mean()) / p),
                            resultant=abs(resultant - 4.0 * p) / (4.0 * p),
                            stress=float(np.abs(syy - p).max() / p))
            yield Run("interface", fam, k, desc, deck, metrics, len(m.elems))


CASE_FAMILIES = {"manufactured": LINEAR_FAMILIES, "timoshenko": LINEAR_FAMILIES, "lame": LINEAR_FAMILIES,
                 "hertz": HERTZ_FAMILIES, "interface": IF_FAMILIES}
CASES = {"manufactured": manufactured, "timoshenko": timoshenko, "lame": lame, "hertz": hertz,
         "interface": interface}
