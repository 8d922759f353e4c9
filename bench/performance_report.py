"""Tables and growth exponents of docs/performance.md from the CSV files of
bench/performance.sh.   usage: performance_report.py LINEAR.csv CONTACT.csv

Growth exponents are log-log slopes: between consecutive sizes, and a least-squares
fit over all sizes (of the phase time against the number of unknowns, and of the
contact search against the number of slave nodes).  A phase growing as n log n
shows slopes slightly above 1 (about 1.1 over 1e4 to 4e6); fixed costs show
slopes below 1 at the small sizes.
"""
import csv
import math
import sys


def rows(path):
    try:
        with open(path) as f:
            return [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    except FileNotFoundError:
        return []


def notes(path):
    try:
        with open(path) as f:
            return [line.strip("# \n") for line in f if line.startswith("#")]
    except FileNotFoundError:
        return []


def fmt_t(x):
    x = float(x)
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    if x >= 1:
        return f"{x:.2f}"
    if x >= 0.01:
        return f"{x:.3f}"
    return f"{x:.1e}"


def fmt_n(x):
    return f"{int(float(x)):,}".replace(",", " ")


def fmt_mb(x):
    x = float(x)
    return f"{x / 1024:.1f} GB" if x >= 1024 else f"{x:.0f} MB"


def slopes(xs, ys):
    """consecutive log-log slopes and the least-squares slope over all points"""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    cons = [(b[1] - a[1]) / (b[0] - a[0]) for a, b in zip(pts, pts[1:])]
    if len(pts) < 2:
        return cons, float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    fit = sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)
    return cons, fit


def table(head, body):
    print("| " + " | ".join(head) + " |")
    print("|" + "|".join("---:" for _ in head) + "|")
    for r in body:
        print("| " + " | ".join(r) + " |")
    print()


def growth(title, xs, series, xname):
    print(f"Growth exponents ({title}): d log t / d log {xname}, between consecutive sizes; last column: fit over all sizes\n")
    body = []
    for name, ys in series:
        cons, fit = slopes(xs, ys)
        if len(cons) < len(xs) - 1:  # a time of zero (below the log's resolution)
            body.append([name] + ["–"] * len(xs))
            continue
        body.append([name] + [f"{c:.2f}" for c in cons] + [f"**{fit:.2f}**"])
    head = ["phase"] + [f"{fmt_n(a)}→{fmt_n(b)}" for a, b in zip(xs, xs[1:])] + ["fit"]
    table(head, body)


def linear(path):
    rs = rows(path)
    if not rs:
        return
    print("## Linear runs\n")
    for n in notes(path):
        print(f"- {n}")
    print()
    phases = ["mesh", "read", "pattern", "assemble", "analyze", "factorize", "solve", "write", "total"]
    head = ["unknowns"] + phases + ["peak RSS", "mesher RSS", "CHOLMOD alone", "ratio"]
    body = []
    for r in rs:
        body.append([fmt_n(r["unknowns"])] + [fmt_t(r[p + "_s"]) for p in phases]
                    + [fmt_mb(r["peak_MB"]), fmt_mb(r["mesh_peak_MB"]), fmt_t(r["cholmod_total_s"]),
                       f"**{float(r['ratio']):.2f}**"])
    table(head, body)
    print("CHOLMOD alone, by phase (s):\n")
    table(["unknowns", "analyze", "factorize", "solve", "total", "vemcontact analyze+factorize+solve"],
          [[fmt_n(r["unknowns"]), fmt_t(r["cholmod_analyze_s"]), fmt_t(r["cholmod_factorize_s"]),
            fmt_t(r["cholmod_solve_s"]), fmt_t(r["cholmod_total_s"]),
            fmt_t(float(r["analyze_s"]) + float(r["factorize_s"]) + float(r["solve_s"]))] for r in rs])
    xs = [float(r["unknowns"]) for r in rs]
    growth("linear", xs, [(p, [float(r[p + "_s"]) for r in rs]) for p in phases]
           + [("peak RSS", [float(r["peak_MB"]) for r in rs]),
              ("CHOLMOD alone", [float(r["cholmod_total_s"]) for r in rs])], "n")


def contact(path):
    rs = rows(path)
    if not rs:
        return
    print("## Contact runs\n")
    for n in notes(path):
        print(f"- {n}")
    print()
    failed = [r for r in rs if r["nodes"].startswith("failed") or not r.get("total_s")]
    rs = [r for r in rs if r not in failed]
    for r in failed:
        print(f"- failed: {r['case']} {r['unknowns_target']}: {r['nodes']}")
    for case in dict.fromkeys(r["case"] for r in rs):
        cr = [r for r in rs if r["case"] == case]
        print(f"### {case}\n")
        phases = ["mesh", "read", "pattern", "assemble", "analyze", "factorize", "solve", "search", "write",
                  "total"]
        head = ["unknowns", "slave nodes", "master segs"] + phases + ["iter.", "peak RSS"]
        table(head, [[fmt_n(r["unknowns"]), fmt_n(r["slave_nodes"]), fmt_n(r["master_segments"])]
                     + [fmt_t(r[p + "_s"]) for p in phases] + [r["iterations"], fmt_mb(r["peak_MB"])]
                     for r in cr])
        print("Per iteration (means; iteration / factorization over the iterations after the first, "
              "without pattern rebuilds):\n")
        table(["unknowns", "iterations", "rebuilds", "iteration", "factorization", "search",
               "search / iteration", "iteration / factorization", "worst", "candidates (in pattern)"],
              [[fmt_n(r["unknowns"]), r["iterations"], r["pattern_rebuilds"], fmt_t(r["mean_iter_s"]),
                fmt_t(r["mean_factorize_s"]), fmt_t(r["mean_search_s"]),
                f"{float(r['mean_search_s']) / float(r['mean_iter_s']):.1e}",
                f"**{float(r['iter_over_factorize']):.3f}**", f"{float(r['worst_iter_over_factorize']):.3f}",
                fmt_t(r["candidates_s"])] for r in cr])
        xs = [float(r["unknowns"]) for r in cr]
        growth(f"contact, {case}, against unknowns", xs,
               [(p, [float(r[p + "_s"]) for r in cr]) for p in phases]
               + [("search / iteration", [float(r["mean_search_s"]) for r in cr]),
                  ("peak RSS", [float(r["peak_MB"]) for r in cr])], "n")
        ns = [float(r["slave_nodes"]) for r in cr]
        growth(f"contact, {case}, search against slave nodes", ns,
               [("search / iteration", [float(r["mean_search_s"]) for r in cr]),
                ("candidates", [float(r["candidates_s"]) for r in cr])], "n_slave")


if __name__ == "__main__":
    linear(sys.argv[1])
    contact(sys.argv[2])
