"""Contour plot of one field of a vemcontact result on its polygon mesh."""
from __future__ import annotations

import numpy as np

from .results import PolyResult, field_values


def fan_triangles(polygons) -> np.ndarray:
    """Triangles (a fan from each polygon's first vertex) for smooth point-data shading.
    A fan is only a drawing device: for non-convex cells a few triangles overlap,
    which shifts colours locally but never the values at the nodes."""
    tris = [np.column_stack([np.full(len(p) - 2, p[0]), p[1:-1], p[2:]]) for p in polygons]
    return np.vstack(tris)


def cell_centroids(res: PolyResult) -> np.ndarray:
    """Vertex means of the cells (the positions used to exclude cell values)."""
    return np.array([res.points[c].mean(axis=0) for c in res.polygons])


def colour_range(values, positions, clip: float | None = None, exclude=None) -> tuple[float, float, str]:
    """The colour range (vmin, vmax) and the note that says how it was chosen.

    `exclude`: (x, y, r) circles; values at positions inside any of them (e.g. the
    singular tip of a joint) do not set the range.  `clip`: a percentile P in (50, 100]:
    the range runs from the (100 - P)th to the Pth percentile of the remaining values.
    Values outside the range are drawn in the end colours (the bar's arrows)."""
    v = np.asarray(values, float)
    keep = np.isfinite(v)
    notes = []
    for x, y, r in exclude or []:
        inside = np.hypot(positions[:, 0] - x, positions[:, 1] - y) <= r
        keep &= ~inside
        notes.append(f"without {int(inside.sum())} values within {r:.3g} of ({x:.6g}, {y:.6g})")
    if not keep.any():
        raise ValueError("the excluded regions cover every value: nothing is left to set the colour range")
    w = v[keep]
    if clip is not None:
        if not 50.0 < clip <= 100.0:
            raise ValueError(f"--clip {clip:g}: the percentile must lie in (50, 100]")
        lo, hi = np.percentile(w, [100.0 - clip, clip])
        notes.append(f"clipped at the percentiles {100.0 - clip:g} and {clip:g}")
    else:
        lo, hi = float(w.min()), float(w.max())
    if hi <= lo:
        hi = lo + max(abs(lo), 1.0) * 1e-12
    note = ("colour range " + ", ".join(notes) + f": {lo:.4g} to {hi:.4g}") if notes else ""
    return float(lo), float(hi), note


def displacement_at(res: PolyResult, pts) -> np.ndarray:
    """U (x, y) at points of the undeformed mesh, linear on the cells' fan triangles; a
    point outside every cell (a line just off the boundary) takes its nearest node's U."""
    from matplotlib.tri import LinearTriInterpolator, Triangulation
    from scipy.spatial import cKDTree

    pts = np.asarray(pts, float).reshape(-1, 2)
    u = np.asarray(res.point_data["U"], float)[:, :2]
    tri = Triangulation(res.points[:, 0], res.points[:, 1], fan_triangles(res.polygons))
    out = np.empty((len(pts), 2))
    for k in range(2):
        out[:, k] = np.ma.filled(LinearTriInterpolator(tri, u[:, k])(pts[:, 0], pts[:, 1]), np.nan)
    miss = ~np.isfinite(out).all(axis=1)
    if miss.any():
        _, idx = cKDTree(res.points).query(pts[miss])
        out[miss] = u[idx]
    return out


def deformed_polyline(res: PolyResult, line, scale: float, per_segment: int = 40) -> np.ndarray:
    """A polyline given in undeformed coordinates, drawn on the deformed shape: each
    segment sampled at `per_segment` points, each moved by scale * U there."""
    p = np.asarray(line, float)
    if scale == 0.0:
        return p
    t = np.linspace(0.0, 1.0, per_segment + 1)
    pts = np.vstack([p[i] + np.outer(t if i == 0 else t[1:], p[i + 1] - p[i]) for i in range(len(p) - 1)])
    return pts + scale * displacement_at(res, pts)


