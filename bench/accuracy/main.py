"""Accuracy against cost: build the meshes and decks of every case, run vemcontact
(Release) REPEAT times per deck, measure the errors against the known answers, write
bench/results/accuracy.csv (and accuracy_runs.csv with every timing), the figures
docs/figures/accuracy_<case>.png and docs/accuracy-vs-speed.md.

    usage: bash bench/accuracy/run.sh [--quick] [--repeat N] [--cases a,b] [--work DIR]
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import re
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from machine_info import describe  # noqa: E402
import cases      # noqa: E402
import fields     # noqa: E402
import meshes     # noqa: E402
import report     # noqa: E402

ROOT = meshes.ROOT
EXE = os.path.join(ROOT, "build", "vemcontact")
_TOTAL = re.compile(r"^\s*total\s+([0-9.Ee+-]+)\s*s", re.M)
_UNK = re.compile(r"unknowns\s+(\d+)")
_ITERS = re.compile(r"contact converged in (\d+) iterations? \((\d+) numeric factori")
_ITER_LINE = re.compile(r"^\s+(\d+)\s+\d+\s+\d+\s+[0-9.E+-]+\s", re.M)
_FALLBACK = "(Newton step on the pairing replaced by the frozen-pairing step"
_INSERTED = re.compile(r"\(SURFACE TO SURFACE\): (\d+) interface nodes inserted")


def contact_stats(log):
    """The contact iterations of a log (replaced by the HDF5 records of a run that
    finished, contact_stats_h5): largest count per step (increment), numeric
    factorizations (sum over the steps), fallbacks to the frozen pairing (lines
    '(Newton step on the pairing replaced by the frozen-pairing step: ...)'), iterations made before a
    failure, interface nodes inserted by SURFACE TO SURFACE."""
    its = [(int(a), int(b)) for a, b in _ITERS.findall(log)]
    lines = [int(k) for k in _ITER_LINE.findall(log)]
    return dict(contact_iterations=max((a for a, _ in its), default=max(lines, default=0)),
                iterations_total=sum(a for a, _ in its) if its else len(lines),
                factorizations=sum(b for _, b in its) if its else float("nan"),
                fallbacks=log.count(_FALLBACK),
                inserted_nodes=sum(int(k) for k in _INSERTED.findall(log)))


def contact_stats_h5(h5path, stats):
    """The same counts from the HDF5 iteration records (/steps/NNNN/contact/iterations:
    one entry per contact iteration, 'factorized' 1 where it paid a numeric
    factorization); the log's counts stay where the file has no records."""
    import h5py
    try:
        with h5py.File(h5path, "r") as f:
            per_step = []
            for name in sorted(f.get("steps", {})):
                g = f["steps"][name]
                if "contact/iterations" in g:
                    it = g["contact/iterations"]
                    per_step.append((len(it["iteration"][...]), int(it["factorized"][...].sum())))
    except OSError:
        return stats
    if per_step and sum(n for n, _ in per_step):
        stats = dict(stats, contact_iterations=max(n for n, _ in per_step),
                     iterations_total=sum(n for n, _ in per_step),
                     factorizations=sum(k for _, k in per_step))
    return stats


