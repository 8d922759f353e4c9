"""Markdown tables of bench/results/contact_formulations.csv (bench/contact_formulations.sh)
for docs/performance.md: per size, each formulation's phases, iterations, factorizations
and its total against the node-to-segment penalty run on the same mesh (same run)."""
import csv
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LABEL = {"nts-pen": "NTS penalty (K = 1e12)", "nts-hard": "NTS HARD", "nts-hard-s": "NTS HARD, SMALL SLIDING",
         "s2s-hard": "S2S HARD"}


def _n(v):
    return f"{int(v):,}".replace(",", " ")


def main(path=os.path.join(ROOT, "bench", "results", "contact_formulations.csv")):
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    rows = list(csv.DictReader(lines))
    print("| unknowns | formulation | inserted nodes | iterations | factorizations | re-solves | analyze | "
          "factorize (mean) | solve | other | total | total / NTS penalty | load |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for target in dict.fromkeys(r["unknowns_target"] for r in rows):
        rs = [r for r in rows if r["unknowns_target"] == target]
        ref = next((float(r["total_s"]) for r in rs if r["formulation"] == "nts-pen" and r["status"] == "ok"), None)
        for r in rs:
            if r["status"] != "ok":
                print(f"| {_n(r['unknowns'])} | {LABEL[r['formulation']]} | | | | | | | | | **{r['status']}** | | |")
                continue
            it, fa = int(r["iterations"]), int(r["factorizations"])
            tot = float(r["total_s"])
            ratio = f"**{tot / ref:.2f}**" if ref else "-"
            print(f"| {_n(r['unknowns'])} | {LABEL[r['formulation']]} | {r['inserted']} | {it} | {fa} | {it - fa} | "
                  f"{float(r['analyze_s']):.3g} | {float(r['factorize_s']):.3g} ({float(r['mean_factorize_s']):.3g}) | "
                  f"{float(r['solve_s']):.3g} | {float(r['other_s']):.3g} | {tot:.3g} | {ratio} | {r['load']} |")


if __name__ == "__main__":
    main(*sys.argv[1:])
