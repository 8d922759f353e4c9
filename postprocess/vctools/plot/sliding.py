"""Pictures of sliding safety (docs/sliding-safety.md): the strength-reduction curve of a
`*STRENGTH REDUCTION` step and the state along a joint.

- `srm_data` / `plot_srm`: F against the characteristic displacement u_char of every
  trial (/steps/NNNN/strength_reduction), failed trials marked, the factor of safety
  (the step's attribute `factor_of_safety`) as a line.
- `joint_data` / `plot_joint`: along a contact pair (arc length s from the heel), the
  effective contact pressure CPRESS, the water pressure CFLUIDP (with *UPLIFT), |CSHEAR|
  and the strength c + mu CPRESS the joint can mobilize (mu and c from the pair's
  attributes `friction_coefficient` and `cohesion`, the values in force in that step;
  given explicitly when the file has none), points coloured by STATUS.

Both read JOB.h5 with h5py directly (vctools.api's Result.plot_srm and Result.plot_joint
call them with the file's path) and return the arrays they draw.
"""
from __future__ import annotations

import os

import numpy as np

from vctools.plot.results import ResultError, h5_path
from vctools.plot.contour import unit_factors

#: STATUS codes of /steps/NNNN/contact/pair_K/STATUS (docs/output-format.md)
STATUS_NAMES = {0: "open", 1: "closed", 2: "slid off", 3: "stick", 4: "slip"}
STATUS_COLORS = {0: "#7f7f7f", 1: "#1f77b4", 2: "#8c564b", 3: "#2ca02c", 4: "#d62728"}


def _step_key(f, path: str, step: int, need: str | None = None) -> str:
    """The group name NNNN of a 1-based step; 0 = the last step (holding `need`, if given)."""
    keys = sorted(f.get("steps", {}), key=int)
    if not keys:
        raise ResultError(f"{path}: holds no step")
    if step:
        key = f"{step:04d}"
        if key not in f["steps"]:
            raise ResultError(f"{path}: no step {step} (steps 1 to {len(keys)})")
        return key
    if need is None:
        return keys[-1]
    with_need = [k for k in keys if need in f["steps"][k]]
    if not with_need:
        raise ResultError(f"{path}: no step has {need} (a *STRENGTH REDUCTION step writes it)")
    return with_need[-1]


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(fig, out: str) -> str:
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out)
    _plt().close(fig)
    return out


# ------------------------------------------------------------------ strength reduction
def srm_data(path: str, step: int = 0) -> dict:
    """The trials of a *STRENGTH REDUCTION step: arrays F, u_char, converged (bool),
    iterations, and factor_of_safety, tolerance, F_lower, F_upper, step (1-based)."""
    import h5py

    path = h5_path(path)
    with h5py.File(path, "r") as f:
        key = _step_key(f, path, step, "strength_reduction")
        g = f["steps"][key]
        if "strength_reduction" not in g:
            raise ResultError(f"{path}: step {int(key)} is not a strength-reduction step "
                              f"(no /steps/{key}/strength_reduction)")
        s = g["strength_reduction"]
        out = {k: s[k][...] for k in ("F", "u_char", "converged", "iterations") if k in s}
        missing = {"F", "u_char", "converged"} - set(out)
        if missing:
            raise ResultError(f"{path}: /steps/{key}/strength_reduction lacks {', '.join(sorted(missing))}")
        out["converged"] = out["converged"].astype(bool)
        fs = g.attrs.get("factor_of_safety")
        out["factor_of_safety"] = float(np.asarray(fs).reshape(-1)[0]) if fs is not None else float("nan")
        for a in ("tolerance", "F_lower", "F_upper"):
            v = s.attrs.get(a)
            out[a] = float(np.asarray(v).reshape(-1)[0]) if v is not None else float("nan")
        out["step"] = int(key)
    return out


