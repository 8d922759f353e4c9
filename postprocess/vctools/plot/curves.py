"""vc-curves: line plots of vemcontact results, across one or several runs.

  vc-curves contact    RUN... [--pair K] [--step K] [--along auto|x|y|s] [--hertz P,R,E1,NU1,E2,NU2] [-o FILE]
  vc-curves deflection RUN... [--exact 0.3] [-o FILE]
  vc-curves peak       RUN... [--hertz P,R,E1,NU1,E2,NU2 | --exact P0] [-o FILE]
  vc-curves iterations RUN... [--label L ...] [--paper-table1] [-o FILE] [--markdown FILE]
  vc-curves srm        JOB.h5 [--step N] [-o FILE]
  vc-curves joint      JOB.h5 [--step N] [--pair K] [--mu MU] [--cohesion C] [-o FILE]

vc-curves is installed with the package (pip install ./postprocess); without it,
`python -m vctools.plot.curves` is the same command.  `pressure` is another name of
`contact`.

RUN is a run's output folder (vemcontact -o DIR) or one of its files: the contact
CSV (JOB_contact_pairK_NNNN.csv) for `contact`, JOB.h5 for `deflection` and
`peak`, JOB.log for `iterations`.

contact,    CPRESS, COPEN and CSLIP of a contact pair against the coordinate along
pressure    it (x, y or the distance s along the slave nodes: --along), runs
            overlaid; --hertz draws the plane-strain Hertz pressure
            p(x) = p0 sqrt(1 - x^2/a^2), a = sqrt(4 P R/(pi E*)), p0 = 2 P/(pi a),
            1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (P: load on the full disc).
deflection  tip deflection / exact against the distortion 2d/b of the two-element
            cantilever (paper example 1), VEM and FEM series; 2d/b is read from
            the mesh, the tip deflection is the mean u_y of the nodes at the
            largest x.
peak        peak contact pressure against the number of elements, VEM and FEM
            series, with the analytical value as a line.
iterations  peak pressure per active-set iteration from JOB.log (the paper's
            Table 1), one series per run; the penalty slope K of each run is
            read back from the log (pressure / penetration).  Prints the table
            as Markdown.
srm         the strength-reduction curve of a *STRENGTH REDUCTION step (default:
            the last one): F against the characteristic displacement u_char of
            each trial, trials without equilibrium as crosses, the factor of
            safety as a line (docs/sliding-safety.md).
joint       the state along a contact pair (default 1) in a step (default: the
            last): CPRESS and the water pressure CFLUIDP, |CSHEAR| against the
            strength c + mu CPRESS, against the arc length from the heel (the
            higher end of the joint); points coloured open / stick / slip.  mu and
            c are the pair's values in force in that step (HDF5 attributes);
            --mu/--cohesion give them for files without.

--units LENGTH[,STRESS] converts the values from the deck's units (--model-units,
default m,Pa) as vc-plot does: coordinates, COPEN and CSLIP take the length factor,
CPRESS and the peaks the stress factor (`--units mm,MPa` on an SI deck: x 1e3 and
x 1e-6); --hertz, --exact and --xmax stay in the deck's units.

Errors (a missing file, a CSV without the columns, a log without contact
iterations) are one line on stderr and exit status 1.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import os
import sys

import numpy as np

from vctools.cli import entry, positive_int
from vctools.paper.runs import ContactCurve, ResultError, read_contact, read_h5, read_log
from vctools.plot.contour import unit_factors
from vctools.plot.sliding import plot_joint, plot_srm

#: the paper's Table 1: peak normal contact traction per penalty iteration
#: (600 elements), for omega_N = 1e5, 1e4, 1e3; compressive, hence negative.
PAPER_TABLE1 = {
    1.0e5: [-227.11, -98.20, -84.71, -80.59],
    1.0e4: [-227.10, -98.01, -84.57, -80.59],
    1.0e3: [-227.11, -102.62, -87.65, -82.29, -79.86],
}

COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#7f7f7f"]


# ------------------------------------------------------------------ Hertz
def hertz(P: float, R: float, E1: float, nu1: float, E2: float, nu2: float) -> tuple[float, float, float]:
    """Plane-strain Hertz contact of a cylinder (line load P per unit thickness,
    radius R) on a body: returns (a, p0, E*)."""
    if P <= 0 or R <= 0 or E1 <= 0 or E2 <= 0:
        raise ValueError("Hertz: P, R, E1 and E2 must be positive")
    estar = 1.0 / ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)
    a = math.sqrt(4.0 * P * R / (math.pi * estar))
    p0 = 2.0 * P / (math.pi * a)
    return a, p0, estar


def hertz_pressure(x, a: float, p0: float) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    return p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))


def parse_hertz(text: str) -> tuple[float, ...]:
    try:
        v = tuple(float(t) for t in text.split(","))
    except ValueError:
        raise ResultError(f"--hertz {text}: expected six numbers P,R,E1,NU1,E2,NU2") from None
    if len(v) != 6:
        raise ResultError(f"--hertz {text}: expected six numbers P,R,E1,NU1,E2,NU2, got {len(v)}")
    try:
        hertz(*v)
    except ValueError as exc:
        raise ResultError(f"--hertz {text}: {exc}") from None
    return v


# ------------------------------------------------------------------ helpers
def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _units(text: str) -> tuple[str, str]:
    parts = (text or "").split(",")
    length = parts[0].strip()
    stress = parts[1].strip() if len(parts) > 1 else ""
    return (f" [{length}]" if length else ""), (f" [{stress}]" if stress else "")


def shown_units(units: str, model_units: str | None = None) -> tuple[float, float, str, str]:
    """(length factor, stress factor, length label, stress label) of the axes.  With
    `model_units` (the deck's units, e.g. "m,Pa"), `units` ("mm,MPa") is converted to,
    as vc-plot converts (vctools.plot.contour.unit_factors); without, `units` only
    names the values' units on the axes (factors 1)."""
    if model_units is None or not units:
        lu, su = _units(units)
        return 1.0, 1.0, lu, su
    lf, sf, length, stress = unit_factors(units, model_units)
    return lf, sf, (f" [{length}]" if length else ""), (f" [{stress}]" if stress else "")


def convert_curve(c: ContactCurve, lf: float, sf: float) -> ContactCurve:
    """A copy of `c` with its coordinates, COPEN and CSLIP times lf (lengths) and
    CPRESS times sf (a stress)."""
    if lf == 1.0 and sf == 1.0:
        return c
    return dataclasses.replace(c, x=c.x * lf, y=c.y * lf, copen=c.copen * lf, cpress=c.cpress * sf,
                               cslip=None if c.cslip is None else c.cslip * lf)


def _save(fig, out: str) -> str:
    d = os.path.dirname(os.path.abspath(out))
    os.makedirs(d, exist_ok=True)
    fig.savefig(out)
    _plt().close(fig)
    return out


def _labels(n: int, given: list | None, default) -> list[str]:
    given = list(given or [])
    if len(given) > n:
        raise ResultError(f"{len(given)} labels given for {n} runs")
    return given + [default(i) for i in range(len(given), n)]


# ------------------------------------------------------------------ pressure
def plot_pressure(curves, out: str, labels=None, hertz_args=None, along: str = "auto", units: str = "",
                  xmax: float | None = None, title: str | None = None, gap: bool = True,
                  slip: bool = True, model_units: str | None = None) -> dict:
    """CPRESS, COPEN and CSLIP of contact curves against the coordinate along the pair
    (one panel each; COPEN with `gap`, CSLIP with `slip` when the files have it), in
    `units` converted from `model_units` (shown_units; `hertz_args` and `xmax` are in
    the model's units).  Returns {'peak': [peak CPRESS of each curve], 'x_peak': [its
    coordinate along the pair]} and, when the Hertz curve is drawn, 'a' and 'p0', all
    in the units shown."""
    plt = _plt()
    lf, sf, lu, su = shown_units(units, model_units)
    curves = [convert_curve(c, lf, sf) for c in curves]
    if xmax is not None:
        xmax = xmax * lf
    labels = _labels(len(curves), labels, lambda i: curves[i].job)
    slip = slip and any(c.cslip is not None for c in curves)
    panels = ["CPRESS"] + (["COPEN"] if gap else []) + (["CSLIP"] if slip else [])
    heights = {"CPRESS": 2.2, "COPEN": 1.0, "CSLIP": 1.0}
    fig, axes = plt.subplots(len(panels), 1, figsize=(7.5, 2.2 + 2.0 * len(panels)), dpi=110, sharex=True,
                             squeeze=False, gridspec_kw={"height_ratios": [heights[k] for k in panels]})
    ax_of = {k: axes[i, 0] for i, k in enumerate(panels)}
    axp = ax_of["CPRESS"]
    info = {"peak": [float(c.cpress.max()) if len(c.cpress) else 0.0 for c in curves],
            "x_peak": [float(c.along(along)[0][np.argmax(c.cpress)]) if len(c.cpress) else float("nan")
                       for c in curves]}
    xlabel = "x"
    styles = ["o-", "s-", "^-", "v-", "d-", "x-", "+-", "<-", ">-"]
    for i, (c, lab) in enumerate(zip(curves, labels)):
        t, xlabel = c.along(along)
        order = np.argsort(t)
        col = COLORS[i % len(COLORS)]
        st = styles[i % len(styles)]
        axp.plot(t[order], c.cpress[order], st, color=col, ms=3.5, lw=1.1, label=lab)
        if gap:
            ax_of["COPEN"].plot(t[order], c.copen[order], st, color=col, ms=3.0, lw=0.9, label=lab)
        if slip and c.cslip is not None:
            ax_of["CSLIP"].plot(t[order], c.cslip[order], st, color=col, ms=3.0, lw=0.9, label=lab)
    if hertz_args is not None:
        a, p0, _ = hertz(*hertz_args)
        a, p0 = a * lf, p0 * sf
        xs = np.linspace(0.0, a, 200)
        axp.plot(xs, hertz_pressure(xs, a, p0), "k--", lw=1.4,
                 label=f"Hertz (analytical): p0 = {p0:.2f}, a = {a:.3f}")
        info.update(a=a, p0=p0)
    if xmax is not None:
        tmin = min(float(np.min(c.along(along)[0])) for c in curves if len(c.x))
        axp.set_xlim(left=min(0.0, tmin) - 0.02 * xmax, right=xmax)
        for k in panels[1:]:   # the lower axes from the visible nodes only (far nodes open wide)
            vals = [getattr(c, k.lower()) for c in curves]
            vis = [v[c.along(along)[0] <= xmax] for c, v in zip(curves, vals) if v is not None]
            lo = min(min(v.min(), 0.0) for v in vis if len(v))
            hi = max(max(v.max(), 0.0) for v in vis if len(v))
            pad = 0.08 * (hi - lo) if hi > lo else 1.0
            ax_of[k].set_ylim(lo - pad, hi + pad)
    axp.set_ylabel(f"contact pressure CPRESS{su}")
    axp.grid(alpha=0.3)
    axp.legend(fontsize=8)
    axp.set_ylim(bottom=0.0)
    if gap:
        ax = ax_of["COPEN"]
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_ylabel(f"gap COPEN{lu}\n(< 0: overclosure)")
        ax.grid(alpha=0.3)
    if slip:
        ax = ax_of["CSLIP"]
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_ylabel(f"slip CSLIP{lu}")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel(f"{xlabel}{lu}")
    if title is None:
        title = "contact along the pair"
        if len({(c.pair, c.step) for c in curves}) == 1:
            title = f"contact pair {curves[0].pair}, step {curves[0].step}"
    axp.set_title(title, fontsize=10)
    fig.tight_layout()
    _save(fig, out)
    return info


# ------------------------------------------------------------------ deflection
def cantilever_point(run: str, exact: float = 0.3, step: int = 0) -> dict:
    """2d/b, formulation, tip deflection and its ratio to `exact` of one
    two-element cantilever run (paper example 1)."""
    info = read_h5(run)
    if not info.steps:
        raise ResultError(f"{info.path}: holds no step")
    xy = info.coordinates
    x0, x1 = xy[:, 0].min(), xy[:, 0].max()
    y0, y1 = xy[:, 1].min(), xy[:, 1].max()
    L, b = x1 - x0, y1 - y0
    tol = 1e-9 * max(L, b)
    bottom_mid = sorted(x for x, y in xy if abs(y - y0) <= tol and x0 + tol < x < x1 - tol)
    if len(bottom_mid) not in (1, 3) or b <= 0:
        raise ResultError(f"{info.path}: not the two-element cantilever of example 1 "
                          f"(expected one bottom node between the ends, found {len(bottom_mid)})")
    # second-order elements: the shared corner lies between the two side nodes
    d = x0 + L / 2 - bottom_mid[len(bottom_mid) // 2]
    key = info.steps[step - 1] if step else info.steps[-1]
    tip = np.abs(xy[:, 0] - x1) <= tol
    uy = float(np.mean(info.displacements[key][tip, 1]))
    return {"job": info.job, "2d/b": 2 * d / b, "formulation": info.formulation, "tip_uy": uy,
            "ratio": uy / exact, "nelem": info.nelem}


def plot_deflection(points: list[dict], out: str, exact: float = 0.3, fem_closed_form: bool = True,
                    title: str | None = None) -> str:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.0, 4.6), dpi=110)
    for i, form in enumerate(sorted({p["formulation"] for p in points}, key=lambda f: (f != "VEM", f))):
        pts = sorted((p for p in points if p["formulation"] == form), key=lambda p: p["2d/b"])
        ax.plot([p["2d/b"] for p in pts], [p["ratio"] for p in pts], "os"[i % 2] + "-",
                color=COLORS[i % len(COLORS)], label=form)
    ax.axhline(1.0, color="k", lw=0.8, ls=":", label=f"exact (tip deflection {exact:g})")
    if fem_closed_form:
        ax.plot([0.0], [1 / 4.125], "k*", ms=10,
                label="Q4 closed form at 2d/b = 0: 1/4.125")
    ax.set_xlabel("distortion parameter 2d/b")
    ax.set_ylabel("tip deflection / exact")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or "cantilever under an end moment, two elements", fontsize=10)
    fig.tight_layout()
    return _save(fig, out)


