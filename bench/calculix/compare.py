#!/usr/bin/env python3
"""vemcontact against CalculiX (ccx) on the same CPE4 decks: linear cantilever and
Hertz contact.  Run through bench/calculix/run.sh (which installs ccx and builds
vemcontact); by hand, from the repository root:

    PYTHONPATH=postprocess .venv/bin/python bench/calculix/compare.py [--sizes 50 100 200 500]
        [--hertz 389 600 1155 h5k h20k h100k] [--residual-max 200]

Writes bench/results/calculix_linear.csv, bench/results/calculix_hertz.csv,
bench/calculix/figures/calculix_scaling.png and docs/calculix-comparison.md.
Every run is sequential (one process at a time) under /usr/bin/time -v: wall time
("Elapsed") and peak resident memory ("Maximum resident set size") of the whole
process.  Both codes get the same threads: OMP_NUM_THREADS = OPENBLAS_NUM_THREADS
= the number of cores (ccx's own default is 1 thread; vemcontact's OpenBLAS would
take all cores).
"""
import argparse
import csv
import datetime
import os
import pathlib
import platform
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import h5py

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent
VC = ROOT / "build" / "vemcontact"
PY = sys.executable
P0, A_HALF = 83.60, 1.523          # analytical Hertz peak pressure and half-width

NPROC = os.cpu_count() or 1
ENV = dict(os.environ, OMP_NUM_THREADS=str(NPROC), OPENBLAS_NUM_THREADS=str(NPROC))


def timed(cmd, cwd):
    """Run cmd under /usr/bin/time -v; return (wall s, peak MB, stdout)."""
    tfile = pathlib.Path(cwd) / "time.txt"
    r = subprocess.run(["/usr/bin/time", "-v", "-o", str(tfile)] + cmd, cwd=cwd, env=ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(map(str, cmd))} in {cwd}\n{r.stdout[-3000:]}")
    t = tfile.read_text()
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", t)
    parts = [float(x) for x in m.group(1).split(":")]
    wall = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1)) / 1024
    return wall, rss, r.stdout


def run_quiet(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(map(str, cmd))}\n{r.stdout[-3000:]}")
    return r.stdout


def dat_blocks(path, title):
    """Rows (id, values...) of the last block of a ccx .dat file whose header starts
    with title (ccx prints every increment; the last is the end of the step)."""
    rows, inblock = [], False
    for line in pathlib.Path(path).read_text().splitlines():
        s = line.strip()
        if not s:
            continue
        if s[0].isalpha():
            inblock = s.startswith(title)
            if inblock:
                rows = []
            continue
        if inblock:
            f = s.split()
            rows.append((int(f[0]), [float(x) for x in f[1:]]))
    return rows


def half_ulp_e13_6(v):
    """Half a unit in the last place of CalculiX's e13.6 print of v (7 significant digits)."""
    a = np.abs(v)
    e = np.floor(np.log10(np.where(a > 0, a, 1e-300)))
    return np.where(a > 0, 0.5e-6 * 10.0 ** e, 0.5e-6 * 1e-300)


def vc_log_value(log, key):
    m = re.search(rf"^\s*{key}\s+([0-9.Ee+-]+) s", log, re.M)
    return float(m.group(1)) if m else float("nan")


def ccx_equations(out):
    m = re.findall(r"number of equations\s+(\d+)", out)
    return int(m[-1]) if m else 0


