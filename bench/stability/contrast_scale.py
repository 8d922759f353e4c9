#!/usr/bin/env python3
"""Stability sweeps of the contact solver at two extremes (issue 6): stiffness
contrast between bodies and absolute scale.

1. Contrast E_top/E_bottom from 1e-12 to 1e12 (every decade; the brief asks for
   1e-6..1e6, the rest finds the breakdown):
   (a) two blocks in frictionless penalty contact under a uniform pressure p on the
       top (exact: contact pressure p, overclosure p/K, stress -p in both blocks,
       piecewise-linear u_y) for three choices of the penalty slope K:
       f E_soft/h, f E_stiff/h and f E_bottom/h (the master's), f = 1e3, h the
       element size;
   (b) a bonded bimaterial bar (one body, two materials, conforming mesh) under
       the same pressure (exact: stress -p, piecewise-linear u_y).
2. Absolute scale: the dam scene (inputs/dam_joint.inp: gravity, hydrostatic load,
   a contact joint) and the blocks, with lengths scaled by s_L and moduli, loads and
   penalty by consistent factors (an exact similarity: u scales by s_L, stresses
   and pressures by s_E), compared with the unscaled run.

Writes bench/results/stability_contrast.csv, bench/results/stability_scale.csv and
docs/stability-contact.md.  Usage:

    VEMCONTACT_EXE=build/vemcontact .venv/bin/python bench/stability/contrast_scale.py

The deck builders and run helpers are imported by postprocess/tests/test_stability_contact.py.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from machine_info import describe  # noqa: E402
NU = 0.3
PRESSURE = 1.0          # applied pressure in the reference (unscaled) decks
PENALTY_FACTOR = 1.0e3  # K = f E / h (h the element size): overclosure 1e-3 of the soft strain * h


# ---------------------------------------------------------------- running
def exe_path():
    e = os.environ.get("VEMCONTACT_EXE")
    if e:
        return e
    for d in ("build", "build-debug"):
        p = ROOT / d / "vemcontact"
        if p.exists():
            return str(p)
    sys.exit("vemcontact executable not found: set VEMCONTACT_EXE")


class Run:
    """One run of the executable: exit status, stderr, the log text and what it says."""

    def __init__(self, exe, deck, out):
        r = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True)
        self.code = r.returncode
        self.stderr = r.stderr
        self.out = Path(out)
        self.job = Path(deck).stem
        log = self.out / f"{self.job}.log"
        self.log = log.read_text() if log.exists() else ""
        self.iterations = [int(m) for m in re.findall(r"contact converged in (\d+) iterations", self.log)]
        self.rconds = [float(m) for m in re.findall(r"rcond\s+([0-9.Ee+-]+)\s*$", self.log, re.M)]
        warn = re.findall(r"warning: ill-conditioned system \(rcond\s*([0-9.Ee+-]+)\)", self.log)
        self.rconds += [float(w) for w in warn]
        self.warned = bool(warn)
        m = re.search(r"estimate\s+([0-9.Ee+-]+)\)", self.stderr)
        if m:
            self.rconds.append(float(m.group(1)))

    @property
    def rcond(self):
        return min(self.rconds) if self.rconds else float("nan")

    def h5(self):
        import h5py
        return h5py.File(self.out / f"{self.job}.h5", "r")

    def diagnosis(self):
        """First line of the error message (empty on success) and the warning, if any."""
        if self.code < 0 or self.code > 5:
            m = re.search(r"Program received signal (\w+)", self.stderr)
            at = re.search(r"in (__\w+|\w+)\s+at (\S+)", self.stderr)
            return f"crash: {m.group(1) if m else 'signal'}" + (f" in {at.group(1)} at {at.group(2)}" if at else "")
        if self.code != 0:
            return self.stderr.strip().splitlines()[0] if self.stderr.strip() else f"exit {self.code}"
        return "warning: ill-conditioned" if self.warned else ""


# ---------------------------------------------------------------- decks
def _grid(nx, ny, x0, y0, lx, ly, first_node, first_elem):
    nodes, elems, ids = [], [], {}
    n = first_node
    for j in range(ny + 1):
        for i in range(nx + 1):
            ids[i, j] = n
            nodes.append((n, x0 + lx * i / nx, y0 + ly * j / ny))
            n += 1
    e = first_elem
    rows = []
    for j in range(ny):
        for i in range(nx):
            elems.append((e, ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]))
            rows.append(j)
            e += 1
    return nodes, elems, rows, ids, n, e


def _fmt_nodes(nodes):
    return [f"{n}, {float(x)!r}, {float(y)!r}" for n, x, y in nodes]


def _fmt_elems(elems):
    return [", ".join(map(str, e)) for e in elems]


def _ids(lst):
    out = []
    for i in range(0, len(lst), 12):
        out.append(", ".join(map(str, lst[i:i + 12])))
    return out


def blocks_deck(path, e_bottom, e_top, penalty, pressure=PRESSURE, length=1.0, nx_low=4, nx_up=4, ny=4,
                small_sliding=False):
    """Lower block [0,L]^2 (E_bottom, master surface on its top) and upper block
    [0,L]x[L,2L] (E_top, slave surface on its bottom), plane stress, nu = 0.3, unit
    thickness; pressure on the top of the upper block; the bottom held in y and every
    node of the four vertical sides held in x (uniaxial strain: the exact solution has
    a uniform stress sigma_yy = -p in both blocks and no sliding, so no slave node
    leaves the end of the master whatever the contrast).  The upper block is held in
    y only by the contact springs (the surfaces touch initially, so they start closed)."""
    L = length
    ln, le, lrows, lids, n, e = _grid(nx_low, ny, 0.0, 0.0, L, L, 1, 1)
    un, ue, urows, uids, _, _ = _grid(nx_up, ny, 0.0, L, L, L, n, e)
    master = [f"{el[0]}, S3" for el, r in zip(le, lrows) if r == ny - 1]
    slave = [f"{el[0]}, S1" for el, r in zip(ue, urows) if r == 0]
    top = [el[0] for el, r in zip(ue, urows) if r == ny - 1]
    bottom = [lids[i, 0] for i in range(nx_low + 1)]
    sides = [lids[0, j] for j in range(ny + 1)] + [lids[nx_low, j] for j in range(ny + 1)] + \
            [uids[0, j] for j in range(ny + 1)] + [uids[nx_up, j] for j in range(ny + 1)]
    opts = ", SMALL SLIDING" if small_sliding else ""
    text = ["** two blocks in frictionless contact under a uniform pressure (bench/stability/contrast_scale.py)",
            "*NODE", *_fmt_nodes(ln + un),
            "*ELEMENT, TYPE=VPS, ELSET=LOWER", *_fmt_elems(le),
            "*ELEMENT, TYPE=VPS, ELSET=UPPER", *_fmt_elems(ue),
            "*ELSET, ELSET=TOPROW", *_ids(top),
            "*NSET, NSET=BOTTOM", *_ids(bottom), "*NSET, NSET=SIDES", *_ids(sorted(set(sides))),
            "*SURFACE, NAME=LOWER_TOP", *master, "*SURFACE, NAME=UPPER_BOTTOM", *slave,
            "*MATERIAL, NAME=MLOW", "*ELASTIC", f"{float(e_bottom)!r}, {float(NU)!r}",
            "*MATERIAL, NAME=MUP", "*ELASTIC", f"{float(e_top)!r}, {float(NU)!r}",
            "*SOLID SECTION, ELSET=LOWER, MATERIAL=MLOW", "1.0",
            "*SOLID SECTION, ELSET=UPPER, MATERIAL=MUP", "1.0",
            "*SURFACE INTERACTION, NAME=I", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{float(penalty)!r}",
            "*CONTACT PAIR, INTERACTION=I, TYPE=NODE TO SURFACE" + opts, "UPPER_BOTTOM, LOWER_TOP",
            "*BOUNDARY", "BOTTOM, 2", "SIDES, 1",
            "*STEP", "*STATIC", "*DLOAD", f"TOPROW, P3, {float(pressure)!r}", "*END STEP"]
    Path(path).write_text("\n".join(text) + "\n")


def bar_deck(path, e_bottom, e_top, pressure=PRESSURE, length=1.0, nx=4, ny=4):
    """One body [0,L]x[0,2L] on a conforming mesh, E_bottom below y = L and E_top
    above (the interface on element sides), the same supports and load as the blocks:
    exact stress -p everywhere and u_y piecewise linear with a kink at y = L."""
    L = length
    nodes, elems, rows, ids, _, _ = _grid(nx, 2 * ny, 0.0, 0.0, L, 2 * L, 1, 1)
    low = [el for el, r in zip(elems, rows) if r < ny]
    up = [el for el, r in zip(elems, rows) if r >= ny]
    top = [el[0] for el, r in zip(elems, rows) if r == 2 * ny - 1]
    bottom = [ids[i, 0] for i in range(nx + 1)]
    sides = [ids[0, j] for j in range(2 * ny + 1)] + [ids[nx, j] for j in range(2 * ny + 1)]
    text = ["** bonded bimaterial bar under a uniform pressure (bench/stability/contrast_scale.py)",
            "*NODE", *_fmt_nodes(nodes),
            "*ELEMENT, TYPE=VPS, ELSET=LOWER", *_fmt_elems(low),
            "*ELEMENT, TYPE=VPS, ELSET=UPPER", *_fmt_elems(up),
            "*ELSET, ELSET=TOPROW", *_ids(top),
            "*NSET, NSET=BOTTOM", *_ids(bottom), "*NSET, NSET=SIDES", *_ids(sides),
            "*MATERIAL, NAME=MLOW", "*ELASTIC", f"{float(e_bottom)!r}, {float(NU)!r}",
            "*MATERIAL, NAME=MUP", "*ELASTIC", f"{float(e_top)!r}, {float(NU)!r}",
            "*SOLID SECTION, ELSET=LOWER, MATERIAL=MLOW", "1.0",
            "*SOLID SECTION, ELSET=UPPER, MATERIAL=MUP", "1.0",
            "*BOUNDARY", "BOTTOM, 2", "SIDES, 1",
            "*STEP", "*STATIC", "*DLOAD", f"TOPROW, P3, {float(pressure)!r}", "*END STEP"]
    Path(path).write_text("\n".join(text) + "\n")


def exact_uy(y, e_bottom, e_top, pressure=PRESSURE, length=1.0, penalty=None):
    """Exact u_y of both decks (uniaxial strain, plane stress: sigma_yy = E/(1-nu^2) eps_yy);
    the blocks' upper nodes at y = L are the slave nodes (upper block) when `upper`."""
    mb = e_bottom / (1 - NU ** 2)
    mt = e_top / (1 - NU ** 2)
    lower = -pressure * np.minimum(y, length) / mb
    upper = -pressure * np.maximum(y - length, 0.0) / mt
    jump = 0.0 if penalty is None else -pressure / penalty
    return lower, upper, jump


