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


def cell_fans(polygons) -> tuple[np.ndarray, np.ndarray]:
    """Each cell's own fan triangles, on copies of its vertices: (the mesh node of every
    copy, (ntri, 3) triangles over the copies).  No two cells share a vertex, so
    coincident nodes (the two faces of a joint, contact surfaces), a deformed shape
    that overlaps itself or a non-convex cell never make an invalid whole-mesh
    triangulation: there is none, only the triangles of each polygon."""
    sizes = np.fromiter((len(p) for p in polygons), dtype=np.int64, count=len(polygons))
    nodes = np.concatenate([np.asarray(p, dtype=np.int64) for p in polygons]) if len(polygons) else np.zeros(0, np.int64)
    start = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    ntri = sizes - 2
    cell = np.repeat(np.arange(len(polygons)), ntri)
    k = np.arange(ntri.sum()) - np.repeat(np.cumsum(ntri) - ntri, ntri)      # fan index within its cell
    first = start[cell]
    tris = np.column_stack([first, first + k + 1, first + k + 2])
    return nodes, tris


# units vc-plot converts between (--units, --model-units): metres and pascals per unit
LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "km": 1e3, "in": 0.0254, "ft": 0.3048}
STRESS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "psi": 6894.757293168361,
                "ksi": 6894757.293168361, "psf": 47.88025898033584}


def _split_units(text: str, what: str) -> tuple[str, str]:
    parts = [t.strip() for t in text.split(",")] if text else []
    if len(parts) > 2 or any(not t for t in parts):
        raise ValueError(f"{what} {text}: expected LENGTH[,STRESS], e.g. mm,MPa")
    length = parts[0] if parts else ""
    stress = parts[1] if len(parts) > 1 else ""
    if length and length not in LENGTH_UNITS:
        raise ValueError(f"{what} {text}: unknown length unit {length} (known: {', '.join(LENGTH_UNITS)})")
    if stress and stress not in STRESS_UNITS:
        raise ValueError(f"{what} {text}: unknown stress unit {stress} (known: {', '.join(STRESS_UNITS)})")
    return length, stress


def unit_factors(units: str, model_units: str = "m,Pa") -> tuple[float, float, str, str]:
    """(length factor, stress factor, length unit, stress unit) that take the model's
    values (in `model_units`, the deck's: "m,Pa" by default) to `units` ("mm,MPa");
    a unit `units` leaves out stays the model's.  Displacements and coordinates take
    the length factor, stresses the stress factor, reaction forces (a stress times a
    length squared) both; strains are ratios and are not converted."""
    ml, ms = _split_units(model_units, "--model-units")
    tl, ts = _split_units(units, "--units")
    if (tl and not ml) or (ts and not ms):
        raise ValueError(f"--model-units {model_units}: give the deck's units of what --units {units} converts")
    lf = LENGTH_UNITS[ml] / LENGTH_UNITS[tl] if tl else 1.0
    sf = STRESS_UNITS[ms] / STRESS_UNITS[ts] if ts else 1.0
    return lf, sf, tl or ml, ts or ms


def field_unit(spec: str, length: str, stress: str) -> str:
    """The unit of a field spec for the colour bar ('' when it has none)."""
    name = spec.removeprefix("cell:").split(":")[0]
    if name == "U":
        return length
    if name in ("S", "S1", "S3", "MISES"):
        return stress
    if name == "RF" and length and stress:
        return "N" if (length, stress) in (("m", "Pa"), ("mm", "MPa")) else f"{stress} {length}^2"
    return ""


