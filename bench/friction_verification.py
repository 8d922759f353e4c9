"""Convergence of the friction verification cases (docs/friction-verification.md): F4, the
closed inclined crack, and F5, Cattaneo-Mindlin, under refinement, and the paper's Hertz
case with friction.  Prints the tables of the document (markdown) and writes the figures
docs/figures/friction_crack.png and docs/figures/friction_mindlin.png.

    nice .venv/bin/python bench/friction_verification.py [--exe build/vemcontact] [--quick]

The decks are those of postprocess/tests/friction_cases.py (the tests run their coarse
meshes).  Accuracy only: the times printed are for orientation, not measurements.
"""
import argparse
import pathlib
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "postprocess" / "tests"))
import friction_cases as fc
from h5results import iteration_records


def unknowns(path):
    """2 x the number of nodes of a generated deck (its *NODE lines)."""
    text = path.read_text()
    block = text.split("*NODE\n", 1)[1].split("*", 1)[0]
    return 2 * sum(1 for line in block.splitlines() if line.strip())


def order(errs, hs):
    out = [""]
    for i in range(1, len(errs)):
        out.append(f"{np.log(abs(errs[i - 1]) / abs(errs[i])) / np.log(hs[i - 1] / hs[i]):.2f}")
    return out


def crack_study(exe, work, ns, etypes, widths):
    rows, profiles = [], {}
    for etype in etypes:
        for width in widths:
            errs = []
            for n in ns:
                path = fc.crack_deck(work / f"crack_{etype}_{int(width)}_{n}.inp", n, 30.0, 0.3, etype=etype,
                                     width=width)
                t = time.time()
                h5 = fc.run(exe, path)
                wall = time.time() - t
                res, _ = fc.pair_results(h5)
                its = max(r["iteration"].size for r in iteration_records(h5))
                d, l2 = fc.crack_errors(res, 30.0, 0.3)
                errs.append((n, unknowns(path), d, l2, its, wall))
                profiles[(etype, width, n)] = (res["x"], np.abs(res["CSLIP"]))
            hs = [1.0 / e[0] for e in errs]
            od, ol = order([e[2] for e in errs], hs), order([e[3] for e in errs], hs)
            for i, (n, nu, d, l2, its, wall) in enumerate(errs):
                rows.append(f"| {etype} | {width:g} a | a/{n} | {nu} | {100 * d:+.2f} % | {od[i]} | {100 * l2:.2f} % | "
                            f"{ol[i]} | {its} | {wall:.1f} |")
    # exact stick control
    stick = []
    for etype in etypes:
        path = fc.crack_deck(work / f"crack_stick_{etype}.inp", ns[-1], 60.0, 0.6, etype=etype)
        res, _ = fc.pair_results(fc.run(exe, path))
        b = np.radians(60.0)
        stick.append(f"| {etype} | a/{ns[-1]} | {np.abs(res['CSLIP']).max():.1e} | "
                     f"{np.abs(res['CPRESS'] / (10.0 * np.sin(b) ** 2) - 1.0).max():.1e} | "
                     f"{np.abs(np.abs(res['CSHEAR']) / (10.0 * np.sin(b) * np.cos(b)) - 1.0).max():.1e} | "
                     f"{'all STICK' if (res['STATUS'] == 3).all() else 'not all STICK'} |")
    return rows, stick, profiles


def voronoi_study(exe, work, cells_list):
    """F4 on the mesher's Voronoi cells and joint (crack_voronoi_deck), beta = 30, mu = 0.3."""
    rows = []
    for cells in cells_list:
        path = fc.crack_voronoi_deck(work / f"voronoi_{cells}.inp", cells, 30.0, 0.3)
        t = time.time()
        h5 = fc.run(exe, path)
        wall = time.time() - t
        res, _ = fc.pair_results(h5)
        its = max(r["iteration"].size for r in iteration_records(h5))
        d, l2 = fc.crack_errors(res, 30.0, 0.3)
        h = np.diff(np.sort(np.r_[res["x"], -1.0, 1.0])).mean()
        law = np.abs(np.abs(res["CSHEAR"]) - 0.3 * res["CPRESS"]).max()
        status = "all SLIP" if (res["STATUS"] == 4).all() else "not all SLIP"
        rows.append(f"| {cells} | {len(res['x'])} | a/{1.0 / h:.0f} | {100 * d:+.2f} % | {100 * l2:.2f} % | {its} | "
                    f"{status}, law {law:.0e} | {wall:.1f} |")
    return rows