# ---------------------------------------------------------------- contrast
def penalty_for(rule, e_bottom, e_top, h):
    e = {"soft": min(e_bottom, e_top), "stiff": max(e_bottom, e_top), "master": e_bottom}[rule]
    return PENALTY_FACTOR * e / h


def blocks_case(exe, work, ratio, rule, e_bottom=1.0e3, nx_low=4, nx_up=4, ny=4, length=1.0, pressure=PRESSURE):
    """Run the two blocks at contrast E_top/E_bottom = ratio; return a result row."""
    e_top = ratio * e_bottom
    h = length / max(nx_low, nx_up, ny)
    K = penalty_for(rule, e_bottom, e_top, h)
    tag = f"blocks_{rule}_{nx_low}_{nx_up}_{ratio:.0e}_{length:.0e}".replace("+", "")
    deck = Path(work) / f"{tag}.inp"
    blocks_deck(deck, e_bottom, e_top, K, pressure=pressure, length=length, nx_low=nx_low, nx_up=nx_up, ny=ny)
    r = Run(exe, deck, work)
    row = dict(case="blocks", mesh=f"{nx_low}/{nx_up}", penalty_rule=rule, ratio=ratio, E_bottom=e_bottom,
               E_top=e_top, K=K, K_h_over_Esoft=K * h / min(e_bottom, e_top),
               exit=r.code, iterations=(r.iterations[0] if r.iterations else ""), rcond=r.rcond,
               diagnosis=r.diagnosis())
    row.update(pressure_err="", mean_pressure_err="", overclosure_err="", stress_err="", u_err="")
    if r.code != 0:
        return row, r
    with r.h5() as f:
        x = f["mesh/coordinates"][:]
        u = f["steps/0001/U"][:]
        s = f["steps/0001/S_element"][:]
        cp = f["steps/0001/contact/pair_1/CPRESS"][:]
        co = f["steps/0001/contact/pair_1/COPEN"][:]
        cx = f["steps/0001/contact/pair_1/coordinates"][:, 0]
    nlow = (nx_low + 1) * (ny + 1)
    o = np.argsort(cx)
    xs = np.sort(cx)
    trib = np.diff(np.concatenate([[xs[0]], (xs[1:] + xs[:-1]) / 2, [xs[-1]]]))
    row["pressure_err"] = float(np.max(np.abs(cp / pressure - 1)))
    row["mean_pressure_err"] = float(abs(np.sum(cp[o] * trib) / np.sum(trib) / pressure - 1))
    row["overclosure_err"] = float(np.max(np.abs(-co / (pressure / K) - 1)))
    row["stress_err"] = float(np.max(np.abs(s[:, 1] / -pressure - 1)))
    lo, up, jump = exact_uy(x[:, 1], e_bottom, e_top, pressure, length, K)
    ex = np.where(np.arange(len(x)) < nlow, lo, lo + up + jump)
    # displacement error of each block relative to its own compression (the stiff
    # block's compression is 1/ratio of the soft one's: a global norm would hide it)
    # the upper block's part: its compression u - u(bottom row), since its rigid
    # motion (the lower block's compression) is up to 1/ratio times larger
    low = np.arange(len(x)) < nlow
    upb = (~low) & np.isclose(x[:, 1], length)
    errs = [np.max(np.abs(u[low, 1] - ex[low])) / (pressure * length / (e_bottom / (1 - NU ** 2))),
            np.max(np.abs((u[~low, 1] - np.mean(u[upb, 1])) - (ex[~low] - np.mean(ex[upb]))))
            / (pressure * length / (e_top / (1 - NU ** 2)))]
    row["u_err"] = float(max(errs))
    row["u_x_max"] = float(np.max(np.abs(u[:, 0])))
    return row, r