def run_once(deck, outdir):
    t0 = time.perf_counter()
    r = subprocess.run([EXE, "-q", "-o", outdir, deck], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    job = os.path.splitext(os.path.basename(deck))[0]
    log = open(os.path.join(outdir, job + ".log")).read() if os.path.exists(os.path.join(outdir, job + ".log")) else ""
    if r.returncode != 0:
        e = RuntimeError(f"vemcontact failed ({r.returncode}) on {deck}:\n{r.stdout}\n{r.stderr}\n{log[-2000:]}")
        e.stats = contact_stats(log)
        e.stats["exit"] = r.returncode
        u = _UNK.search(log)
        if u:
            e.stats["unknowns"] = int(u.group(1))
        raise e
    total = float(_TOTAL.findall(log)[-1])
    unk = int(_UNK.search(log).group(1))
    h5 = os.path.join(outdir, job + ".h5")
    return wall, total, unk, contact_stats_h5(h5, contact_stats(log)), h5


def snapshot_exe(work):
    """Run a private copy of the executable: others may rebuild build/ during the study."""
    global EXE
    import shutil
    dst = os.path.join(work, "bin", "vemcontact")
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    for _ in range(60):
        if os.access(EXE, os.X_OK):
            try:
                shutil.copy2(EXE, dst)
                if subprocess.run([dst, "--version"], capture_output=True).returncode == 0:
                    EXE = dst
                    return
            except OSError:
                pass
        time.sleep(5)
    raise RuntimeError(f"{EXE} is not usable (being rebuilt?)")


def source_state():
    try:
        # the last commit that changed the code (commits to bench/ or docs/ do not change the runs)
        head = subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h", "--", "src", "CMakeLists.txt", "cmake"],
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "src", "CMakeLists.txt"],
                               capture_output=True, text=True).stdout.strip()
        return f"commit {head}" + (" with uncommitted changes in src/" if dirty else "")
    except OSError:
        return "unknown commit"


