#!/usr/bin/env python3
"""The Voronoi case of the CalculiX comparison: the peers' Timoshenko cantilever
(bench/peers/case.py: L = 8, D = 4, E = 1e7, nu = 0.3, plane strain, parabolic end
shear P = -1000 as consistent nodal loads, the exact displacement prescribed on
x = 0; exact tip deflection u_y(8, 0) = -2.9120e-3) on a Lloyd-Voronoi mesh from
vctools.mesh, written three ways on the same nodes:

    make_voronoi.py DIR [--cells 125000] [--seed 1] [--lloyd 20]

    DIR/beam_mesh.inp   the Voronoi polygons (VPE), vctools.mesh's file with the
                        coordinates rounded to 14 significant digits (CalculiX reads
                        at most 20 characters a field)
    DIR/tri_mesh.inp    the same nodes and node sets, every polygon split into CPE3
                        (the polygons' element surfaces left out; no deck uses them)
    DIR/vc_vpe.inp      vemcontact deck on the polygons (VEM)
    DIR/vc_cpe3.inp     vemcontact deck on the triangles (FEM, constant strain)
    DIR/ccx.inp         CalculiX deck on the triangles: vc_cpe3.inp + *NODE PRINT, U

The three decks have the same material, thickness (1), prescribed displacements
and loads (the lines of bench/peers/case.py, the values rounded to 14 significant
digits, the most a 20-character field of CalculiX holds); they differ in the mesh and
in ccx's print request.

Triangles: each (convex) Voronoi cell of k nodes is split into k - 2 triangles by a
fan from one of its own vertices, so that the triangle mesh has exactly the nodes
(and unknowns) of the polygon mesh; of the k possible apexes the one whose fan has
the largest smallest angle is taken. A fan from the cell's centroid would add one
node per cell (1.5 x the unknowns) for little gain in shape: a Voronoi cell's
shortest side gives a thin triangle in either fan. The sides on the boundary are the
polygons' own, so the tip deflection is interpolated the same way on both meshes.
Every triangle is checked to have positive area (counter-clockwise, as the cells).
"""
import argparse
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "peers"))
import case  # noqa: E402  (bench/peers/case.py: the peers' cantilever)


def read_elements(path):
    """The *ELEMENT blocks of a mesh file: (list of (id, [nodes])), lines before, lines after."""
    lines = pathlib.Path(path).read_text().splitlines()
    first = last = None
    elems, cur = [], None
    for i, line in enumerate(lines):
        s = line.strip()
        if s.startswith("*") and not s.startswith("**"):
            if s.upper().startswith("*ELEMENT"):
                if first is None:
                    first = i
                cur = True
                continue
            if cur:
                last = i
            cur = None
            continue
        if cur and s and not s.startswith("**"):
            f = [int(v) for v in s.rstrip(",").split(",")]
            if elems and elems[-1][2]:                       # continuation of a line ending in ","
                elems[-1][1].extend(f)
                elems[-1][2] = s.endswith(",")
            else:
                elems.append([f[0], f[1:], s.endswith(",")])
    if last is None:
        last = len(lines)
    return [(e[0], e[1]) for e in elems], lines[:first], lines[last:]


def _angles(p0, p1, p2):
    """The three angles (radians) of triangles p0 p1 p2 (arrays (..., 2)) and the signed area."""
    def ang(a, b, c):
        u, v = b - a, c - a
        cr = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
        return np.arctan2(np.abs(cr), (u * v).sum(-1)), cr
    a0, cr = ang(p0, p1, p2)
    a1, _ = ang(p1, p2, p0)
    a2, _ = ang(p2, p0, p1)
    return np.stack([a0, a1, a2], -1), 0.5 * cr


def fan_triangles(cells, xy):
    """CPE3 connectivity (rows of node indices into xy) of the vertex fans with the
    largest smallest angle, and the smallest / largest angle (deg) and smallest area."""
    by_k = {}
    for c in cells:
        by_k.setdefault(len(c), []).append(c)
    tris, amin, amax, area_min = [], 180.0, 0.0, np.inf
    for k, group in sorted(by_k.items()):
        C = np.array(group)                                  # (m, k)
        best, best_ang = None, None
        for a in range(k):
            idx = np.array([[a, (a + j) % k, (a + j + 1) % k] for j in range(1, k - 1)])
            T = C[:, idx]                                    # (m, k-2, 3)
            ang, ar = _angles(xy[T[..., 0]], xy[T[..., 1]], xy[T[..., 2]])
            mn = np.where(ar > 0, ang.min(-1), -1.0).min(-1)    # a non-positive area never wins
            if best is None:
                best, best_ang, bestT = mn, np.full(len(C), a), T
            else:
                better = mn > best
                best = np.where(better, mn, best)
                bestT = np.where(better[:, None, None], T, bestT)
        ang, ar = _angles(xy[bestT[..., 0]], xy[bestT[..., 1]], xy[bestT[..., 2]])
        if (ar <= 0).any():
            sys.exit(f"make_voronoi: a cell of {k} nodes has no fan of positive-area triangles")
        amin = min(amin, np.degrees(ang.min()))
        amax = max(amax, np.degrees(ang.max()))
        area_min = min(area_min, ar.min())
        tris.append(bestT.reshape(-1, 3))
    return np.concatenate(tris), amin, amax, area_min