def bar_case(exe, work, ratio, e_bottom=1.0e3, nx=4, ny=4, length=1.0, pressure=PRESSURE):
    e_top = ratio * e_bottom
    tag = f"bar_{ratio:.0e}_{length:.0e}".replace("+", "")
    deck = Path(work) / f"{tag}.inp"
    bar_deck(deck, e_bottom, e_top, pressure=pressure, length=length, nx=nx, ny=ny)
    r = Run(exe, deck, work)
    row = dict(case="bar", mesh=f"{nx}x{2 * ny}", penalty_rule="", ratio=ratio, E_bottom=e_bottom, E_top=e_top,
               K="", K_h_over_Esoft="", exit=r.code, iterations="", rcond=r.rcond, diagnosis=r.diagnosis(),
               pressure_err="", mean_pressure_err="", overclosure_err="", stress_err="", u_err="")
    if r.code != 0:
        return row, r
    with r.h5() as f:
        x = f["mesh/coordinates"][:]
        u = f["steps/0001/U"][:]
        s = f["steps/0001/S_element"][:]
    lo, up, _ = exact_uy(x[:, 1], e_bottom, e_top, pressure, length)
    ex = lo + up
    errs = []
    for sel, comp in ((x[:, 1] <= length * (1 + 1e-12), pressure * length / (e_bottom / (1 - NU ** 2))),
                      (x[:, 1] >= length * (1 - 1e-12), pressure * length / (e_top / (1 - NU ** 2)))):
        # the upper part's error is measured on its own compression: u - u(interface)
        if comp == pressure * length / (e_top / (1 - NU ** 2)):
            ui = np.mean(u[np.isclose(x[:, 1], length), 1])
            eu = ex[np.isclose(x[:, 1], length)][0]
            errs.append(np.max(np.abs((u[sel, 1] - ui) - (ex[sel] - eu))) / comp)
        else:
            errs.append(np.max(np.abs(u[sel, 1] - ex[sel])) / comp)
    row["stress_err"] = float(np.max(np.abs(s[:, 1] / -pressure - 1)))
    row["u_err"] = float(max(errs))
    row["u_x_max"] = float(np.max(np.abs(u[:, 0])))
    return row, r