def machine():
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return describe(), load


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="3 coarse levels, 2 repeats: a smoke test")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--cases", default=",".join(cases.CASES))
    ap.add_argument("--families", default="",
                    help="run only these families (comma-separated); the case's other families keep their "
                         "rows (from out/.../rows/<case>.json, else bench/results/accuracy.csv)")
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "accuracy"))
    ap.add_argument("--no-doc", action="store_true", help="do not rewrite docs/ (with --quick: the default)")
    ap.add_argument("--report-only", action="store_true",
                    help="only redraw the figures and the document from bench/results/accuracy.csv")
    args = ap.parse_args(argv)
    if args.report_only:
        return report_only(os.path.abspath(args.work))
    repeat = 2 if args.quick else args.repeat
    work = os.path.abspath(args.work)
    for sub in ("decks", "out", "meshes"):
        os.makedirs(os.path.join(work, sub), exist_ok=True)
    snapshot_exe(work)
    mach, load0 = machine()
    rowdir = os.path.join(work, "rows" + ("_quick" if args.quick else ""))
    os.makedirs(rowdir, exist_ok=True)
    only = [f for f in args.families.split(",") if f]
    for cname in args.cases.split(","):
        print(f"== {cname}", flush=True)
        rows, timings, failed = [], [], set()
        t_case = time.time()
        fams = [f for f in cases.CASE_FAMILIES[cname] if not only or f in only]
        kept = kept_rows(rowdir, cname, fams, args.quick) if only else None
        for run in cases.CASES[cname](work, quick=args.quick, families=fams):
            if run.family in failed:
                continue
            job = f"{run.case}_{run.family}_{run.level}".replace(".", "_")
            deck = os.path.join(work, "decks", job + ".inp")
            with open(deck, "w") as f:
                f.write(run.deck)
            outdir = os.path.join(work, "out", job)
            walls, totals = [], []
            row = dict(case=run.case, family=run.family, level=run.level, mesh=run.mesh_desc,
                       elements=run.elements, status="ok")
            try:
                for k in range(repeat):
                    if k >= 3 and min(totals) > 5.0:
                        break                   # runs over 5 s: 3 repeats are enough (run time)
                    wall, total, unk, stats, h5 = run_once(deck, outdir)
                    walls.append(wall)
                    totals.append(total)
                    timings.append(dict(case=run.case, family=run.family, level=run.level, repeat=k + 1,
                                        wall_s=f"{wall:.5f}", log_total_s=f"{total:.5f}"))
            except RuntimeError as e:
                # a failed run is a result: recorded, reported, and the family's finer
                # meshes are skipped
                msg = next((ln for ln in str(e).splitlines() if ln.startswith("error:")), str(e).splitlines()[0])
                unk = re.search(r"unknowns (\d+)", str(e))
                row.update(status="failed: " + msg.replace(",", ";"), unknowns=int(unk.group(1)) if unk else 0,
                           time_s=float("nan"), wall_s=float("nan"),
                           time_min_s=float("nan"), time_max_s=float("nan"), repeats=0)
                row.update(getattr(e, "stats", {}))
                rows.append(row)
                failed.add(run.family)
                print(f"  {run.family:12s} {str(run.level):>8s} FAILED: {msg}", flush=True)
                continue
            met = run.metrics(fields.read_result(h5))
            row.update(stats)
            row.update(unknowns=unk,
                       time_s=statistics.median(totals), wall_s=statistics.median(walls),
                       time_min_s=min(totals), time_max_s=max(totals), repeats=len(totals))
            row.update(met)
            rows.append(row)
            mets = ", ".join(f"{k} {v:.3e}" for k, v in met.items())
            its = (f"  iter {stats['contact_iterations']} fact {stats['factorizations']} fallbacks {stats['fallbacks']}"
                   if stats["iterations_total"] else "")
            print(f"  {run.family:20s} {str(run.level):>8s} {unk:>8d} unknowns  {row['time_s']:.4f} s  {mets}{its}",
                  flush=True)
        source = (f"{time.strftime('%Y-%m-%d')}, vemcontact {source_state()}, load average "
                  f"{load0:.2f} at its start, {os.getloadavg()[0]:.2f} at its end")
        elapsed = time.time() - t_case
        if kept is not None:
            # the families not run keep their rows, in the case's family order
            order = {f: k for k, f in enumerate(cases.CASE_FAMILIES[cname])}
            rows = sorted(kept["rows"] + rows, key=lambda r: order.get(r["family"], len(order)))
            timings = sorted(kept["timings"] + timings, key=lambda r: order.get(r["family"], len(order)))
            elapsed += kept["elapsed"]
            if kept["source"]:
                source = f"{kept['source']}, and for {', '.join(fams)} {source}"
        with open(os.path.join(rowdir, cname + ".json"), "w") as f:
            json.dump(dict(rows=rows, timings=timings, elapsed=elapsed, repeat=repeat,
                           load=[load0, os.getloadavg()[0]], source=source), f)
    # every case run so far in this work folder (a --cases run replaces only its cases)
    rows, timings, elapsed, sources = [], [], {}, {}
    previous = None if args.quick else previous_results()
    for cname in cases.CASES:
        path = os.path.join(rowdir, cname + ".json")
        if os.path.exists(path):
            d = json.load(open(path))
            rows += d["rows"]
            timings += d["timings"]
            elapsed[cname] = d["elapsed"]
            sources[cname] = d.get("source", "")
        elif previous and any(r["case"] == cname for r in previous[0]):
            # not run in this work folder: the rows of the committed CSV (an earlier run)
            rows += [r for r in previous[0] if r["case"] == cname]
            tl = [t for t in previous[1] if t["case"] == cname]
            timings += tl
            elapsed[cname] = sum(float(t["wall_s"]) for t in tl)
            sources[cname] = previous[2].get(cname, previous[2]["default"])
    total_elapsed = sum(elapsed.values())
    mach_load = (f"{mach}; load average {load0:.2f} at the start of the last run, {os.getloadavg()[0]:.2f} at "
                 f"its end; vemcontact {source_state()}")
    suffix = "_quick" if args.quick else ""
    resdir = work if args.quick else os.path.join(ROOT, "bench", "results")
    os.makedirs(resdir, exist_ok=True)
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(os.path.join(resdir, f"accuracy{suffix}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(resdir, f"accuracy{suffix}_runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(timings[0]))
        w.writeheader()
        w.writerows(timings)
    print("elapsed " + ", ".join(f"{k} {v:.0f} s" for k, v in elapsed.items()) + f" on {mach_load}")
    if not args.quick:
        with open(os.path.join(work, "accuracy_machine.txt"), "w") as f:
            f.write(f"{mach_load}\n{total_elapsed:.0f}\n{repeat}\n{json.dumps(sources)}\n")
    rows = [_numeric({k: r.get(k, "") for k in keys}) for r in rows]
    if not (args.quick or args.no_doc):
        report.write(rows, mach_load, total_elapsed, repeat, sources=sources)
    elif args.quick:
        report.write(rows, mach_load, total_elapsed, repeat, sources=sources, figdir=os.path.join(work, "figures"),
                     doc=os.path.join(work, "accuracy-vs-speed.md"))


def kept_rows(rowdir, cname, fams, quick):
    """Rows, timings, elapsed time and source of case `cname` for the families not in
    `fams`: from this work folder's rows/<case>.json, else from the committed CSV."""
    path = os.path.join(rowdir, cname + ".json")
    if os.path.exists(path):
        d = json.load(open(path))
        rows, timings, src = d["rows"], d["timings"], d.get("source", "")
    else:
        prev = None if quick else previous_results()
        if not prev:
            return dict(rows=[], timings=[], elapsed=0.0, source="")
        rows = [{k: v for k, v in r.items() if v != ""} for r in prev[0] if r["case"] == cname]
        timings = [t for t in prev[1] if t["case"] == cname]
        src = prev[2].get(cname, prev[2]["default"])
    rows = [r for r in rows if r["family"] not in fams]
    timings = [t for t in timings if t["family"] not in fams]
    return dict(rows=rows, timings=timings, elapsed=sum(float(t["wall_s"]) for t in timings), source=src)


def previous_results():
    """Rows and timings of bench/results/accuracy*.csv and the run each case came from (the
    **Machine:** line of the current document: its 'Cases by run', else the last run), for
    the cases not run in this work folder."""
    path = os.path.join(ROOT, "bench", "results", "accuracy.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(ROOT, "bench", "results", "accuracy_runs.csv")) as f:
        timings = list(csv.DictReader(f))
    src = "an earlier run"
    doc = os.path.join(ROOT, "docs", "accuracy-vs-speed.md")
    if os.path.exists(doc):
        m = re.search(r"load average ([0-9.]+) at the start of the last run, ([0-9.]+) at its end; vemcontact ([^.]*)\.",
                      open(doc).read())
        if m:
            src = f"an earlier run, vemcontact {m.group(3)}, load average {m.group(1)} at its start, {m.group(2)} at its end"
        # the run of each case as the document names it ('Cases by run: a, b: source; c: ...'):
        # rows kept from an earlier run keep the commit and load of the run that made them
        m = re.search(r"Cases by run: (.*?at its end)\. ", open(doc).read())
        if m:
            per_case = {}
            for g in re.finditer(r"((?:[a-z]+, )*[a-z]+): (.+?at its end)(?:; |$)", m.group(1)):
                for c in g.group(1).split(", "):
                    per_case[c] = g.group(2) if g.group(2).startswith("an earlier run") else "an earlier run, " + g.group(2)
            src = dict(per_case, default=src)
    if isinstance(src, str):
        src = dict(default=src)
    return rows, timings, src


def _numeric(r):
    out = {}
    for k, v in r.items():
        if k in ("case", "family", "level", "mesh", "status"):
            out[k] = v
        else:
            try:
                out[k] = float(v)
            except (TypeError, ValueError):
                out[k] = float("nan")
    return out


def report_only(work):
    path = os.path.join(ROOT, "bench", "results", "accuracy.csv")
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            rows.append(_numeric(r))
    meta = open(os.path.join(work, "accuracy_machine.txt")).read().split("\n")
    report.write(rows, meta[0], float(meta[1]), int(meta[2]),
                 sources=json.loads(meta[3]) if len(meta) > 3 and meta[3] else {})


if __name__ == "__main__":
    main()
