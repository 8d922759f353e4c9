#!/usr/bin/env python3
"""Penalty sweep of the contact solver (issue 6, item 2): the penalty slope K from
1e0 to 1e16 times E/h, every decade, swept past the point of breakdown.

Cases
  blocks, matching 4/4 and non-matching 3/5: two blocks under a uniform pressure p
      (bench/stability/contrast_scale.py, blocks_deck; E = 1e3 both, h = 0.25). Exact:
      contact pressure p at every K (equilibrium), overclosure p/K.
  hertz: inputs/hertz_389_vem.inp with its penalty replaced (E_disc = 1e3, the slave
      segment at the contact point h = its shortest slave segment). Reference: the
      analytic peak pressure 83.60, and the run at K h/E = 1e3 (whose difference from
      83.60 is the discretisation error).

Columns: f = K h / E (E of the softer body); pressure error (blocks: max |CPRESS/p - 1|;
hertz: peak / peak at f = 1e3 - 1); interpenetration max(-COPEN)/h; iterations; CHOLMOD's
smallest reciprocal condition estimate of the run; exit status and diagnosis.

Writes bench/results/stability_penalty.csv and docs/stability-penalty.md.  Usage:

    VEMCONTACT_EXE=build/vemcontact .venv/bin/python bench/stability/penalty.py
"""
import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import contrast_scale as cs  # noqa: E402  (deck builders, Run, machine())

ROOT = HERE.parents[1]
FACTORS = [10.0 ** k for k in range(0, 17)]
E = 1.0e3
H = 0.25
HERTZ_PEAK = 83.60


def blocks_row(exe, work, f, nx_low, nx_up):
    K = f * E / H
    deck = Path(work) / f"pen_{nx_low}_{nx_up}_{f:.0e}.inp".replace("+", "")
    cs.blocks_deck(deck, E, E, K, nx_low=nx_low, nx_up=nx_up)
    r = cs.Run(exe, deck, work)
    row = dict(case=f"blocks {nx_low}/{nx_up}", f=f, K=K, exit=r.code,
               iterations=(r.iterations[0] if r.iterations else ""), rcond=r.rcond,
               diagnosis=r.diagnosis(), pressure_err="", mean_pressure_err="", penetration_over_h="")
    if r.code == 0:
        with r.h5() as h5:
            cp = h5["steps/0001/contact/pair_1/CPRESS"][:]
            co = h5["steps/0001/contact/pair_1/COPEN"][:]
            cx = h5["steps/0001/contact/pair_1/coordinates"][:, 0]
        o = np.argsort(cx)
        xs = cx[o]
        trib = np.diff(np.concatenate([[xs[0]], (xs[1:] + xs[:-1]) / 2, [xs[-1]]]))
        row["pressure_err"] = float(np.max(np.abs(cp / cs.PRESSURE - 1)))
        row["mean_pressure_err"] = float(abs(np.sum(cp[o] * trib) / np.sum(trib) / cs.PRESSURE - 1))
        row["penetration_over_h"] = float(np.max(-co) / H)
    return row


def hertz_deck(path, K):
    src = (ROOT / "inputs" / "hertz_389_vem.inp").read_text()
    text, n = re.subn(r"(\*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n)[^\n]*\n", rf"\g<1>{float(K)!r}\n", src)
    assert n == 1, "penalty line not found in hertz_389_vem.inp"
    text = text.replace("*INCLUDE, INPUT=meshes/", f"*INCLUDE, INPUT={ROOT / 'inputs' / 'meshes'}/")
    Path(path).write_text(text)