# ---------------------------------------------------------------- absolute scale
def scale_dam_deck(src_dir, dst, s_len, s_mod):
    """inputs/dam_joint.inp with lengths times s_len, moduli, pressures and stresses
    times s_mod: coordinates, y levels of HP loads, E, density (rho g L ~ stress: times
    s_mod/s_len, g kept), HP pressure, penalty slope (stress/length: s_mod/s_len).
    Thickness (1) and nu are kept.  Displacements then scale by s_len, stresses by s_mod."""
    src_dir = Path(src_dir)
    deck = (src_dir / "dam_joint.inp").read_text().splitlines()
    mesh = (src_dir / "meshes" / "ex4_dam.inp").read_text().splitlines()
    out_mesh = []
    in_nodes = False
    for line in mesh:
        if line.startswith("*"):
            in_nodes = line.upper().startswith("*NODE")
            out_mesh.append(line)
            continue
        if in_nodes and line.strip() and not line.startswith("**"):
            p = [t.strip() for t in line.split(",")]
            out_mesh.append(f"{p[0]}, {float(p[1]) * s_len!r}, {float(p[2]) * s_len!r}")
        else:
            out_mesh.append(line)
    dst = Path(dst)
    mesh_name = dst.stem + "_mesh.inp"
    (dst.parent / mesh_name).write_text("\n".join(out_mesh) + "\n")
    out = []
    kw = ""
    for line in deck:
        if line.startswith("**"):
            continue
        if line.startswith("*"):
            kw = line.split(",")[0].strip().upper()
            if kw == "*INCLUDE":
                line = f"*INCLUDE, INPUT={mesh_name}"
            out.append(line)
            continue
        p = [t.strip() for t in line.split(",")]
        if kw == "*ELASTIC":
            line = f"{float(p[0]) * s_mod!r}, {p[1]}"
        elif kw == "*DENSITY":
            line = f"{float(p[0]) * s_mod / s_len!r}"
        elif kw == "*SURFACE BEHAVIOR":
            line = f"{float(p[0]) * s_mod / s_len!r}"
        elif kw == "*DSLOAD" and len(p) >= 5 and p[1].upper().startswith("HP"):
            line = f"{p[0]}, {p[1]}, {float(p[2]) * s_mod!r}, {float(p[3]) * s_len!r}, {float(p[4]) * s_len!r}"
        elif (kw == "*BOUNDARY" and len(p) > 3 and float(p[3]) != 0) or kw == "*CLOAD" or \
                (kw in ("*DLOAD", "*DSLOAD") and not p[1].upper().startswith("GRAV")):
            raise ValueError(f"scale_dam_deck: no scaling rule for {line!r}")
        out.append(line)
    dst.write_text("\n".join(out) + "\n")