# ------------------------------------------------------------------ peak
def peak_point(run: str, pair: int = 1, step: int = 0) -> dict:
    """Number of elements, formulation and peak CPRESS of one contact run."""
    info = read_h5(run)
    c = read_contact(run if os.path.isdir(run) or str(run).endswith(".csv") else info.path, pair, step)
    k = int(np.argmax(c.cpress)) if len(c.cpress) else 0
    return {"job": info.job, "nelem": info.nelem, "formulation": info.formulation,
            "peak": float(c.cpress[k]) if len(c.cpress) else 0.0,
            "x_peak": float(c.x[k]) if len(c.x) else float("nan")}


def plot_peak(points: list[dict], out: str, exact: float | None = None, units: str = "",
              paper: dict | None = None, title: str | None = None, model_units: str | None = None) -> list[dict]:
    """`paper`: optional {label: [(nelem, peak), ...]} drawn as open markers.  Peaks,
    `exact` and `paper` are in the model's units, shown in `units` (shown_units).
    Returns the points drawn (peak and x_peak in the units shown)."""
    plt = _plt()
    lf, sf, _, su = shown_units(units, model_units)
    points = [{**p, "peak": p["peak"] * sf, "x_peak": p["x_peak"] * lf} for p in points]
    paper = {k: [(n, v * sf) for n, v in pts] for k, pts in (paper or {}).items()}
    exact = None if exact is None else exact * sf
    fig, ax = plt.subplots(figsize=(7.0, 4.6), dpi=110)
    for i, form in enumerate(sorted({p["formulation"] for p in points}, key=lambda f: (f != "VEM", f))):
        pts = sorted((p for p in points if p["formulation"] == form), key=lambda p: p["nelem"])
        ax.plot([p["nelem"] for p in pts], [p["peak"] for p in pts], "os"[i % 2] + "-",
                color=COLORS[i % len(COLORS)], label=f"{form} (ours)")
    for j, (lab, pts) in enumerate((paper or {}).items()):
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "os"[j % 2], mfc="none", ms=9,
                color=COLORS[j % len(COLORS)], label=lab)
    if exact is not None:
        ax.axhline(exact, color="k", ls="--", lw=1.2, label=f"analytical {exact:.2f}")
    ax.set_xlabel("number of elements")
    ax.set_ylabel(f"peak contact pressure{su}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or "peak contact pressure against mesh size", fontsize=10)
    fig.tight_layout()
    _save(fig, out)
    return points


# ------------------------------------------------------------------ iterations
def iteration_series(runs: list[str], labels=None, step: int = 0) -> list[dict]:
    """Per run: label, penalty slope K (from the log), per-iteration peak pressures,
    active counts, converged flag."""
    out = []
    logs = [read_log(r) for r in runs]
    for _i, lg in enumerate(logs):
        name, its, conv = lg.step(step)
        out.append({"job": lg.job, "step": name, "K": lg.penalty(step), "converged": conv,
                    "peaks": [it.pressure for it in its], "active": [it.active for it in its],
                    "penetrations": [it.penetration for it in its],
                    "changed": [it.changed for it in its]})
    labs = _labels(len(out), labels, lambda i: (f"K = {out[i]['K']:.0e}" if out[i]["K"] else out[i]["job"]))
    for s, lab in zip(out, labs):
        s["label"] = lab
    return out


def iterations_markdown(series: list[dict], paper: dict | None = None, digits: int = 2) -> str:
    """Markdown table: one row per iteration, a column per run (and, with
    `paper`, the paper's Table 1 column for the same K beside ours)."""
    cols = []
    for s in series:
        cols.append((f"ours, {s['label']}", s["peaks"]))
        if paper is not None and s["K"]:
            k = min(paper, key=lambda kk: abs(math.log10(kk) - math.log10(s["K"])))
            if abs(math.log10(k) - math.log10(s["K"])) < 0.01:
                cols.append((f"paper, omega = {k:.0e}", [abs(v) for v in paper[k]]))
    n = max(len(c[1]) for c in cols)
    lines = ["| iteration | " + " | ".join(c[0] for c in cols) + " |",
             "|---:|" + "---:|" * len(cols)]
    for r in range(n):
        cells = [f"{c[1][r]:.{digits}f}" if r < len(c[1]) else "" for c in cols]
        lines.append(f"| {r + 1} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot_iterations(series: list[dict], out: str, paper: dict | None = None, exact: float | None = None,
                    units: str = "", title: str | None = None, model_units: str | None = None) -> list[dict]:
    """Two panels: every iteration on a log scale, and from iteration 2 on a
    linear scale (the first iteration's peak can be orders of magnitude larger).
    The peaks, `paper` and `exact` are in the model's units, shown in `units`
    (shown_units; the paper's Table 1 is in its decks' units).  Returns the series
    drawn (peaks in the units shown)."""
    plt = _plt()
    _, sf, _, su = shown_units(units, model_units)
    series = [{**s, "peaks": [v * sf for v in s["peaks"]]} for s in series]
    if paper is not None:
        paper = {k: [v * sf for v in vals] for k, vals in paper.items()}
    exact = None if exact is None else exact * sf
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.6), dpi=110)
    nmax = 1
    for ax, first in zip(axes, (1, 2)):
        for i, s in enumerate(series):
            it = np.arange(1, len(s["peaks"]) + 1)
            nmax = max(nmax, len(it))
            ax.plot(it[first - 1:], s["peaks"][first - 1:], "o-", color=COLORS[i % len(COLORS)],
                    label=f"ours, {s['label']}")
            if paper is not None and s["K"]:
                k = min(paper, key=lambda kk: abs(math.log10(kk) - math.log10(s["K"])))
                if abs(math.log10(k) - math.log10(s["K"])) < 0.01:
                    v = [abs(x) for x in paper[k]]
                    nmax = max(nmax, len(v))
                    ax.plot(np.arange(1, len(v) + 1)[first - 1:], v[first - 1:], "s--", mfc="none",
                            color=COLORS[i % len(COLORS)], label=f"paper, omega = {k:.0e} (|value|)")
        if exact is not None:
            ax.axhline(exact, color="k", ls=":", lw=1.0, label=f"analytical {exact:.2f}")
        ax.set_xlabel("active-set (penalty) iteration")
        ax.set_ylabel(f"peak contact pressure{su}")
        ax.set_xticks(range(first, nmax + 1))
        ax.grid(alpha=0.3, which="both")
    axes[0].set_yscale("log")
    axes[0].set_title("all iterations (log scale)", fontsize=10)
    axes[1].set_title("from iteration 2 (linear scale)", fontsize=10)
    axes[1].legend(fontsize=7.5)
    fig.suptitle(title or "peak contact pressure per iteration", fontsize=11)
    fig.tight_layout()
    _save(fig, out)
    return series


