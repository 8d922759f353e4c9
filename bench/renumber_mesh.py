"""Renumber the nodes and elements of a vctools.mesh file in Z order (Morton order
of the node coordinates and of the element centroids), for bench/assembly.sh: the
Voronoi mesher numbers nodes and cells in the random order of its seeds, so the
nodes of one cell are far apart in memory; this shows what a spatial numbering
would change.  Node sets are renumbered with the nodes; element sides keep their
element ids (the elements keep their ids, only their order changes).

    python renumber_mesh.py IN.inp OUT.inp
"""
import sys

import numpy as np


def morton(pts):
    lo, span = pts.min(0), np.ptp(pts, 0)
    span[span == 0] = 1.0
    c = np.minimum(((pts - lo) / span * 65535).astype(np.int64), 65535)
    key = np.zeros(len(pts), np.int64)
    for b in range(16):
        key |= ((c[:, 0] >> b) & 1) << (2 * b) | ((c[:, 1] >> b) & 1) << (2 * b + 1)
    return key


def main(src, dst):
    lines = open(src).read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.upper().startswith("*NODE"))
    j = next(k for k, l in enumerate(lines) if l.upper().startswith("*ELEMENT"))
    k = i + 1
    ids, xy = [], []
    while not lines[k].startswith("*"):
        p = lines[k].split(",")
        ids.append(int(p[0]))
        xy.append([float(p[1]), float(p[2])])
        k += 1
    nend = k
    xy = np.array(xy)
    order = np.argsort(morton(xy), kind="stable")
    new_id = {ids[o]: n + 1 for n, o in enumerate(order)}
    index = {v: n for n, v in enumerate(ids)}
    out = lines[:i + 1] + [f"{n + 1}, {float(xy[o, 0])!r}, {float(xy[o, 1])!r}" for n, o in enumerate(order)]
    out += lines[nend:j + 1]
    k = j + 1
    els = []
    while k < len(lines) and not lines[k].startswith("*"):
        els.append([int(x) for x in lines[k].replace(",", " ").split()])
        k += 1
    cent = np.array([xy[[index[v] for v in e[1:]]].mean(0) for e in els])
    out += [", ".join(str(x) for x in [els[o][0]] + [new_id[v] for v in els[o][1:]])
            for o in np.argsort(morton(cent), kind="stable")]
    in_nset = False
    for line in lines[k:]:
        if line.startswith("*"):
            in_nset = line.upper().startswith("*NSET")
            out.append(line)
        elif in_nset and not line.startswith("**"):
            out.append(", ".join(str(new_id[int(x)]) for x in line.replace(",", " ").split()))
        else:
            out.append(line)
    open(dst, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