def dam_fields(run):
    with run.h5() as f:
        steps = sorted(f["steps"].keys())
        return {k: dict(U=f[f"steps/{k}/U"][:], S=f[f"steps/{k}/S_element"][:],
                        CPRESS=f[f"steps/{k}/contact/pair_1/CPRESS"][:],
                        COPEN=f[f"steps/{k}/contact/pair_1/COPEN"][:],
                        STATUS=f[f"steps/{k}/contact/pair_1/STATUS"][:]) for k in steps}


def scaled_difference(ref, cur, s_len, s_mod):
    """Largest relative difference of the scaled fields over the steps:
    max |u/s_len - u_ref| / max |u_ref| and likewise for S, CPRESS (s_mod), COPEN (s_len);
    whether the active sets agree."""
    d = dict(u_diff=0.0, s_diff=0.0, cpress_diff=0.0, copen_diff=0.0, active_same=True)
    for k in ref:
        a, b = ref[k], cur[k]
        if np.max(np.abs(a["U"])) > 0:
            d["u_diff"] = max(d["u_diff"], np.max(np.abs(b["U"] / s_len - a["U"])) / np.max(np.abs(a["U"])))
        d["s_diff"] = max(d["s_diff"], np.max(np.abs(b["S"] / s_mod - a["S"])) / np.max(np.abs(a["S"])))
        if np.max(np.abs(a["CPRESS"])) > 0:
            d["cpress_diff"] = max(d["cpress_diff"],
                                   np.max(np.abs(b["CPRESS"] / s_mod - a["CPRESS"])) / np.max(np.abs(a["CPRESS"])))
        d["copen_diff"] = max(d["copen_diff"],
                              np.max(np.abs(b["COPEN"] / s_len - a["COPEN"])) / np.max(np.abs(a["COPEN"])))
        d["active_same"] = d["active_same"] and bool(np.all(a["STATUS"] == b["STATUS"]))
    return d