def hertz_runs(exe, work):
    rows = []
    # the shortest slave segment sets h: the springs at the contact point are the stiff ones
    probe = Path(work) / "hertz_probe.inp"
    hertz_deck(probe, 1.0e5)
    r = cs.Run(exe, probe, work)
    assert r.code == 0, r.stderr
    with r.h5() as h5:
        cx = np.sort(h5["steps/0001/contact/pair_1/coordinates"][:, 0])
    h = float(np.min(np.diff(cx)))
    e_disc = 1.0e3
    for f in FACTORS:
        K = f * e_disc / h
        deck = Path(work) / f"hertz_{f:.0e}.inp".replace("+", "")
        hertz_deck(deck, K)
        r = cs.Run(exe, deck, work)
        row = dict(case="hertz 389 vem", f=f, K=K, exit=r.code,
                   iterations=(r.iterations[0] if r.iterations else ""), rcond=r.rcond,
                   diagnosis=r.diagnosis(), pressure_err="", mean_pressure_err="", penetration_over_h="",
                   peak=float("nan"))
        if r.code == 0:
            with r.h5() as h5:
                cp = h5["steps/0001/contact/pair_1/CPRESS"][:]
                co = h5["steps/0001/contact/pair_1/COPEN"][:]
            row["peak"] = float(np.max(cp))
            row["penetration_over_h"] = float(np.max(-co) / h)
        rows.append(row)
    ref = next(r["peak"] for r in rows if r["f"] == 1e3)
    for row in rows:
        if row["exit"] == 0:
            row["pressure_err"] = row["peak"] / ref - 1
            row["mean_pressure_err"] = row["peak"] / HERTZ_PEAK - 1
    return rows, h


def fmt(v, spec="{:.1e}"):
    if v == "" or v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return spec.format(v) if isinstance(v, float) else str(v)


def main():
    exe = cs.exe_path()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for nx_low, nx_up in ((4, 4), (3, 5)):
            for f in FACTORS:
                rows.append(blocks_row(exe, work, f, nx_low, nx_up))
        hrows, h = hertz_runs(exe, work)
        rows += hrows
    out = ROOT / "bench" / "results" / "stability_penalty.csv"
    keys = ["case", "f", "K", "exit", "iterations", "rcond", "pressure_err", "mean_pressure_err",
            "penetration_over_h", "peak", "diagnosis"]
    with open(out, "w", newline="") as fh:
        w = csv.DictWriter(fh, keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in keys})
    write_doc(rows, h, exe)
    print(f"wrote {out} and docs/stability-penalty.md")


def table(rows, second):
    lines = ["| f = K h/E | iterations | rcond | pressure error | " + second + " | interpenetration / h | outcome |",
             "|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        outcome = "ok" if r["exit"] == 0 and not r["diagnosis"] else r["diagnosis"].replace("|", "/")
        if r["exit"] != 0:
            outcome = f"**exit {r['exit']}**: " + outcome
        lines.append(f"| {r['f']:.0e} | {fmt(r['iterations'])} | {fmt(r['rcond'])} | {fmt(r['pressure_err'])} | "
                     f"{fmt(r['mean_pressure_err'])} | {fmt(r['penetration_over_h'])} | {outcome} |")
    return "\n".join(lines)


def write_doc(rows, h, exe):
    by = {}
    for r in rows:
        by.setdefault(r["case"], []).append(r)
    text = (ROOT / "bench" / "stability" / "penalty.md.in").read_text()
    try:
        commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    text = text.replace("@MACHINE@", cs.machine()).replace("@EXE@", f"{exe}, source commit {commit}")
    text = text.replace("@HERTZ_H@", f"{h:.4g}")
    text = text.replace("@BLOCKS_MATCHING@", table(by["blocks 4/4"], "tributary mean error"))
    text = text.replace("@BLOCKS_NONMATCHING@", table(by["blocks 3/5"], "tributary mean error"))
    text = text.replace("@HERTZ@", table(by["hertz 389 vem"], "peak / 83.60 - 1"))
    disc = (ROOT / "bench" / "stability" / "penalty_discussion.md").read_text().strip()
    text = text.replace("@DISCUSSION@", disc)
    (ROOT / "docs" / "stability-penalty.md").write_text(text)


if __name__ == "__main__":
    main()