def plot_srm(path: str, out: str, step: int = 0, title: str | None = None, units: str = "") -> dict:
    """F against u_char, converged trials joined in the order of F, failed trials as
    crosses, the factor of safety as a horizontal line.  Returns srm_data's dict."""
    d = srm_data(path, step)
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.8, 4.6), dpi=110)
    ok = d["converged"]
    order = np.argsort(d["F"][ok])
    ax.plot(d["u_char"][ok][order], d["F"][ok][order], "o-", color="#1f77b4", ms=4, label="converged trial")
    if (~ok).any():
        # a failed trial has no displacement to show (the file holds 0 or NaN): its cross
        # stands at the largest converged u_char, at its F
        u_fail = np.full(int((~ok).sum()), float(np.nanmax(d["u_char"][ok])) if ok.any() else 0.0)
        ax.plot(u_fail, d["F"][~ok], "x", color="#d62728", ms=8, mew=2, label="no equilibrium (trial F)")
    if np.isfinite(d["factor_of_safety"]):
        ax.axhline(d["factor_of_safety"], color="k", ls="--", lw=1.0,
                   label=f"factor of safety {d['factor_of_safety']:.4g}")
    ax.set_xlabel(f"characteristic displacement u_char{f' [{units}]' if units else ''}")
    ax.set_ylabel("strength reduction factor F")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or f"strength reduction, step {d['step']}", fontsize=10)
    fig.tight_layout()
    _save(fig, out)
    return d


# ------------------------------------------------------------------ joint state
def chain_order(xy: np.ndarray) -> np.ndarray:
    """The slave nodes of a joint in order along it, from the heel.  The ends: the node
    farthest from the first node, and the node farthest from that one (the two ends of an
    open joint); of the two the higher one is the heel (a tie: the one of smaller x,
    upstream in the scenes' convention).  Then each next node is the nearest unvisited
    one.  O(n) memory, O(n^2) time (a joint has thousands of nodes at most)."""
    xy = np.asarray(xy, dtype=float)
    n = len(xy)
    if n <= 1:
        return np.arange(n)
    i = int(np.argmax(((xy - xy[0]) ** 2).sum(1)))
    j = int(np.argmax(((xy - xy[i]) ** 2).sum(1)))
    tie = 1e-9 * float(np.sqrt(((xy[i] - xy[j]) ** 2).sum()))
    if abs(xy[i, 1] - xy[j, 1]) > tie:
        start = i if xy[i, 1] > xy[j, 1] else j
    else:
        start = i if xy[i, 0] < xy[j, 0] else j
    order = [start]
    left = np.ones(n, bool)
    left[start] = False
    for _ in range(n - 1):
        cand = np.flatnonzero(left)
        k = int(cand[np.argmin(((xy[cand] - xy[order[-1]]) ** 2).sum(1))])
        order.append(k)
        left[k] = False
    return np.asarray(order)