def dam_case(exe, work, s_len, s_mod, ref=None):
    tag = f"dam_L{s_len:.3e}_E{s_mod:.3e}".replace("+", "")
    deck = Path(work) / f"{tag}.inp"
    scale_dam_deck(ROOT / "inputs", deck, s_len, s_mod)
    r = Run(exe, deck, work)
    row = dict(case="dam", s_len=s_len, s_mod=s_mod, E=1.0e10 * s_mod, exit=r.code,
               iterations="/".join(map(str, r.iterations)), rcond=r.rcond, diagnosis=r.diagnosis(),
               u_diff="", s_diff="", cpress_diff="", copen_diff="", active_same="")
    if r.code == 0 and ref is not None:
        row.update(scaled_difference(ref, dam_fields(r), s_len, s_mod))
    return row, r


def blocks_scale_case(exe, work, s_len, s_mod, ref=None):
    """The equal-modulus blocks (E = 1e3, K = 1e3 E/h, p = 1) scaled: lengths by s_len,
    E and p by s_mod, K by s_mod/s_len."""
    e = 1.0e3 * s_mod
    h = 0.25 * s_len
    K = PENALTY_FACTOR * e / h
    tag = f"blk_L{s_len:.3e}_E{s_mod:.3e}".replace("+", "")
    deck = Path(work) / f"{tag}.inp"
    blocks_deck(deck, e, e, K, pressure=PRESSURE * s_mod, length=s_len)
    r = Run(exe, deck, work)
    row = dict(case="blocks", s_len=s_len, s_mod=s_mod, E=e, exit=r.code,
               iterations="/".join(map(str, r.iterations)), rcond=r.rcond, diagnosis=r.diagnosis(),
               u_diff="", s_diff="", cpress_diff="", copen_diff="", active_same="")
    if r.code == 0 and ref is not None:
        row.update(scaled_difference(ref, dam_fields(r), s_len, s_mod))
    return row, r