def mindlin_study(exe, work, ns, etypes):
    rows, profiles = [], {}
    for etype in etypes:
        errs = []
        for n in ns:
            path = fc.mindlin_deck(work / f"mindlin_{etype}_{n}.inp", n, press=-0.045, shift=0.010, etype=etype)
            t = time.time()
            h5 = fc.run(exe, path)
            wall = time.time() - t
            res, _ = fc.pair_results(h5, "0002")
            its = max(r["iteration"].size for r in iteration_records(h5))
            e = fc.mindlin_errors(res)
            h = fc.hertz_half_width(10.0) / n
            errs.append((n, unknowns(path), e, its, wall, h))
            profiles[(etype, n)] = (res, e)
        hs = [1.0 / v[0] for v in errs]
        oq = order([v[2]["l2q"] for v in errs], hs)
        op = order([v[2]["l2p"] for v in errs], hs)
        for i, (n, nu, e, its, wall, h) in enumerate(errs):
            rows.append(f"| {etype} | a/{n} | {nu} | {e['P']:.3f} | {e['ratio']:.3f} | {e['c'] / e['a']:.4f} | "
                        f"{e['c_h'] / e['a']:.4f} | {100 * e['c_err']:+.2f} % ({(e['c_h'] - e['c']) / h:+.2f} h) | "
                        f"{100 * e['c_fit_err']:+.2f} % | {100 * e['l2s']:.2f} % | {e['stick_slip']:.0e} | "
                        f"{100 * e['l2q']:.2f} % | {oq[i]} | {100 * e['l2p']:.2f} % | {op[i]} | {its} | {wall:.1f} |")
    return rows, profiles


def hertz_study(exe, work, meshes):
    rows = []
    for mesh in meshes:
        src = (ROOT / "inputs" / f"hertz_{mesh}.inp").read_text()
        src = src.replace("INPUT=meshes/", f"INPUT={ROOT / 'inputs' / 'meshes'}/")
        src = src.replace("TYPE=NODE TO SURFACE\n", "TYPE=NODE TO SURFACE, SMALL SLIDING\n")
        for label, block in (("paper (disc 1e3 on block 1e6)", None), ("identical (block 1e3)", 1.0e3)):
            text = src
            if block is not None:
                text = text.replace("*MATERIAL, NAME=BLOCK_MATERIAL\n*ELASTIC\n1.0e6, 0.3",
                                    f"*MATERIAL, NAME=BLOCK_MATERIAL\n*ELASTIC\n{float(block)!r}, 0.3")
            peaks = []
            for mu in (None, 0.3):
                t = text if mu is None else text.replace("*CONTACT PAIR", f"*FRICTION\n{float(mu)!r}\n*CONTACT PAIR")
                path = work / f"hertz_{mesh}_{'s' if block else 'p'}_{'f' if mu else 'n'}.inp"
                path.write_text(t)
                h5 = fc.run(exe, path)
                res, _ = fc.pair_results(h5)
                its = max(r["iteration"].size for r in iteration_records(h5))
                peaks.append((res["CPRESS"].max(), np.abs(res["CSHEAR"]).max(), (res["STATUS"] == 3).sum(),
                              (res["STATUS"] == 4).sum(), its, (res["CPRESS"] > 0).sum()))
            (p0, _, _, _, i0, c0), (p1, s1, nst, nsl, i1, c1) = peaks
            rows.append(f"| {mesh} | {label} | {p0:.3f} | {p1:.3f} | {100 * (p1 / p0 - 1):+.3f} % | {s1:.3f} | "
                        f"{nst} / {nsl} | {c0} / {c1} | {i0} / {i1} |")
    return rows