# ------------------------------------------------------------------ command line
def _table(rows: list[dict], keys: list[str]) -> str:
    lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    for r in rows:
        lines.append("| " + " | ".join(f"{r[k]:.5g}" if isinstance(r[k], float) else str(r[k]) for k in keys) + " |")
    return "\n".join(lines) + "\n"


def units_options(sp) -> None:
    """--units and --model-units, as vc-plot's."""
    sp.add_argument("--units", default="", metavar="LENGTH[,STRESS]",
                    help="units to show, converted from --model-units (as vc-plot): lengths (coordinates, COPEN, "
                         "CSLIP) in the first, contact pressures in the second, e.g. mm,MPa")
    sp.add_argument("--model-units", default="m,Pa", metavar="LENGTH,STRESS",
                    help="the deck's units (default m,Pa); --hertz, --exact and --xmax are in these units")


@entry("vc-curves")
def main(argv=None) -> int:
    doc = __doc__.split("\n\n")
    p = argparse.ArgumentParser(prog="vc-curves", description=doc[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n\n".join(doc[1:]))
    sub = p.add_subparsers(dest="cmd", required=True, metavar="{contact,deflection,peak,iterations,srm,joint}")

    def common(sp, default_out):
        sp.add_argument("runs", nargs="+", metavar="RUN", help="run folder or result file (several: overlaid)")
        sp.add_argument("-o", "--output", default=default_out, help=f"picture to write (.png or .pdf; default {default_out})")
        sp.add_argument("--title", default=None, help="title of the picture")

    sp = sub.add_parser("pressure", aliases=["contact"],
                        help="CPRESS, COPEN and CSLIP along a contact pair, runs overlaid")
    common(sp, "pressure.png")
    sp.add_argument("--hertz", metavar="P,R,E1,NU1,E2,NU2", help="overlay the plane-strain Hertz pressure")
    sp.add_argument("--pair", type=positive_int, default=1, help="contact pair (default 1)")
    sp.add_argument("--step", type=positive_int, default=0, help="step, 1-based (default: last)")
    sp.add_argument("--along", choices=["auto", "x", "y", "s"], default="auto",
                    help="coordinate along the pair (default auto: x, y or the distance s)")
    sp.add_argument("--label", action="append", help="legend label of each run, in order (repeatable)")
    units_options(sp)
    sp.add_argument("--xmax", type=float, default=None, help="right end of the x axis")
    sp.add_argument("--no-gap", action="store_true", help="without the COPEN panel")
    sp.add_argument("--no-slip", action="store_true", help="without the CSLIP panel")

    sp = sub.add_parser("deflection", help="tip deflection ratio against 2d/b (example 1), VEM and FEM")
    common(sp, "deflection.png")
    sp.add_argument("--exact", type=float, default=0.3, help="exact tip deflection M L^2/(2 E I) (default 0.3)")

    sp = sub.add_parser("peak", help="peak contact pressure against the number of elements")
    common(sp, "peak.png")
    g = sp.add_mutually_exclusive_group()
    g.add_argument("--hertz", metavar="P,R,E1,NU1,E2,NU2", help="analytical line at the Hertz p0")
    g.add_argument("--exact", type=float, default=None, help="analytical line at this value")
    sp.add_argument("--pair", type=int, default=1)
    units_options(sp)

    sp = sub.add_parser("iterations", help="peak pressure per active-set iteration (Table 1)")
    common(sp, "iterations.png")
    sp.add_argument("--label", action="append", help="label of each run, in order (default: K from the log)")
    sp.add_argument("--step", type=positive_int, default=0, help="step with contact iterations, 1-based (default: last)")
    sp.add_argument("--paper-table1", action="store_true", help="the paper's Table 1 beside ours (matched by K)")
    sp.add_argument("--markdown", default=None, metavar="FILE", help="also write the Markdown table to FILE")
    units_options(sp)

    sp = sub.add_parser("srm", help="F against u_char of a strength-reduction step, and the factor of safety")
    sp.add_argument("runs", nargs=1, metavar="JOB.h5", help="run folder or its JOB.h5")
    sp.add_argument("-o", "--output", default="fs.png", help="picture to write (default fs.png)")
    sp.add_argument("--title", default=None)
    sp.add_argument("--step", type=positive_int, default=0, help="step, 1-based (default: the last SRM step)")

    sp = sub.add_parser("joint", help="CPRESS, CFLUIDP, |CSHEAR| and c + mu CPRESS along a joint, by STATUS")
    sp.add_argument("runs", nargs=1, metavar="JOB.h5", help="run folder or its JOB.h5")
    sp.add_argument("-o", "--output", default="joint.png", help="picture to write (default joint.png)")
    sp.add_argument("--title", default=None)
    sp.add_argument("--step", type=positive_int, default=0, help="step, 1-based (default: last)")
    sp.add_argument("--pair", type=positive_int, default=1, help="contact pair (default 1)")
    sp.add_argument("--mu", type=float, default=None, help="friction coefficient (default: the file's)")
    sp.add_argument("--cohesion", type=float, default=None, help="cohesion (default: the file's, else 0)")
    units_options(sp)

    a = p.parse_args(argv)
    try:
        if a.cmd in ("pressure", "contact"):
            hz = parse_hertz(a.hertz) if a.hertz else None
            curves = [read_contact(r, a.pair, a.step) for r in a.runs]
            info = plot_pressure(curves, a.output, labels=a.label, hertz_args=hz, along=a.along, units=a.units,
                                 xmax=a.xmax, title=a.title, gap=not a.no_gap, slip=not a.no_slip,
                                 model_units=a.model_units)
            for c, peak in zip(curves, info["peak"]):
                print(f"{c.job}: {int(c.closed.sum())} of {len(c.closed)} slave nodes closed, "
                      f"peak CPRESS {peak:.6g}")
            if "a" in info:
                print(f"Hertz: a = {info['a']:.4f}, p0 = {info['p0']:.4f}")
        elif a.cmd == "deflection":
            pts = [cantilever_point(r, a.exact) for r in a.runs]
            plot_deflection(pts, a.output, exact=a.exact, title=a.title)
            print(_table(sorted(pts, key=lambda q: (q["formulation"], q["2d/b"])),
                         ["job", "formulation", "2d/b", "tip_uy", "ratio"]), end="")
        elif a.cmd == "peak":
            exact = hertz(*parse_hertz(a.hertz))[1] if a.hertz else a.exact
            pts = [peak_point(r, a.pair) for r in a.runs]
            pts = plot_peak(pts, a.output, exact=exact, units=a.units, title=a.title, model_units=a.model_units)
            print(_table(sorted(pts, key=lambda q: (q["formulation"], q["nelem"])),
                         ["job", "formulation", "nelem", "peak"]), end="")
        elif a.cmd == "srm":
            d = plot_srm(a.runs[0], a.output, a.step, title=a.title)
            print(f"step {d['step']}: {len(d['F'])} trials ({int(d['converged'].sum())} converged), "
                  f"factor of safety {d['factor_of_safety']:.6g}")
        elif a.cmd == "joint":
            d = plot_joint(a.runs[0], a.output, a.step, a.pair, a.mu, a.cohesion, title=a.title, units=a.units,
                           model_units=a.model_units)
            counts = ", ".join(f"{int((d['STATUS'] == k).sum())} {n}" for k, n in
                               ((0, "open"), (1, "closed"), (3, "stick"), (4, "slip")) if (d["STATUS"] == k).any())
            print(f"step {d['step']}, pair {d['pair']}: {len(d['s'])} slave nodes over {d['s'][-1]:.6g} "
                  f"({counts}); mu = {d['mu']:.6g}, c = {d['cohesion']:.6g}")
        else:
            series = iteration_series(a.runs, a.label, a.step)
            paper = PAPER_TABLE1 if a.paper_table1 else None
            shown = plot_iterations(series, a.output, paper=paper, units=a.units, title=a.title,
                                    model_units=a.model_units)
            _, sf, _, _ = shown_units(a.units, a.model_units)
            md = iterations_markdown(shown, None if paper is None else
                                     {k: [v * sf for v in vals] for k, vals in paper.items()})
            if a.markdown:
                with open(a.markdown, "w") as fh:
                    fh.write(md)
            print(md, end="")
    except ResultError as exc:
        print(f"vc-curves: error: {exc}", file=sys.stderr)
        return 1
    except (ValueError, OSError) as exc:
        print(f"vc-curves: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