# ---------------------------------------------------------------- driver
def write_csv(path, rows):
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.3e}" if isinstance(v, float) else v) for k, v in r.items()})


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", help="directory for decks and results (default: a temporary one)")
    ap.add_argument("--no-doc", action="store_true", help="write the CSVs only")
    ap.add_argument("--exe-nostop", help="a build with rcond_stop = 0 in src/driver/linear.f90: the contrast "
                    "sweep is repeated with it to show what the stop prevents")
    args = ap.parse_args()
    exe = exe_path()
    work = Path(args.work or tempfile.mkdtemp(prefix="stability_"))
    work.mkdir(parents=True, exist_ok=True)
    (work / "nostop").mkdir(exist_ok=True)

    ratios = [10.0 ** k for k in range(-12, 13)]
    contrast = []
    for rule in ("soft", "stiff", "master"):
        for q in ratios:
            row, _ = blocks_case(exe, work, q, rule)
            contrast.append(row)
            print(_brief(row), flush=True)
    for q in ratios:
        row, _ = blocks_case(exe, work, q, "soft", nx_low=3, nx_up=5)
        contrast.append(row)
        print(_brief(row), flush=True)
    for q in ratios:
        row, _ = bar_case(exe, work, q)
        contrast.append(row)
        print(_brief(row), flush=True)

    if args.exe_nostop:
        for rule in ("soft", "stiff"):
            for q in ratios:
                row, _ = blocks_case(args.exe_nostop, work / "nostop", q, rule)
                row["build"] = "rcond_stop=0"
                contrast.append(row)
        for q in ratios:
            row, _ = bar_case(args.exe_nostop, work / "nostop", q)
            row["build"] = "rcond_stop=0"
            contrast.append(row)

    scale = []
    ref_dam = dam_fields(dam_case(exe, work, 1.0, 1.0)[1])
    ref_blk = dam_fields(blocks_scale_case(exe, work, 1.0, 1.0)[1])
    lens = [10.0 ** k for k in range(-9, 10, 1)]
    mods = [10.0 ** k for k in range(-15, 10, 1)]   # dam E = 1e10 * s_mod: 1e-5 .. 1e19
    for s_len in lens:
        row, _ = dam_case(exe, work, s_len, 1.0, ref_dam)
        scale.append(row)
        print(_brief(row), flush=True)
    for s_mod in mods:
        row, _ = dam_case(exe, work, 1.0, s_mod, ref_dam)
        scale.append(row)
        print(_brief(row), flush=True)
    for s_len, s_mod in ((1e-3, 1e-6), (1e3, 1e6), (1e-3, 1e6), (1e3, 1e-6)):
        row, _ = dam_case(exe, work, s_len, s_mod, ref_dam)
        scale.append(row)
        print(_brief(row), flush=True)
    for s_len, s_mod in ((2.0 ** -20, 1.0), (4.0, 1.0), (8.0, 1.0), (2.0 ** 20, 1.0)):
        # powers of two: the scaled data are exact, so the fields should be too
        row, _ = dam_case(exe, work, s_len, s_mod, ref_dam)
        scale.append(row)
        print(_brief(row), flush=True)
    for s_len in lens:
        row, _ = blocks_scale_case(exe, work, s_len, 1.0, ref_blk)
        scale.append(row)
        print(_brief(row), flush=True)
    for s_mod in mods:
        row, _ = blocks_scale_case(exe, work, 1.0, s_mod * 1e7, ref_blk)
        scale.append(row)
        print(_brief(row), flush=True)

    # far outside practice: where the floating-point range ends (squares of lengths
    # or stresses over- or underflow)
    for s_len, s_mod in ((1e-150, 1.0), (1e-160, 1.0), (1e-200, 1.0), (1e150, 1.0), (1e160, 1.0), (1e200, 1.0),
                         (1.0, 1e-300), (1.0, 1e-310), (1.0, 1e280), (1.0, 1e290)):
        row, _ = blocks_scale_case(exe, work, s_len, s_mod, ref_blk)
        scale.append(row)
        print(_brief(row), flush=True)

    res = ROOT / "bench" / "results"
    res.mkdir(parents=True, exist_ok=True)
    write_csv(res / "stability_contrast.csv", contrast)
    write_csv(res / "stability_scale.csv", scale)
    if not args.no_doc:
        write_doc(contrast, scale, exe)
    print("wrote", res / "stability_contrast.csv", res / "stability_scale.csv")


