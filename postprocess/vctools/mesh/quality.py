"""Mesh quality figures, computed vectorised on the flat cell storage."""
from __future__ import annotations

import numpy as np


def quality(m):
    """Dictionary of quality figures of a mesh (per body and overall)."""
    xy = m.nodes[m.conn]
    nxt = m.next_index()
    prv = np.empty_like(nxt)
    prv[nxt] = np.arange(len(nxt))
    e = xy[nxt] - xy
    elen = np.hypot(e[:, 0], e[:, 1])
    area = m.cell_areas()
    starts = m.ptr[:-1]
    cell = m.cell_index()
    # diameter: largest vertex distance within a cell (exact, pairwise; cells are small)
    diam = np.zeros(m.ncell)
    counts = np.diff(m.ptr)
    for k in np.unique(counts):
        cs = np.flatnonzero(counts == k)
        P = m.nodes[m.conn[starts[cs][:, None] + np.arange(k)]]
        d = np.sqrt(((P[:, :, None, :] - P[:, None, :, :]) ** 2).sum(-1))
        diam[cs] = d.reshape(len(cs), -1).max(1)
    short = np.minimum.reduceat(elen, starts) / diam
    # interior angles at each vertex: between the edge to the previous and to the next node
    a = xy[prv] - xy
    b = xy[nxt] - xy
    cross = b[:, 0] * a[:, 1] - b[:, 1] * a[:, 0]      # > 0 for a convex (left) turn
    dot = (a * b).sum(1)
    ang = np.degrees(np.arctan2(cross, dot))
    ang = np.where(ang < 0, ang + 360.0, ang)
    reflex = np.zeros(m.ncell, bool)
    # a reflex vertex beyond 180 deg by more than roundoff (collinear hanging nodes are 180)
    np.logical_or.at(reflex, cell, ang > 180.0 + 1e-7)
    minang = np.minimum.reduceat(ang, starts)
    maxang = np.maximum.reduceat(ang, starts)
    return {
        "cells": int(m.ncell),
        "nodes": int(len(m.nodes)),
        "area_total": float(area.sum()),
        "area_min": float(area.min()),
        "area_max": float(area.max()),
        "short_edge_ratio_min": float(short.min()),
        "angle_min_deg": float(minang.min()),
        "angle_max_deg": float(maxang.max()),
        "nonconvex_cells": int(reflex.sum()),
        "nodes_per_cell_max": int(counts.max()),
        "per_cell": {"area": area, "short": short, "minang": minang, "reflex": reflex},
    }


def report_lines(m, title=None):
    q = quality(m)
    lines = []
    if title:
        lines.append(title)
    lines.append(f"cells {q['cells']}, nodes {q['nodes']}, at most {q['nodes_per_cell_max']} nodes per cell")
    lines.append(f"cell area: smallest {q['area_min']:.6g}, largest {q['area_max']:.6g}, "
                 f"ratio {q['area_max'] / q['area_min']:.4g}, total {q['area_total']:.12g}")
    lines.append(f"shortest edge / cell diameter: {q['short_edge_ratio_min']:.4g}")
    lines.append(f"interior angle: smallest {q['angle_min_deg']:.4g} deg, largest {q['angle_max_deg']:.4g} deg")
    lines.append(f"non-convex cells: {q['nonconvex_cells']}")
    per = q["per_cell"]
    for k, (name, etype) in enumerate(m.bodies):
        sel = m.cell_body == k
        if sel.any():
            lines.append(f"  {name} ({etype}): {int(sel.sum())} cells, area {per['area'][sel].sum():.12g}, "
                         f"min angle {per['minang'][sel].min():.4g} deg, "
                         f"short edge ratio {per['short'][sel].min():.4g}")
    for k in ("lloyd_energy",):
        v = m.info.get(k)
        if v:
            lines.append(f"Lloyd energy: {v[0]:.6g} -> {v[-1]:.6g} in {len(v) - 1} iterations")
    return lines