def figures(crack_profiles, mindlin_profiles, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    xx = np.linspace(-1.0, 1.0, 401)
    ax.plot(xx, fc.crack_slip(xx, 30.0, 0.3), "k-", label="closed form")
    for key, (x, s) in sorted(crack_profiles.items()):
        if key[0] == "CPE4" and key[1] == 20.0:
            ax.plot(x, s, ".-", ms=3, lw=0.8, label=f"CPE4, h = a/{key[2]}")
    ax.set_xlabel("x / a")
    ax.set_ylabel("slip |delta|")
    ax.set_title("F4: closed crack, beta = 30 deg, mu = 0.3")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "friction_crack.png", dpi=120)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    n = max(k[1] for k in mindlin_profiles if k[0] == "CPE4")
    res, e = mindlin_profiles[("CPE4", n)]
    xx = np.linspace(-1.1 * e["a"], 1.1 * e["a"], 801)
    q, c, a = fc.mindlin_shear(xx, e["P"], e["Q"])
    s = np.sign(e["Q"])
    ax.plot(xx / a, s * q, "k-", label="Cattaneo-Mindlin q(x)")
    ax.plot(xx / a, 0.3 * fc.hertz_pressure(xx, e["P"]), "k--", lw=0.8, label="mu p(x), Hertz")
    closed = res["STATUS"] >= 3
    for status, mark, name in ((3, "o", "STICK"), (4, "s", "SLIP")):
        sel = closed & (res["STATUS"] == status)
        ax.plot(res["x"][sel] / a, s * res["CSHEAR"][sel], mark, ms=3, label=f"CSHEAR, {name}")
    ax.axvline(c / a, color="0.6", lw=0.6)
    ax.axvline(-c / a, color="0.6", lw=0.6)
    ax.set_xlabel("x / a")
    ax.set_ylabel("shear traction")
    ax.set_title(f"F5: Cattaneo-Mindlin, Q/(mu P) = {e['ratio']:.3f}, CPE4 h = a/{n}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "friction_mindlin.png", dpi=120)


def increment_iterations(h5):
    """From the run's log (JOB.log beside JOB.h5; the HDF5 records hold each step's last
    increment only): the contact iterations of every increment, and the number of
    increments cut back.  Log text is fine for a benchmark, not for a test."""
    log = pathlib.Path(h5).with_suffix(".log").read_text()
    its = [int(line.split("converged in")[1].split()[0]) for line in log.splitlines() if "contact converged in" in line]
    return its, log.count("increment not converged: cut back")


def iteration_study(exe, work):
    """Every increment of the verification decks at the sizes the tests run, and the
    CalculiX friction deck: the most contact iterations of an increment, cut-backs."""
    rows = []
    decks = [("F4 slip (beta 30, mu 0.3), CPE4 a/10", fc.crack_deck(work / "it_crack.inp", 10, 30.0, 0.3)),
             ("F4 stick (beta 60, mu 0.6), CPE4 a/10", fc.crack_deck(work / "it_stick.inp", 10, 60.0, 0.6)),
             ("F5 Cattaneo-Mindlin, CPE4 a/10, 4 increments",
              fc.mindlin_deck(work / "it_mindlin.inp", 10, press=-0.045, shift=0.010)),
             ("F5 with the stick slope 1e4 (10 E), a/10",
              fc.mindlin_deck(work / "it_mindlin_slope.inp", 10, press=-0.045, shift=0.010, slope=1.0e4))]
    from test_friction_limit import pad_deck
    pad = pad_deck(work, "*FRICTION\n0.3")
    pad.write_text(pad.read_text().replace("*STATIC\n", "*STATIC, DIRECT\n0.25, 1.0\n"))
    decks.append(("F1 pad (test_friction_limit), 3 steps of 4 increments", pad))
    ccx = ROOT / "tests" / "data" / "calculix" / "two_blocks_friction.inp"
    (work / "it_ccx.inp").write_text(ccx.read_text())
    decks.append(("CalculiX two blocks, 5 increments", work / "it_ccx.inp"))
    for name, path in decks:
        its, cuts = increment_iterations(fc.run(exe, path))
        rows.append(f"| {name} | {len(its)} | {max(its)} | {cuts} |")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", default=str(ROOT / "build" / "vemcontact"))
    ap.add_argument("--quick", action="store_true", help="the coarse meshes only")
    ap.add_argument("--no-figures", action="store_true")
    ap.add_argument("--iterations", action="store_true", help="only the iterations of every increment")
    ap.add_argument("--voronoi", action="store_true", help="only F4 on the mesher's Voronoi cells")
    args = ap.parse_args()
    if args.voronoi:
        with tempfile.TemporaryDirectory() as tmp:
            print("| cells | slave nodes | mean h along the crack | delta_max error | L2 error | iterations | "
                  "status | s |\n|---|---|---|---|---|---|---|---|")
            cells = [500, 1000, 2000] if args.quick else [500, 1000, 2000, 4000, 8000]
            print("\n".join(voronoi_study(args.exe, pathlib.Path(tmp), cells)))
        return
    if args.iterations:
        with tempfile.TemporaryDirectory() as tmp:
            print("| deck | increments (with contact) | most iterations | cut-backs |\n|---|---|---|---|")
            print("\n".join(iteration_study(args.exe, pathlib.Path(tmp))))
        return
    ns_crack = [5, 10, 20] if args.quick else [5, 10, 20, 40, 80]
    ns_mindlin = [5, 10, 20] if args.quick else [5, 10, 20, 40, 80]
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        rows, stick, cprof = crack_study(args.exe, work, ns_crack, ["CPE4", "VPE"], [20.0])
        wrows, _, _ = crack_study(args.exe, work, ns_crack[-2:], ["CPE4"], [40.0])
        print("### F4 slip, beta = 30 deg, mu = 0.3\n")
        print("| element | plate half-width | h | unknowns | delta_max error | order | L2 error | order | iterations | s |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(rows + wrows))
        print("\n### F4 stick, beta = 60 deg, mu = 0.6\n")
        print("| element | h | max abs CSLIP | CPRESS rel. error | CSHEAR rel. error | status |")
        print("|---|---|---|---|---|---|")
        print("\n".join(stick))
        mrows, mprof = mindlin_study(args.exe, work, ns_mindlin, ["CPE4", "VPE"])
        print("\n### F5 Cattaneo-Mindlin\n")
        print("| element | h | unknowns | P | Q/(mu P) | c/a exact | c/a from status | its error | c from tractions, "
              "error | L2 slip | stick slip | L2 q | order | L2 p | order | iterations | s |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(mrows))
        hrows = hertz_study(args.exe, work, ["389_fem", "1155_fem", "600_vem"])
        print("\n### Hertz with friction (mu = 0.3, exact stick)\n")
        print("| mesh | materials | peak p, mu = 0 | peak p, mu = 0.3 | change | max abs CSHEAR | stick / slip | "
              "closed nodes mu = 0 / 0.3 | iterations |")
        print("|---|---|---|---|---|---|---|---|---|")
        print("\n".join(hrows))
        if not args.no_figures:
            figures(cprof, mprof, ROOT / "docs" / "figures")


if __name__ == "__main__":
    main()
