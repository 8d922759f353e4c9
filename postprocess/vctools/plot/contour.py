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


def plot(res: PolyResult, spec: str, out: str, deformed: float | str | None = None,
         units: str = "", title: str | None = None, lines: list | None = None,
         contact: tuple | None = None) -> float:
    """Draw `spec` on the (optionally deformed) mesh into `out` (.png or .pdf).
    Returns the deformation scale used (0 when undeformed)."""
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
    # a field without variation (U of a geostatic step, zero by construction) gets
    # one flat colour and its value in the title, not a colour bar over nothing
    flat = len(values) > 0 and float(np.ptp(values)) == 0.0
    # figure shaped after the domain (plus room for the colour bar)
    ext = np.ptp(xy, axis=0)
    aspect = float(ext[0] / ext[1]) if ext[1] > 0 else 1.0
    fig, ax = plt.subplots(figsize=(min(11.0, max(4.5, 5.0 * aspect + 2.2)), 5.5), dpi=150)
    verts = [xy[p] for p in res.polygons]
    if flat:
        m = None
        ax.add_collection(PolyCollection(verts, facecolors="0.85", edgecolors="k", linewidths=0.15))
    elif where == "point":
        tri = Triangulation(xy[:, 0], xy[:, 1], fan_triangles(res.polygons))
        m = ax.tripcolor(tri, values, shading="gouraud", cmap="viridis")
        ax.add_collection(PolyCollection(verts, facecolors="none", edgecolors="k", linewidths=0.15, alpha=0.5))
    else:
        m = PolyCollection(verts, array=values, cmap="viridis", edgecolors="k", linewidths=0.15)
        ax.add_collection(m)
    for line in lines or []:
        seg = np.asarray(line, dtype=float)
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
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    if m is not None:
        cb = fig.colorbar(m, ax=ax, shrink=0.85)
        cb.set_label(f"{label} [{units}]" if units else label)
    t = title or f"{label}"
    if flat:
        t += f" = {values[0]:.6g}{' ' + units if units else ''} everywhere"
    if deformed is not None:
        t += f"  (deformed shape, displacements x {scale:.3g})" if scale else "  (displacements are zero: undeformed shape)"
    ax.set_title(t, fontsize=10)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return scale