def joint_data(path: str, step: int = 0, pair: int = 1, mu: float | None = None,
               cohesion: float | None = None) -> dict:
    """Along contact pair `pair` of a step (0: the last), ordered from the heel: s (arc
    length), x, y, CPRESS, CFLUIDP (zeros without *UPLIFT; `has_uplift` says which),
    shear (|CSHEAR|), strength (c + mu CPRESS on closed nodes, 0 on open ones), STATUS,
    and mu, cohesion, step, pair."""
    import h5py

    path = h5_path(path)
    with h5py.File(path, "r") as f:
        key = _step_key(f, path, step)
        g = f["steps"][key]
        name = f"pair_{pair}"
        if "contact" not in g or name not in g["contact"]:
            have = sorted(k for k in g.get("contact", {}) if k.startswith("pair_"))
            raise ResultError(f"{path}: step {int(key)} has no contact pair {pair}"
                              f"{' (it has ' + ', '.join(have) + ')' if have else ''}")
        p = g["contact"][name]
        for k in ("coordinates", "CPRESS", "STATUS"):
            if k not in p:
                raise ResultError(f"{path}: /steps/{key}/contact/{name} lacks {k} (request CSTR output)")
        xy = p["coordinates"][...]
        xy = xy if xy.shape[-1] == 2 else xy.T
        cpress = p["CPRESS"][...]
        cshear = p["CSHEAR"][...] if "CSHEAR" in p else np.zeros_like(cpress)
        has_uplift = "CFLUIDP" in p
        cfluidp = p["CFLUIDP"][...] if has_uplift else np.zeros_like(cpress)
        status = p["STATUS"][...].astype(int)
        a_mu, a_c = p.attrs.get("friction_coefficient"), p.attrs.get("cohesion")
    if mu is None:
        if a_mu is None:
            raise ResultError(f"{path}: contact pair {pair} of step {int(key)} has no attribute "
                              "friction_coefficient: give --mu (and --cohesion)")
        mu = float(np.asarray(a_mu).reshape(-1)[0])
    if cohesion is None:
        cohesion = float(np.asarray(a_c).reshape(-1)[0]) if a_c is not None else 0.0
    order = chain_order(xy)
    xy = xy[order]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
    cpress, cshear, cfluidp, status = cpress[order], cshear[order], cfluidp[order], status[order]
    closed = status != 0
    strength = np.where(closed, cohesion + mu * cpress, 0.0)
    return {"s": s, "x": xy[:, 0], "y": xy[:, 1], "CPRESS": cpress, "CFLUIDP": cfluidp,
            "has_uplift": has_uplift, "shear": np.abs(cshear), "strength": strength, "STATUS": status,
            "mu": float(mu), "cohesion": float(cohesion), "step": int(key), "pair": pair}


def plot_joint(path: str, out: str, step: int = 0, pair: int = 1, mu: float | None = None,
               cohesion: float | None = None, title: str | None = None, units: str = "",
               model_units: str = "m,Pa") -> dict:
    """Two panels along the joint: the normal stresses (CPRESS, CFLUIDP) and the shear
    (|CSHEAR| against c + mu CPRESS); markers coloured by STATUS.  `units` converts from
    `model_units` as vc-plot does (arc length by the length factor, stresses by the
    stress factor; the returned dict holds the converted values).  Returns
    joint_data's dict."""
    d = joint_data(path, step, pair, mu, cohesion)
    lf, sf, length, stress = unit_factors(units, model_units)
    d["s"] = d["s"]*lf
    for k in ("CPRESS", "CFLUIDP", "shear", "strength"):
        if k in d and d[k] is not None:
            d[k] = np.asarray(d[k])*sf
    d["cohesion"] = d["cohesion"]*sf
    plt = _plt()
    lu = f" [{length}]" if length else ""
    su = f" [{stress}]" if stress else ""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 6.4), dpi=110, sharex=True)
    s = d["s"]
    a1.plot(s, d["CPRESS"], "-", color="#1f77b4", lw=1.1, label="effective pressure CPRESS")
    if d["has_uplift"]:
        a1.plot(s, d["CFLUIDP"], "-", color="#17becf", lw=1.1, label="water pressure CFLUIDP")
    a2.plot(s, d["strength"], "--", color="k", lw=1.1,
            label=f"strength c + mu CPRESS (c = {d['cohesion']:.4g}, mu = {d['mu']:.4g})")
    a2.plot(s, d["shear"], "-", color="#9467bd", lw=1.0, label="|CSHEAR|")
    for code in sorted(set(d["STATUS"].tolist())):
        m = d["STATUS"] == code
        lab = STATUS_NAMES.get(code, str(code))
        col = STATUS_COLORS.get(code, "#000000")
        a1.plot(s[m], d["CPRESS"][m], "o", color=col, ms=4, label=lab)
        a2.plot(s[m], d["shear"][m], "o", color=col, ms=4, label=lab)
    a1.set_ylabel(f"normal stress{su}")
    a2.set_ylabel(f"shear stress{su}")
    a2.set_xlabel(f"arc length from the heel s{lu}")
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7.5)
        ax.set_ylim(bottom=0.0)
    a1.set_title(title or f"joint state, contact pair {d['pair']}, step {d['step']}", fontsize=10)
    fig.tight_layout()
    _save(fig, out)
    return d