# ---------------------------------------------------------------- linear cantilever
def linear_case(n, work, residual):
    d = work / f"cant{n}"
    run_quiet([PY, str(HERE / "make_cantilever.py"), str(n), str(d)], ROOT)
    vc_wall, vc_rss, _ = timed([str(VC), "-q", "-o", "vc", "vc.inp"], d)
    log = (d / "vc" / "vc.log").read_text()
    with h5py.File(d / "vc" / "vc.h5") as f:
        u = f["steps/0001/U"][...]
        ids = f["mesh/node_ids"][...]
    assert np.all(ids == np.arange(1, len(ids) + 1))
    cx_wall, cx_rss, out = timed(["ccx", "ccx"], d)
    rows = dat_blocks(d / "ccx.dat", "displacements")
    uc = np.zeros_like(u)
    for k, v in rows:
        uc[k - 1] = v[:2]
    umax = np.abs(u).max()
    diff = np.abs(u - uc)
    rel = diff.max() / umax
    big = np.abs(u) >= 1e-4 * umax          # near-zero components excluded (see the report)
    ulps = (diff[big] / half_ulp_e13_6(uc[big])).max()
    row = dict(n=n, nodes=len(u), elements=n * n, unknowns=2 * len(u),
               free_unknowns=2 * len(u) - 2 * (n + 1), ccx_equations=ccx_equations(out),
               vc_wall_s=round(vc_wall, 3), vc_peak_MB=round(vc_rss, 1),
               vc_total_s=vc_log_value(log, "total"),
               ccx_wall_s=round(cx_wall, 3), ccx_peak_MB=round(cx_rss, 1),
               time_ratio=round(cx_wall / vc_wall, 2), memory_ratio=round(cx_rss / vc_rss, 2),
               u_max=f"{umax:.6e}", max_abs_diff_rel=f"{rel:.3e}", diff_in_print_halfulps=f"{ulps:.3f}",
               residual_rel="", du_rel="")
    if residual:
        np.save(d / "u.npy", u)
        run_quiet([PY, str(HERE / "make_cantilever.py"), str(n), str(d), "--residual", str(d / "u.npy")], ROOT)
        run_quiet(["ccx", "ccx_res"], d)
        rf = np.zeros_like(u)
        for k, v in dat_blocks(d / "ccx_res.dat", "forces"):
            rf[k - 1] = v[:2]
        f = np.zeros_like(u)
        for line in (d / "vc.inp").read_text().split("*CLOAD")[1].splitlines()[1:]:
            if line.startswith("*"):
                break
            k, dof, val = line.split(",")
            f[int(k) - 1, int(dof) - 1] += float(val)
        free = np.ones(len(u), bool)
        free[0::n + 1] = False                         # the clamped nodes carry reactions
        r = np.where(free[:, None], rf - f, 0.0)
        row["residual_rel"] = f"{np.abs(r).max() / np.abs(f).max():.3e}"
        # the displacement error of our solution in CalculiX's equations: K^-1 r,
        # solved by vemcontact (same stiffness) with r as the loads
        deck = (d / "vc.inp").read_text().split("*CLOAD")[0]
        loads = [f"{k + 1}, {j + 1}, {r[k, j]:.9e}" for k in range(len(u)) for j in (0, 1)
                 if free[k] and r[k, j] != 0.0]
        (d / "vc_du.inp").write_text(deck + "*CLOAD\n" + "\n".join(loads) + "\n*END STEP\n")
        run_quiet([str(VC), "-q", "-o", "du", "vc_du.inp"], d)
        with h5py.File(d / "du" / "vc_du.h5") as h:
            du = h["steps/0001/U"][...]
        row["du_rel"] = f"{np.abs(du).max() / umax:.3e}"
    shutil.rmtree(d)
    return row


# ---------------------------------------------------------------- Hertz contact
def vc_hertz_deck(name, work):
    """vemcontact's Hertz deck: inputs/hertz_N_fem.inp, or the 1155 deck on a refined mesh."""
    if name.isdigit():
        return ROOT / "inputs" / f"hertz_{name}_fem.inp"
    meshdir = work / "meshes"
    if not meshdir.exists():
        run_quiet([PY, "-m", "vctools.mesh", "scene", str(HERE / "hertz_refined_fem.toml"), "-o", f"{meshdir}/"], ROOT)
    mesh = meshdir / f"hertz_refined_fem_{name}.inp"
    text = (ROOT / "inputs" / "hertz_1155_fem.inp").read_text()
    deck = work / f"hertz_{name}_fem.inp"
    deck.write_text(text.replace("meshes/ex2_hertz_1155_fem.inp", str(mesh)))
    return deck