def write(out, cells, seed, lloyd):
    out = pathlib.Path(out)
    case.make_deck(str(out), cells, seed, lloyd)
    lines, block = [], None                      # coordinates to 14 digits: ccx reads 20 characters
    for line in (out / "beam_mesh.inp").read_text().splitlines():
        if line.startswith("*") and not line.startswith("**"):
            block = line.split(",")[0].strip().upper()
        elif block == "*NODE" and line.strip():
            k, x, y = line.split(",")
            line = f"{k}, {float(x):.14g}, {float(y):.14g}"
        lines.append(line)
    (out / "beam_mesh.inp").write_text("\n".join(lines) + "\n")
    nodes, _ = case.read_mesh(out / "beam_mesh.inp")
    ids = np.array(sorted(nodes))
    xy = np.array([nodes[i] for i in ids])
    pos = np.full(ids.max() + 1, -1)
    pos[ids] = np.arange(len(ids))
    elems, before, after = read_elements(out / "beam_mesh.inp")
    cells_idx = [pos[np.array(c)] for _, c in elems]
    tri, amin, amax, area_min = fan_triangles(cells_idx, xy)
    head = [l for l in before if not l.upper().startswith("*ELEMENT")]
    kept, skip = [], False                       # the element surfaces name polygons: dropped
    for l in after:
        if l.startswith("*") and not l.startswith("**"):
            skip = l.upper().startswith("*SURFACE")
        if not skip:
            kept.append(l)
    after = kept
    body = ["*ELEMENT, TYPE=CPE3, ELSET=BEAM"]
    body += [f"{e + 1}, {ids[t[0]]}, {ids[t[1]]}, {ids[t[2]]}" for e, t in enumerate(tri)]
    note = [f"** {len(elems)} Voronoi cells split into {len(tri)} CPE3 triangles by bench/calculix/make_voronoi.py",
            f"** (vertex fans, largest smallest angle): angles {amin:.3f}-{amax:.3f} deg, smallest area {area_min:.3e}"]
    (out / "tri_mesh.inp").write_text("\n".join(note + head + body + after) + "\n")
    deck = []
    for line in (out / "beam.inp").read_text().splitlines():
        f = line.split(",")
        if not line.startswith("*") and len(f) in (3, 4):         # a *BOUNDARY or *CLOAD value:
            f[-1] = f" {float(f[-1]):.13e}"                       # 14 digits fit ccx's 20 characters
        deck.append(",".join(f))
    deck = "\n".join(deck) + "\n"
    deck = deck.replace("MATERIAL=STEEL\n*STEP", "MATERIAL=STEEL\n1.0\n*STEP")   # thickness 1, stated
    assert "\n1.0\n*STEP" in deck
    (out / "vc_vpe.inp").write_text(deck)
    tri_deck = deck.replace("INPUT=beam_mesh.inp", "INPUT=tri_mesh.inp")
    (out / "vc_cpe3.inp").write_text(tri_deck)
    (out / "ccx.inp").write_text(tri_deck.replace("*END STEP", "*NODE PRINT, NSET=NALL\nU\n*END STEP"))
    return dict(cells=len(elems), nodes=len(ids), triangles=len(tri), tri_angle_min_deg=f"{amin:.3g}",
                tri_angle_max_deg=round(amax, 3), tri_area_min=f"{area_min:.3e}",
                prescribed_nodes=deck.count(", 1, 1, "))


def tip_from(xy, u):
    """u_y(L, 0) interpolated linearly between the two nodes of x = L around y = 0
    (bench/peers/case.py's rule), and its error against the exact tip."""
    on = np.flatnonzero(np.abs(xy[:, 0] - case.L) <= 1e-9 * case.L)
    on = on[np.argsort(xy[on, 1])]
    k = np.searchsorted(xy[on, 1], 0.0)
    a, b = on[max(k - 1, 0)], on[min(k, len(on) - 1)]
    t = 0.0 if a == b else (0.0 - xy[a, 1]) / (xy[b, 1] - xy[a, 1])
    uy = (1 - t) * u[a, 1] + t * u[b, 1]
    return uy, abs(uy - case.TIP_EXACT) / abs(case.TIP_EXACT)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--cells", type=int, default=125000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--lloyd", type=int, default=20)
    a = ap.parse_args()
    print(write(a.out, a.cells, a.seed, a.lloyd))


if __name__ == "__main__":
    main()