def plot(res: PolyResult, spec: str, out: str, deformed: float | str | None = None,
         units: str = "", title: str | None = None, lines: list | None = None,
         contact: tuple | None = None, length_unit: str = "", step: str = "",
         clip: float | None = None, exclude=None) -> float:
    """Draw `spec` on the (optionally deformed) mesh into `out` (.png or .pdf).
    `units` labels the colour bar, `length_unit` the axes; `step` (e.g. "step 2, RESERVOIR")
    goes into the title; `lines` (undeformed coordinates) are drawn on the same, possibly
    deformed, geometry as the field; `clip` and `exclude` choose the colour range
    (colour_range) and the bar says so.  Returns the deformation scale used (0 when undeformed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.tri import Triangulation

    xy = res.points.copy()
    scale = 0.0
    if deformed is not None:
        u = np.asarray(res.point_data["U"])[:, :2]
        umax = float(np.max(np.linalg.norm(u, axis=1))) if len(u) else 0.0
        size = float(np.max(np.ptp(xy, axis=0)))
        if deformed == "auto":
            scale = 0.08 * size / umax if umax > 0 else 0.0
        else:
            scale = float(deformed)
        xy = xy + scale * u
    values, where, label = field_values(res, spec)
    positions = res.points if where == "point" else cell_centroids(res)
    vmin, vmax, range_note = colour_range(values, positions, clip, exclude)
    # a field without variation (U of a geostatic step, zero by construction) gets
    # one flat colour and its value in the title, not a colour bar over nothing
    flat = len(values) > 0 and float(np.ptp(values)) == 0.0
    # figure shaped after the domain (plus room for the colour bar)
    ext = np.ptp(xy, axis=0)
    aspect = float(ext[0] / ext[1]) if ext[1] > 0 else 1.0
    fig, ax = plt.subplots(figsize=(min(11.0, max(4.5, 5.0 * aspect + 2.2)) + (0.6 if range_note else 0.0), 5.5),
                           dpi=150)
    verts = [xy[p] for p in res.polygons]
    if flat:
        m = None
        ax.add_collection(PolyCollection(verts, facecolors="0.85", edgecolors="k", linewidths=0.15))
    elif where == "point":
        tri = Triangulation(xy[:, 0], xy[:, 1], fan_triangles(res.polygons))
        m = ax.tripcolor(tri, values, shading="gouraud", cmap="viridis", vmin=vmin, vmax=vmax)
        ax.add_collection(PolyCollection(verts, facecolors="none", edgecolors="k", linewidths=0.15, alpha=0.5))
    else:
        m = PolyCollection(verts, array=values, cmap="viridis", edgecolors="k", linewidths=0.15)
        m.set_clim(vmin, vmax)
        ax.add_collection(m)
    for line in lines or []:
        seg = deformed_polyline(res, line, scale)
        ax.plot(seg[:, 0], seg[:, 1], color="red", lw=1.5)
    if contact is not None:
        # slave nodes of the contact faces, at their undeformed positions plus the
        # drawn deformation: filled when closed, hollow when open
        pts, status = contact
        shown = pts.copy()
        if scale:
            from scipy.spatial import cKDTree
            _, idx = cKDTree(res.points).query(pts)
            shown = shown + scale * np.asarray(res.point_data["U"])[idx, :2]
        closed = status == 1
        ax.scatter(shown[closed, 0], shown[closed, 1], s=9, c="red", marker="o", label="contact closed", zorder=3)
        ax.scatter(shown[~closed, 0], shown[~closed, 1], s=9, facecolors="none", edgecolors="red",
                   marker="o", label="contact open", zorder=3)
        ax.legend(loc="best", fontsize=7)
    ax.autoscale_view()
    ax.set_aspect("equal")
    lu = f" [{length_unit}]" if length_unit else ""
    ax.set_xlabel(f"x{lu}")
    ax.set_ylabel(f"y{lu}")
    if m is not None:
        clipped = bool(range_note) and (np.nanmin(values) < vmin or np.nanmax(values) > vmax)
        cb = fig.colorbar(m, ax=ax, shrink=0.85, extend="both" if clipped else "neither")
        bar = f"{label} [{units}]" if units else label
        if range_note:
            import textwrap
            bar += "\n" + textwrap.fill(range_note, 48)
        cb.set_label(bar, fontsize=8 if range_note else None)
    t = title or f"{label}"
    if flat:
        t += f" = {values[0]:.6g}{' ' + units if units else ''} everywhere"
    if step:
        t += f", {step}"
    if deformed is not None:
        if scale:
            t += f"  (deformed shape, displacements x {scale:.3g})"
        else:
            t += "  (undeformed shape: the displacements of this step are zero)"
    ax.set_title(t, fontsize=10)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return scale