def ccx_pressures(dat, nmax):
    """{2D node id: pressure} from *CONTACT PRINT CSTR; a 2D node k is expanded by
    CalculiX into nodes nmax + 3 (k-1) + 1 and + 3 (front and back layers); the
    pressure of a 2D node is the mean of its two springs.  Also returns the largest
    difference between the two."""
    p = {}
    for e, v in dat_blocks(dat, "contact stress"):
        k, rem = divmod(e - nmax - 1, 3)
        assert rem in (0, 2), e
        p.setdefault(k + 1, []).append(v[0])
    assert all(len(v) == 2 for v in p.values()), p
    # the two layers' springs agree to ccx's Newton tolerance, not exactly (3e-5 seen)
    layer = max(abs(v[0] - v[1]) for v in p.values())
    return {k: 0.5 * (v[0] + v[1]) for k, v in p.items()}, layer


def hertz_case(name, work):
    d = work / f"hertz_{name}"
    d.mkdir()
    deck = vc_hertz_deck(name, work)
    vc_wall, vc_rss, _ = timed([str(VC), "-q", "-o", "vc", str(deck)], d)
    job = deck.stem
    log = (d / "vc" / f"{job}.log").read_text()
    unknowns = int(re.search(r"unknowns (\d+)", log).group(1))
    iters = int(re.search(r"contact converged in (\d+) iterations", log).group(1))
    pv = {}
    with open(d / "vc" / f"{job}_contact_pair1_0001.csv") as f:
        for r in csv.DictReader(f):
            pv[int(r["node"])] = float(r["CPRESS"])
    out = {}
    variants = [("small", [])]
    if unknowns <= 50000:        # the finite-sliding run is for the explanation, not timed in the target
        variants.append(("finite", ["--finite-sliding"]))
    for variant, extra in variants:
        dd = d / variant
        run_quiet([PY, str(HERE / "make_hertz.py"), str(deck), str(dd)] + extra, ROOT)
        nmax = max(int(l.split(",")[0]) for l in (dd / "mesh.inp").read_text().split("*NODE")[1].splitlines()[1:]
                   if l and l[0].isdigit())
        wall, rss, o = timed(["ccx", "ccx"], dd)
        pc, layer = ccx_pressures(dd / "ccx.dat", nmax)
        incs = len(re.findall(r"^ increment \d+ attempt", o, re.M))
        its = len(re.findall(r"^ iteration \d+", o, re.M))
        out[variant] = (wall, rss, pc, incs, its, ccx_equations(o), layer)
    wall, rss, pc, incs, its, neq, layer = out["small"]
    fin = out.get("finite")
    pv_peak, pc_peak = max(pv.values()), max(pc.values())
    nodes = sorted(set(pv) | set(pc))
    dp = max(abs(pv.get(k, 0.0) - max(pc.get(k, 0.0), 0.0)) for k in nodes)
    closed_v = sum(1 for v in pv.values() if v > 0)
    closed_c = sum(1 for v in pc.values() if v > 1e-3)       # open springs carry -sigma_inf
    row = dict(mesh=name, unknowns=unknowns, ccx_equations=neq, vc_iterations=iters,
               ccx_increments=incs, ccx_iterations=its,
               vc_wall_s=round(vc_wall, 3), vc_peak_MB=round(vc_rss, 1),
               ccx_wall_s=round(wall, 3), ccx_peak_MB=round(rss, 1),
               time_ratio=round(wall / vc_wall, 2), memory_ratio=round(rss / vc_rss, 2),
               closed_vc=closed_v, closed_ccx=closed_c,
               peak_vc=f"{pv_peak:.4f}", peak_ccx=f"{pc_peak:.4f}",
               peak_rel_diff=f"{(pc_peak - pv_peak) / pv_peak:.2e}",
               max_node_diff_rel=f"{dp / pv_peak:.2e}",
               ccx_layer_diff_rel=f"{layer / pc_peak:.1e}",
               peak_vc_vs_analytical=f"{(pv_peak - P0) / P0:+.4f}",
               peak_ccx_finite_sliding=f"{max(fin[2].values()):.4f}" if fin else "",
               ccx_finite_increments=fin[3] if fin else "", ccx_finite_wall_s=round(fin[0], 3) if fin else "")
    shutil.rmtree(d)
    return row