def convert_result(res: PolyResult, lf: float, sf: float) -> PolyResult:
    """A copy of `res` with coordinates and displacements times lf, stresses times sf,
    reaction forces times sf lf^2 (see unit_factors)."""
    if lf == 1.0 and sf == 1.0:
        return res
    scale = {"U": lf, "S": sf, "S1": sf, "S3": sf, "MISES": sf, "RF": sf * lf * lf}

    def conv(data):
        return {k: np.asarray(v, float) * scale[k] if k in scale else v for k, v in data.items()}
    return PolyResult(points=res.points * lf, polygons=res.polygons, point_data=conv(res.point_data),
                      cell_data=conv(res.cell_data), path=res.path)


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
    """U (x, y) at points of the undeformed mesh, linear on the cells' fan triangles (the
    triangle that holds the point among those whose centroids are nearest it; a point on
    a joint, in the cells of both faces, takes the first found); a point outside every
    cell (a line just off the boundary) takes its nearest node's U.  No whole-mesh
    triangulation is made (coincident joint nodes would make it invalid)."""
    from scipy.spatial import cKDTree

    pts = np.asarray(pts, float).reshape(-1, 2)
    u = np.asarray(res.point_data["U"], float)[:, :2]
    tri = fan_triangles(res.polygons)
    a, b, c = res.points[tri[:, 0]], res.points[tri[:, 1]], res.points[tri[:, 2]]
    cen = (a + b + c) / 3.0
    out = np.full((len(pts), 2), np.nan)
    k = min(len(tri), 32)
    _, cand = cKDTree(cen).query(pts, k=k)
    cand = np.asarray(cand).reshape(len(pts), -1)
    size = float(np.max(np.ptp(res.points, axis=0))) or 1.0
    for i, p in enumerate(pts):
        t = cand[i]
        d1, d2 = b[t] - a[t], c[t] - a[t]
        det = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
        ok = np.abs(det) > 0
        r = p - a[t]
        with np.errstate(divide="ignore", invalid="ignore"):
            l1 = (r[:, 0] * d2[:, 1] - r[:, 1] * d2[:, 0]) / det
            l2 = (d1[:, 0] * r[:, 1] - d1[:, 1] * r[:, 0]) / det
            # inside up to round-off of the coordinates (relative to the model's size)
            tol = 1e-9 * size * size / np.where(ok, np.abs(det), 1.0)
            inside = ok & (l1 >= -tol) & (l2 >= -tol) & (l1 + l2 <= 1 + tol)
        if inside.any():
            j = int(np.flatnonzero(inside)[0])
            tt = tri[t[j]]
            out[i] = (1 - l1[j] - l2[j]) * u[tt[0]] + l1[j] * u[tt[1]] + l2[j] * u[tt[2]]
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
         clip: float | None = None, exclude=None, length_factor: float = 1.0, stress_factor: float = 1.0) -> float:
    """Draw `spec` on the (optionally deformed) mesh into `out` (.png or .pdf).
    `units` labels the colour bar, `length_unit` the axes; `step` (e.g. "step 2, RESERVOIR")
    goes into the title; `lines` (undeformed coordinates) are drawn on the same, possibly
    deformed, geometry as the field; `clip` and `exclude` choose the colour range
    (colour_range) and the bar says so.  `length_factor` and `stress_factor` convert the
    model's values to the units shown (unit_factors): the mesh, the displacements, the
    stresses, and the lines, excluded circles and contact points, which are given in the
    model's coordinates.  Returns the deformation scale used (0 when undeformed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.tri import Triangulation

    lf = float(length_factor)
    res = convert_result(res, lf, float(stress_factor))
    if lf != 1.0:
        lines = [np.asarray(line, float) * lf for line in lines or []]
        exclude = [(x * lf, y * lf, r * lf) for x, y, r in exclude or []]
        if contact is not None:
            contact = (np.asarray(contact[0], float) * lf, contact[1])
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
        # Gouraud shading on each cell's own fan (cell_fans): the colours interpolate the
        # nodal values within a cell, and the cells are drawn one by one
        nodes, tris = cell_fans(res.polygons)
        tri = Triangulation(xy[nodes, 0], xy[nodes, 1], tris)
        m = ax.tripcolor(tri, values[nodes], shading="gouraud", cmap="viridis", vmin=vmin, vmax=vmax)
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