def _brief(row):
    return ", ".join(f"{k}={v:.2e}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items()
                     if k not in ("E_bottom",))


def _f(v, fmt="{:.1e}"):
    if v == "" or v is None:
        return "-"
    if isinstance(v, float):
        return fmt.format(v)
    return str(v)


def _table(rows, cols):
    out = ["| " + " | ".join(h for h, _ in cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        out.append("| " + " | ".join(_f(r.get(k, "")) for _, k in cols) + " |")
    return "\n".join(out)


def _outcome(r):
    if r["exit"] != 0:
        return f"stop (exit {r['exit']})"
    return "warning" if r["diagnosis"] else "ok"


def machine():
    return describe()


def write_doc(contrast, scale, exe):
    for r in contrast + scale:
        r["outcome"] = _outcome(r)
    ccols = [("E_top/E_bottom", "ratio"), ("K", "K"), ("iter", "iterations"), ("rcond", "rcond"),
             ("pressure err", "pressure_err"), ("overclosure err", "overclosure_err"),
             ("stress err", "stress_err"), ("u err", "u_err"), ("outcome", "outcome")]
    parts = []
    for title, sel in (("(a) blocks, K = 1e3 E_soft/h (penalty of the softer body)",
                        lambda r: r["case"] == "blocks" and r["penalty_rule"] == "soft" and r["mesh"] == "4/4"
                        and r.get("build", "") == ""),
                       ("(a) blocks, K = 1e3 E_stiff/h (penalty of the stiffer body)",
                        lambda r: r["case"] == "blocks" and r["penalty_rule"] == "stiff" and r.get("build", "") == ""),
                       ("(a) blocks, K = 1e3 E_bottom/h (penalty of the master body)",
                        lambda r: r["case"] == "blocks" and r["penalty_rule"] == "master" and r.get("build", "") == ""),
                       ("(a) blocks, non-matching 3/5 meshes, K = 1e3 E_soft/h (pressure err: nodal scatter; "
                        "the tributary mean is in the CSV)",
                        lambda r: r["case"] == "blocks" and r["mesh"] == "3/5" and r.get("build", "") == ""),
                       ("(b) bonded bimaterial bar (one body, conforming mesh)",
                        lambda r: r["case"] == "bar" and r.get("build", "") == ""),
                       ("without the stop (a build with rcond_stop = 0): what the stop prevents",
                        lambda r: r.get("build", "") != "")):
        rows = [r for r in contrast if sel(r)]
        if not rows:
            continue
        cols = ccols if "without" not in title else [("case", "case"), ("K rule", "penalty_rule")] + ccols
        parts.append(f"#### {title}\n\n" + _table(rows, cols))
    scols = [("s_len", "s_len"), ("s_mod", "s_mod"), ("E", "E"), ("iterations", "iterations"), ("rcond", "rcond"),
             ("u diff", "u_diff"), ("S diff", "s_diff"), ("CPRESS diff", "cpress_diff"), ("COPEN diff", "copen_diff"),
             ("same active set", "active_same"), ("outcome", "outcome"), ("diagnosis", "diagnosis")]
    sparts = []
    for title, case in (("dam (inputs/dam_joint.inp)", "dam"), ("blocks (E = 1e3 s_mod, K = 1e3 E/h)", "blocks")):
        rows = [r for r in scale if r["case"] == case]
        sparts.append(f"#### {title}\n\n" + _table(rows, scols))
    text = DOC.format(machine=machine(), exe=exe, contrast_tables="\n\n".join(parts),
                      scale_tables="\n\n".join(sparts))
    (ROOT / "docs" / "stability-contact.md").write_text(text)


DOC = open(Path(__file__).with_name("contrast_scale.md.in")).read() if \
    Path(__file__).with_name("contrast_scale.md.in").exists() else "{contrast_tables}\n\n{scale_tables}\n"


if __name__ == "__main__":
    main()