# ---------------------------------------------------------------- report
def machine():
    cpu = "?"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    mem = int(re.search(r"MemTotal:\s+(\d+)", open("/proc/meminfo").read()).group(1)) / 1048576
    ccxv = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "calculix-ccx"], stdout=subprocess.PIPE, text=True).stdout
    vcv = subprocess.run([str(VC), "--version"], stdout=subprocess.PIPE, text=True).stdout.strip()
    return (f"{NPROC} cores ({cpu}), {mem:.0f} GiB, {platform.system()} {platform.release()}; "
            f"{vcv} (Release build), CalculiX ccx {ccxv} (Debian package calculix-ccx, SPOOLES solver); "
            f"OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = {NPROC} for both")


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def plot(lin, hz, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for rows, mark, what in ((lin, "o", "cantilever"), (hz, "s", "Hertz")):
        x = [r["unknowns"] for r in rows]
        ax[0].loglog(x, [r["vc_wall_s"] for r in rows], "b" + mark + "-", label=f"vemcontact, {what}")
        ax[0].loglog(x, [r["ccx_wall_s"] for r in rows], "r" + mark + "--", label=f"ccx, {what}")
        ax[1].loglog(x, [r["vc_peak_MB"] for r in rows], "b" + mark + "-", label=f"vemcontact, {what}")
        ax[1].loglog(x, [r["ccx_peak_MB"] for r in rows], "r" + mark + "--", label=f"ccx, {what}")
    ax[0].set(xlabel="unknowns (2 x nodes)", ylabel="wall time [s]", title="wall time")
    ax[1].set(xlabel="unknowns (2 x nodes)", ylabel="peak RSS [MB]", title="peak memory")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


def fmt_int(v):
    return f"{v:,}".replace(",", " ")


def report(lin, hz, mach, when, elapsed, path):
    L = []
    w = L.append
    w("# vemcontact against CalculiX on the same CPE4 decks")
    w("")
    w("Issue 6, part 4. Generated by `bash bench/calculix/run.sh` (one command: installs the")
    w("Debian packages `calculix-ccx` and `time`, builds vemcontact in Release if needed, runs")
    w("every case and rewrites this page). Raw numbers: `bench/results/calculix_linear.csv`,")
    w("`bench/results/calculix_hertz.csv`; plot: `bench/calculix/figures/calculix_scaling.png`.")
    w("Timings are benchmark output, not tests: each table is one run on a shared, noisy")
    w("machine, and the ratios are taken within that run.")
    w("")
    w(f"**Machine:** {mach}. Run {when}, {elapsed:.0f} s in all.")
    w("")
    w("Wall time and peak memory are those of the whole process under `/usr/bin/time -v`")
    w("(read the deck, assemble, factorize, solve, write the results): vemcontact writes")
    w("VTU + HDF5 (+ contact CSV), ccx writes its `.dat` print of the requested nodes.")
    w("\"Unknowns\" is 2 x the number of nodes of the 2D mesh, the same mesh for both codes.")
    w("")
    w("## Linear cantilever")
    w("")
    w("Square plate [0, 10] x [0, 10] as a deep cantilever: n x n CPE4, plane strain,")
    w("E = 1000, nu = 0.3, thickness 1, clamped at x = 0, total tip shear -1 on x = 10 as")
    w("consistent nodal loads (`bench/calculix/make_cantilever.py`). The square matches the")
    w("issue's 500 x 500 reference case and keeps every element square, so the comparison")
    w("measures the codes, not an ill-conditioned mesh. Both codes read the same")
    w("`mesh.inp` and the same model lines; the CalculiX deck adds only `*NODE PRINT, U`.")
    w("")
    w("| n x n | unknowns | ccx equations | vemcontact | ccx | time ratio | vemcontact peak | ccx peak | memory ratio |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in lin:
        w(f"| {r['n']} x {r['n']} | {fmt_int(r['unknowns'])} | {fmt_int(r['ccx_equations'])} | {r['vc_wall_s']:.2f} s | "
          f"{r['ccx_wall_s']:.2f} s | **{r['time_ratio']:.1f}** | {r['vc_peak_MB']:.0f} MB | {r['ccx_peak_MB']:.0f} MB | "
          f"**{r['memory_ratio']:.1f}** |")
    big = lin[-1]
    ok_t = big["time_ratio"] >= 5
    ok_m = big["memory_ratio"] >= 5
    w("")
    w(f"Target at equal unknowns: at least 5 times faster and at most one fifth of the memory. At")
    w(f"{big['n']} x {big['n']} ({fmt_int(big['unknowns'])} unknowns): ccx / vemcontact = "
      f"{big['time_ratio']:.1f} in time ({'met' if ok_t else 'NOT met'}) and {big['memory_ratio']:.1f} in "
      f"memory ({'met' if ok_m else 'NOT met'}).")
    w("")
    w("### Agreement of the displacements")
    w("")
    w("| n x n | max abs U | max abs(U_vc - U_ccx) / max abs U | same, in half-units of ccx's last printed digit | residual of U_vc in ccx | K^-1 residual / max abs U |")
    w("|---|---:|---:|---:|---:|---:|")
    for r in lin:
        w(f"| {r['n']} x {r['n']} | {r['u_max']} | {r['max_abs_diff_rel']} | {r['diff_in_print_halfulps']} | "
          f"{r['residual_rel'] or '-'} | {r['du_rel'] or '-'} |")
    w("")
    w("ccx prints displacements with 7 significant digits (`e13.6`, in `.dat` and `.frd`")
    w("alike), so a direct comparison cannot go below about 5e-7 relative. The fourth column")
    w("divides each difference by half a unit of the last printed digit of that value (for the")
    w("components above 1e-4 max abs U: smaller ones include round-off zeros such as 1e-18 on")
    w("the mid-line, and there half a printed unit falls below the solvers' own round-off):")
    w("at most 1 means that ccx's displacements are vemcontact's rounded to 7 digits. To go to")
    w("solver precision the check is turned around (`make_cantilever.py --residual`):")
    w("vemcontact's displacements are prescribed in ccx on every node (14 digits, the most")
    w("ccx's 20-character fields hold; one dof left free because ccx needs an unknown), and")
    w("ccx returns the nodal forces RF = K_ccx U_vc. Their difference from the applied loads")
    w("at the unclamped nodes, relative to the largest load, is the \"residual\" column; solved")
    w("with vemcontact's own stiffness (the same matrix) it gives the displacement error of")
    w("our solution in ccx's equations, the last column. Both at round-off level mean the")
    w("element stiffness matrices, the plane-strain material and the loads are the same.")
    w("The error of our solution grows with the condition number (about n^2), which is why")
    w("the largest mesh can exceed one half-unit slightly on its smallest components above")
    w("the 1e-4 cut-off: there half a printed unit is 5e-11 of max abs U, the size of K^-1 r.")
    w("")
    w("What ccx does with CPE4 (ccx 2.20 source, `elements.f`, `gen3delem.f`): every plane")
    w("element is expanded into a one-layer brick. CPE4 becomes C3D8 with full 2 x 2 x 2")
    w("Gauss integration (8 integration points: CPE4R would become the reduced C3D8R), the")
    w("expanded nodes are tied back to the 2D node by MPCs (the printed \"multiple point")
    w("constraints\"), and the out-of-plane dof is fixed for plane strain. With the in-plane")
    w("displacement constant through the thickness and w = 0, the 2 x 2 x 2 rule of the brick")
    w("is exactly the 2 x 2 rule of the quad times the thickness, so the element is the same")
    w("as vemcontact's FEM quad; the equation count ccx prints equals the free 2D unknowns.")
    w("The cost of the expansion is memory and set-up time: three times the nodes (ccx")
    w("numbers three expanded nodes per 2D node and uses two), eight-node bricks, and the")
    w("MPC bookkeeping.")
    w("")
    w("## Hertz contact")
    w("")
    w("The paper's Hertz half model (disc R = 10, E = 1e3, on a block, E = 1e6, nu = 0.3,")
    w("P = 100 on the half disc, K = 1e5; analytical p0 = 83.60, a = 1.523) on the quad")
    w("meshes `inputs/meshes/ex2_hertz_{389,600,1155}_fem.inp` and on refined quad meshes of")
    w("the same scene (`bench/calculix/hertz_refined_fem.toml`: h5k, h20k, h100k).")
    w("vemcontact runs `inputs/hertz_*_fem.inp` unchanged (the refined meshes through the")
    w("1155 deck); the ccx deck is written from it by `bench/calculix/make_hertz.py`, whose")
    w("header lists every change: slave as element faces (same areas as vemcontact's node")
    w("surface), `PRESSURE-OVERCLOSURE=LINEAR` with K = 1e5, sigma_inf = 1e-5, c0 = 10,")
    w("`SMALL SLIDING`, one increment, `*CONTACT PRINT, CSTR`.")
    w("")
    w("| mesh | unknowns | vemcontact (iterations) | ccx (increments / iterations) | time ratio | vemcontact peak | ccx peak | memory ratio |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in hz:
        w(f"| {r['mesh']} | {fmt_int(r['unknowns'])} | {r['vc_wall_s']:.2f} s ({r['vc_iterations']}) | "
          f"{r['ccx_wall_s']:.2f} s ({r['ccx_increments']} / {r['ccx_iterations']}) | **{r['time_ratio']:.1f}** | "
          f"{r['vc_peak_MB']:.0f} MB | {r['ccx_peak_MB']:.0f} MB | **{r['memory_ratio']:.1f}** |")
    w("")
    w("| mesh | closed nodes vc / ccx | peak pressure vemcontact | vs 83.60 | peak pressure ccx | ccx - vc (relative) | worst node (relative to peak) | ccx without SMALL SLIDING |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in hz:
        w(f"| {r['mesh']} | {r['closed_vc']} / {r['closed_ccx']} | {r['peak_vc']} | {float(r['peak_vc_vs_analytical']) * 100:+.2f} % | "
          f"{r['peak_ccx']} | {r['peak_rel_diff']} | {r['max_node_diff_rel']} | {r['peak_ccx_finite_sliding'] or '(not run)'} |")
    hb = hz[-1]
    w("")
    w(f"At the largest mesh ({hb['mesh']}, {fmt_int(hb['unknowns'])} unknowns) ccx / vemcontact = "
      f"{hb['time_ratio']:.1f} in time and {hb['memory_ratio']:.1f} in memory.")
    w("")
    w("What the columns show and what ccx does:")
    w("")
    w("- ccx's node-to-face penalty contact is a nonlinear spring per slave node (and per")
    lay = max(float(r["ccx_layer_diff_rel"]) for r in hz)
    w("  layer of the expansion: two springs per 2D node, whose printed pressures are "
      + ("equal here" if lay == 0 else f"within {lay:.1e} of the peak here") + "; the tables use")
    w("  their mean). Its LINEAR law is")
    w("  the smoothed ramp p = K h (1/2 + atan(h/eps)/pi), eps = pi sigma_inf / K")
    w("  (`springforc_n2f.f`): p = K h - sigma_inf in contact and a tension sigma_inf at large")
    w("  clearance. sigma_inf must be positive (0 is replaced by a default with an *INFO*);")
    w("  with sigma_inf = 1e-5 the law is vemcontact's p = K <h> to 1e-7 of the peak and Newton")
    w("  still converges in a handful of iterations. c0 decides which slave nodes get a")
    w("  spring (clearance below c0 sqrt(slave area), default 1e-3): 10 gives all of them one.")
    w("- The pressure printed is K h in both codes; the force is pressure times the slave's")
    w("  tributary area. ccx computes those areas from the *current* coordinates")
    w("  (`gencontelem_n2f.f`, co + vold) every iteration, unless `SMALL SLIDING`, which")
    w("  pairs and measures once per increment, at its start. The last column is ccx without")
    w("  it (run up to 50 000 unknowns): the disc's contact faces shrink laterally by about 3 %, so the same load needs")
    w("  about 3 % more pressure. That is a finite-deformation effect that a small-strain")
    w("  code leaves out by design; with `SMALL SLIDING` and one increment ccx uses the")
    w("  undeformed areas, as vemcontact does.")
    w("- What remains is small: ccx measures the clearance between current positions, where")
    w("  vemcontact linearises the gap about the undeformed pairing. The slave nodes slide by")
    w("  up to about 0.03 along the slightly deflected master, which shows at the edge of the")
    w("  contact zone (the worst node) more than at the peak. No `NLGEOM` in either code.")
    w("- ccx solves the contact with Newton iterations on the springs (its increment and")
    w("  iteration counts above); vemcontact with active-set iterations on a linear system.")
    w("")
    w("## Reproduce")
    w("")
    w("    bash bench/calculix/run.sh                   # everything, as above")
    w("    bash bench/calculix/run.sh --sizes 50 100 --hertz 389 600   # a subset")
    w("")
    w("The decks can be written on their own: `python bench/calculix/make_cantilever.py N DIR`")
    w("(`DIR/vc.inp`, `DIR/ccx.inp`, shared `DIR/mesh.inp`; run ccx as `ccx ccx` inside DIR)")
    w("and `python bench/calculix/make_hertz.py inputs/hertz_389_fem.inp DIR`.")
    path.write_text("\n".join(L) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[50, 100, 200, 500])
    ap.add_argument("--hertz", nargs="+", default=["389", "600", "1155", "h5k", "h20k", "h100k"])
    ap.add_argument("--residual-max", type=int, default=500,
                    help="largest n for the residual check (one more untimed ccx run each)")
    a = ap.parse_args()
    t0 = datetime.datetime.now()
    work = pathlib.Path(tempfile.mkdtemp(prefix="vc_ccx_"))
    lin, hz = [], []
    try:
        for n in a.sizes:
            r = linear_case(n, work, n <= a.residual_max)
            print(f"cantilever {n}x{n}: vc {r['vc_wall_s']} s {r['vc_peak_MB']} MB, ccx {r['ccx_wall_s']} s "
                  f"{r['ccx_peak_MB']} MB, ratios {r['time_ratio']} / {r['memory_ratio']}, "
                  f"diff {r['max_abs_diff_rel']} ({r['diff_in_print_halfulps']} half-ulps), "
                  f"residual {r['residual_rel']}, du {r['du_rel']}", flush=True)
            lin.append(r)
        for name in a.hertz:
            r = hertz_case(name, work)
            print(f"hertz {name}: vc {r['vc_wall_s']} s {r['vc_peak_MB']} MB, ccx {r['ccx_wall_s']} s "
                  f"{r['ccx_peak_MB']} MB, ratios {r['time_ratio']} / {r['memory_ratio']}, peaks "
                  f"{r['peak_vc']} / {r['peak_ccx']} (finite sliding {r['peak_ccx_finite_sliding']})", flush=True)
            hz.append(r)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    mach = machine()
    for r in lin + hz:
        r["machine"] = mach
    res = ROOT / "bench" / "results"
    res.mkdir(parents=True, exist_ok=True)
    if lin:
        write_csv(res / "calculix_linear.csv", lin)
    if hz:
        write_csv(res / "calculix_hertz.csv", hz)
    if lin and hz:
        plot(lin, hz, HERE / "figures" / "calculix_scaling.png")
        elapsed = (datetime.datetime.now() - t0).total_seconds()
        report(lin, hz, mach, t0.strftime("%Y-%m-%d %H:%M"), elapsed, ROOT / "docs" / "calculix-comparison.md")
    print("machine:", mach)


if __name__ == "__main__":
    main()
