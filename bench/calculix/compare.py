#!/usr/bin/env python3
"""vemcontact against CalculiX (ccx): the linear CPE4 cantilever, the Voronoi
cantilever (VEM polygons in vemcontact, the same mesh as CPE3 triangles in both
codes) and Hertz contact.  Run through bench/calculix/run.sh (which installs ccx
and builds vemcontact); by hand, from the repository root:

    PYTHONPATH=postprocess .venv/bin/python bench/calculix/compare.py [--sizes 50 100 200 500]
        [--voronoi 125000] [--seed 1] [--hertz 389 600 1155 h5k h20k h100k] [--rounds 2]
        [--residual-max 500]

Writes bench/results/calculix_linear.csv, calculix_voronoi.csv, calculix_hertz.csv,
calculix_runs.csv (every timed run, added to those of the earlier runs),
calculix_phases.csv (vemcontact's phases of its fastest run of each case, likewise),
bench/calculix/figures/calculix_scaling.png and
docs/calculix-comparison.md.  `--hertz` with no name (or `--voronoi` with no
size) keeps that part's rows of the previous run (its CSV) in the page, with their date.

Every run is sequential (one process at a time): wall time measured around the
process, peak resident memory by /usr/bin/time -f %M, and the load average
(1 minute) before each run.  Every case runs `--rounds` times, alternating the
programs, and the tables give the minimum of each.  Threads: vemcontact runs with
its defaults (no OPENBLAS_NUM_THREADS / OMP_NUM_THREADS: one BLAS thread, and
`--solver auto`, whose choice is read from the HDF5 root attribute `solver`); ccx
with each of `--ccx-threads` (OMP_NUM_THREADS; default 1, its own default, and the
number of cores, its documented way to use them: CalculiX uses one thread unless
OMP_NUM_THREADS or CCX_NPROC_EQUATION_SOLVER says more), and its faster setting
counts in the ratios.
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
import time

import numpy as np
import h5py

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent
VC = ROOT / "build" / "vemcontact"
PY = sys.executable
P0, A_HALF = 83.60, 1.523          # analytical Hertz peak pressure and half-width

NPROC = os.cpu_count() or 1
ENV_VC = {k: v for k, v in os.environ.items() if k not in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
CCX_THREADS = [1, NPROC]          # ccx runs with each (OMP_NUM_THREADS); the faster counts


def env_ccx(t):
    return dict(ENV_VC, OMP_NUM_THREADS=str(t))


def ccx_progs(cwd, case):
    """alternate() entries of ccx with each thread count of CCX_THREADS."""
    return [(f"ccx t{t}", ["ccx", "ccx"], cwd, env_ccx(t), ccx_after(case)) for t in CCX_THREADS]


def ccx_best(res):
    """The fastest ccx setting of an alternate() result: (min wall, min peak MB, walls,
    threads) and a text of every setting's runs."""
    names = [n for n in res if n.startswith("ccx t")]
    best = min(names, key=lambda n: res[n][0])
    runs = "; ".join(f"{n[5:]} thread(s): " + " ".join(f"{w:.2f}" for w in res[n][2]) for n in names)
    return res[best][0], min(res[n][1] for n in names), res[best][2], int(best[5:]), runs
RUNS = []                          # every timed run, for calculix_runs.csv
PHASES = []                        # vemcontact's phases of the fastest run per case
CCX_EQ = {}                        # ccx's "number of equations" per case


def commit():
    r = subprocess.run(["git", "-C", str(ROOT), "log", "-1", "--format=%h"], stdout=subprocess.PIPE, text=True)
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                           stdout=subprocess.PIPE, text=True).stdout.strip()
    return r.stdout.strip() + ("+changes" if dirty else "")


def timed(cmd, cwd, env=None, label=None):
    """Run cmd under /usr/bin/time -f %M; return (wall s, peak MB, stdout).  With a
    label (case, round, program) the run is also recorded for calculix_runs.csv."""
    tfile = pathlib.Path(cwd) / "time.txt"
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    r = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", str(tfile)] + cmd, cwd=cwd,
                       env=ENV_VC if env is None else env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(map(str, cmd))} in {cwd}\n{r.stdout[-3000:]}")
    rss = int(tfile.read_text().split()[-1]) / 1024
    if label:
        RUNS.append(dict(case=label[0], round=label[1], program=label[2], wall_s=round(wall, 3),
                         peak_MB=round(rss, 1), load1_before=round(load, 2),
                         load1_after=round(os.getloadavg()[0], 2),
                         utc=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")))
    return wall, rss, r.stdout


def alternate(progs, rounds, case):
    """Run the programs [(name, cmd, cwd, env, after)] one after the other, `rounds`
    times; after(round) is called after each run (to read and remove its results).
    Returns {name: (min wall, min peak MB, [walls])} and the loads seen."""
    res = {name: [] for name, *_ in progs}
    loads = []
    for k in range(1, rounds + 1):
        for name, cmd, cwd, env, after in progs:
            wall, rss, out = timed(cmd, cwd, env, (case, k, name))
            loads += [RUNS[-1]["load1_before"], RUNS[-1]["load1_after"]]
            res[name].append((wall, rss))
            if after:
                after(k, wall, out)
    return {n: (min(w for w, _ in v), min(m for _, m in v), [w for w, _ in v]) for n, v in res.items()}, loads


def ccx_after(case):
    def after(k, wall, out):
        CCX_EQ[case] = ccx_equations(out)
    return after


def vc_run(case, name, outdir, deck):
    """The vemcontact entry of alternate(): keeps the solver, the results of the first
    run and the phases of the fastest run."""
    best = {"wall": float("inf")}
    job = pathlib.Path(deck).stem

    def after(k, wall, out):
        d = pathlib.Path(outdir)
        with h5py.File(d / f"{job}.h5") as f:
            best["solver"] = f.attrs["solver"].decode() if isinstance(f.attrs["solver"], bytes) else str(f.attrs["solver"])
            if k == 1:
                best["u"] = f["steps/0001/U"][...]
                best["xy"] = f["mesh/coordinates"][...]
                best["ids"] = f["mesh/node_ids"][...]
        log = (d / f"{job}.log").read_text()
        m = re.search(r"unknowns (\d+)", log)
        best["unknowns_log"] = int(m.group(1)) if m else 0
        if wall < best["wall"]:
            best["wall"] = wall
            with open(d / f"{job}_phases.csv") as f:
                best["phases"] = [dict(case=case, program=name, **r) for r in csv.DictReader(f)]
        shutil.rmtree(d)

    return after, best


def run_quiet(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, env=ENV_VC, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
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
def linear_case(n, work, residual, rounds):
    d = work / f"cant{n}"
    run_quiet([PY, str(HERE / "make_cantilever.py"), str(n), str(d)], ROOT)
    case = f"cpe4_{n}"
    after, vc = vc_run(case, "vemcontact", d / "vc", d / "vc.inp")
    res, loads = alternate([("vemcontact", [str(VC), "-q", "-o", "vc", "vc.inp"], d, ENV_VC, after)]
                           + ccx_progs(d, case), rounds, case)
    PHASES.extend(vc["phases"])
    vc_wall, vc_rss, vc_walls = res["vemcontact"]
    cx_wall, cx_rss, cx_walls, cx_t, cx_runs = ccx_best(res)
    u, ids = vc["u"], vc["ids"]
    assert np.all(ids == np.arange(1, len(ids) + 1))
    rows = dat_blocks(d / "ccx.dat", "displacements")
    uc = np.zeros_like(u)
    for k, v in rows:
        uc[k - 1] = v[:2]
    umax = np.abs(u).max()
    diff = np.abs(u - uc)
    rel = diff.max() / umax
    big = np.abs(u) >= 1e-4 * umax          # near-zero components excluded (see the report)
    ulps = (diff[big] / half_ulp_e13_6(uc[big])).max()
    tip = (n + 1) * (n // 2 + 1) - 1        # node at (L, L/2), 0-based
    row = dict(n=n, nodes=len(u), elements=n * n, unknowns=2 * len(u),
               free_unknowns=2 * len(u) - 2 * (n + 1), ccx_equations=CCX_EQ.get(case, 0),
               rounds=rounds, vc_solver=vc["solver"],
               vc_wall_s=round(vc_wall, 3), vc_peak_MB=round(vc_rss, 1),
               ccx_wall_s=round(cx_wall, 3), ccx_peak_MB=round(cx_rss, 1),
               time_ratio=round(cx_wall / vc_wall, 2), memory_ratio=round(cx_rss / vc_rss, 2),
               ccx_threads=cx_t,
               vc_walls=" ".join(f"{w:.2f}" for w in vc_walls), ccx_walls=cx_runs,
               load_min=min(loads), load_max=max(loads),
               u_max=f"{umax:.6e}", tip_uy_vc=f"{u[tip, 1]:.7e}", tip_uy_ccx=f"{uc[tip, 1]:.7e}",
               max_abs_diff_rel=f"{rel:.3e}", diff_in_print_halfulps=f"{ulps:.3f}",
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
        run_quiet([str(VC), "-q", "--solver", "cholmod", "-o", "du", "vc_du.inp"], d)   # a check: direct
        with h5py.File(d / "du" / "vc_du.h5") as h:
            du = h["steps/0001/U"][...]
        row["du_rel"] = f"{np.abs(du).max() / umax:.3e}"
    shutil.rmtree(d)
    return row


# ---------------------------------------------------------------- Voronoi cantilever
def voronoi_case(cells, seed, lloyd, work, rounds):
    """The peers' Timoshenko cantilever on `cells` Lloyd-Voronoi cells: vemcontact on the
    polygons (VPE) and on the same nodes as CPE3 triangles, ccx on the triangles."""
    sys.path.insert(0, str(HERE))
    import make_voronoi as mv
    d = work / f"voronoi{cells}"
    t0 = time.perf_counter()
    info = mv.write(d, cells, seed, lloyd)
    t_mesh = time.perf_counter() - t0
    case = f"voronoi_{cells}"
    after_vpe, vpe = vc_run(case, "vemcontact VPE", d / "vpe", d / "vc_vpe.inp")
    after_tri, tri = vc_run(case, "vemcontact CPE3", d / "cpe3", d / "vc_cpe3.inp")
    res, loads = alternate([("vemcontact VPE", [str(VC), "-q", "-o", "vpe", "vc_vpe.inp"], d, ENV_VC, after_vpe)]
                           + ccx_progs(d, case)
                           + [("vemcontact CPE3", [str(VC), "-q", "-o", "cpe3", "vc_cpe3.inp"], d, ENV_VC, after_tri)],
                           rounds, case)
    cx_wall, cx_rss, _, cx_t, cx_runs = ccx_best(res)
    res["ccx"] = (cx_wall, cx_rss, [])
    PHASES.extend(vpe["phases"] + tri["phases"])
    ids, xy = tri["ids"], tri["xy"]
    pos = {int(k): i for i, k in enumerate(ids)}
    uc = np.zeros_like(tri["u"])
    for k, v in dat_blocks(d / "ccx.dat", "displacements"):
        uc[pos[k]] = v[:2]
    tip_vpe, err_vpe = mv.tip_from(vpe["xy"], vpe["u"])
    tip_tri, err_tri = mv.tip_from(xy, tri["u"])
    tip_ccx, err_ccx = mv.tip_from(xy, uc)
    umax = np.abs(tri["u"]).max()
    free = 2 * info["nodes"] - 2 * info["prescribed_nodes"]
    w = {k: v[0] for k, v in res.items()}
    m = {k: v[1] for k, v in res.items()}
    row = dict(cells=info["cells"], seed=seed, lloyd=lloyd, nodes=info["nodes"], triangles=info["triangles"],
               tri_angle_min_deg=info["tri_angle_min_deg"], tri_angle_max_deg=info["tri_angle_max_deg"],
               tri_area_min=info["tri_area_min"], unknowns=2 * info["nodes"], free_unknowns=free,
               ccx_equations=CCX_EQ.get(case, 0), rounds=rounds, mesh_s=round(t_mesh, 1),
               vc_vpe_solver=vpe["solver"], vc_cpe3_solver=tri["solver"],
               vc_vpe_wall_s=round(w["vemcontact VPE"], 3), vc_cpe3_wall_s=round(w["vemcontact CPE3"], 3),
               ccx_wall_s=round(w["ccx"], 3),
               vc_vpe_peak_MB=round(m["vemcontact VPE"], 1), vc_cpe3_peak_MB=round(m["vemcontact CPE3"], 1),
               ccx_peak_MB=round(m["ccx"], 1),
               time_ratio_vpe=round(w["ccx"] / w["vemcontact VPE"], 2),
               memory_ratio_vpe=round(m["ccx"] / m["vemcontact VPE"], 2),
               time_ratio_cpe3=round(w["ccx"] / w["vemcontact CPE3"], 2),
               memory_ratio_cpe3=round(m["ccx"] / m["vemcontact CPE3"], 2),
               vc_vpe_walls=" ".join(f"{x:.2f}" for x in res["vemcontact VPE"][2]),
               vc_cpe3_walls=" ".join(f"{x:.2f}" for x in res["vemcontact CPE3"][2]),
               ccx_threads=cx_t, ccx_walls=cx_runs,
               load_min=min(loads), load_max=max(loads),
               tip_exact=f"{mv.case.TIP_EXACT:.6e}",
               tip_vc_vpe=f"{tip_vpe:.7e}", tip_rel_err_vc_vpe=f"{err_vpe:.3e}",
               tip_vc_cpe3=f"{tip_tri:.7e}", tip_rel_err_vc_cpe3=f"{err_tri:.3e}",
               tip_ccx=f"{tip_ccx:.7e}", tip_rel_err_ccx=f"{err_ccx:.3e}",
               cpe3_vc_ccx_max_diff_rel=f"{np.abs(tri['u'] - uc).max() / umax:.3e}")
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


def hertz_case(name, work, rounds):
    """vemcontact and ccx (small sliding) alternately `rounds` times (minimum of each),
    then ccx once more without SMALL SLIDING (untimed in the ratios) up to 50 000 unknowns."""
    d = work / f"hertz_{name}"
    d.mkdir()
    deck = vc_hertz_deck(name, work)
    vc_walls, vc_rsss, cx_runs = [], [], {t: [] for t in CCX_THREADS}
    small = d / "small"
    run_quiet([PY, str(HERE / "make_hertz.py"), str(deck), str(small)], ROOT)
    for k in range(1, rounds + 1):
        shutil.rmtree(d / "vc", ignore_errors=True)
        w_, m_, _ = timed([str(VC), "-q", "-o", "vc", str(deck)], d, ENV_VC, (f"hertz_{name}", k, "vemcontact"))
        vc_walls.append(w_)
        vc_rsss.append(m_)
        for t in CCX_THREADS:
            w_, m_, o_small = timed(["ccx", "ccx"], small, env_ccx(t), (f"hertz_{name}_small", k, f"ccx t{t}"))
            cx_runs[t].append((w_, m_))
    vc_wall, vc_rss = min(vc_walls), min(vc_rsss)
    cx_t = min(CCX_THREADS, key=lambda t: min(w_ for w_, _ in cx_runs[t]))
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
        if not dd.exists():
            run_quiet([PY, str(HERE / "make_hertz.py"), str(deck), str(dd)] + extra, ROOT)
        nmax = max(int(l.split(",")[0]) for l in (dd / "mesh.inp").read_text().split("*NODE")[1].splitlines()[1:]
                   if l and l[0].isdigit())
        if variant == "small":
            wall = min(w_ for w_, _ in cx_runs[cx_t])
            rss = min(m_ for t in CCX_THREADS for _, m_ in cx_runs[t])
            o = o_small
        else:
            wall, rss, o = timed(["ccx", "ccx"], dd, env_ccx(cx_t), (f"hertz_{name}_{variant}", 1, f"ccx t{cx_t}"))
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
    row = dict(mesh=name, rounds=rounds, ccx_threads=cx_t, unknowns=unknowns, ccx_equations=neq, vc_iterations=iters,
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
            f"vemcontact with its defaults (one BLAS thread, `--solver auto`), ccx with OMP_NUM_THREADS = "
            f"{' and '.join(map(str, CCX_THREADS))}, the faster of them per case")


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


def voronoi_report(w, vor):
    w("## Voronoi cantilever: VEM polygons against CPE3 triangles")
    w("")
    w("The peers' Timoshenko cantilever (bench/peers/case.py; docs/performance.md, \"The")
    w("peers' cantilever\"): x in [0, 8], y in [-2, 2], E = 1e7, nu = 0.3, plane strain,")
    w("thickness 1, the parabolic end shear P = -1000 on x = 8 as consistent nodal loads, the")
    w("exact displacement prescribed on x = 0, on a Lloyd-Voronoi mesh from vctools.mesh")
    w("(uniform random seeds, 20 Lloyd iterations). Its exact tip deflection")
    w("u_y(8, 0) = P L^3/(3 E' I) = -2.9120e-3 gives both codes' errors; the tip is")
    w("interpolated linearly on the side of x = 8 that holds y = 0. Written by")
    w("`bench/calculix/make_voronoi.py` three ways on the same nodes: vemcontact on the")
    w("polygons (VPE, first-order VEM), and the same polygons split into CPE3 triangles, run")
    w("by ccx and, like for like, by vemcontact (FEM constant-strain triangles). Each convex")
    w("cell of k nodes becomes k - 2 triangles by a fan from one of its own vertices, the")
    w("apex whose fan has the largest smallest angle: no node is added, so the triangles have")
    w("the polygons' unknowns. Every triangle has positive area; their smallest angles are")
    w("small where a Voronoi cell has a very short side (any triangulation of the cell has a")
    w("triangle on that side), their largest angles stay those of the cells (below 150 deg).")
    w("A fan from each cell's centroid would add one node per cell (1.5 x the unknowns).")
    w("125 000 cells give the 500 x 500 case's unknowns (500 004 against 502 002); ccx's")
    w("peak memory grows linearly with them on these meshes (docs/performance.md), so")
    w("250 000 cells (1e6 unknowns) would need about 28 GB there, more than this machine has.")
    w("")
    w("| cells (seed) | nodes | triangles | angles of the triangles | unknowns | free (ccx equations) |")
    w("|---:|---:|---:|---:|---:|---:|")
    for r in vor:
        w(f"| {fmt_int(r['cells'])} ({r['seed']}) | {fmt_int(r['nodes'])} | {fmt_int(r['triangles'])} | "
          f"{r['tri_angle_min_deg']}-{r['tri_angle_max_deg']} deg | {fmt_int(r['unknowns'])} | "
          f"{fmt_int(r['free_unknowns'])} ({fmt_int(r['ccx_equations'])}) |")
    w("")
    for r in vor:
        w(f"Run {r.get('run', '?')}, {r['rounds']} alternating rounds (vemcontact VPE, ccx, vemcontact "
          f"CPE3), load {r['load_min']}-{r['load_max']}; {fmt_int(r['cells'])} cells:")
        w("")
        w("| program, mesh | solver | wall (min) | every run | peak RSS | ccx / this: time | memory | tip u_y(8, 0) | relative tip error |")
        w("|---|---|---:|---|---:|---:|---:|---:|---:|")
        w(f"| vemcontact, VPE polygons | {r['vc_vpe_solver'].split(' ')[0]} | {r['vc_vpe_wall_s']:.2f} s | "
          f"{r['vc_vpe_walls']} | {r['vc_vpe_peak_MB']:.0f} MB | **{r['time_ratio_vpe']:.1f}** | "
          f"**{r['memory_ratio_vpe']:.1f}** | {r['tip_vc_vpe']} | {r['tip_rel_err_vc_vpe']} |")
        w(f"| vemcontact, CPE3 triangles | {r['vc_cpe3_solver'].split(' ')[0]} | {r['vc_cpe3_wall_s']:.2f} s | "
          f"{r['vc_cpe3_walls']} | {r['vc_cpe3_peak_MB']:.0f} MB | **{r['time_ratio_cpe3']:.1f}** | "
          f"**{r['memory_ratio_cpe3']:.1f}** | {r['tip_vc_cpe3']} | {r['tip_rel_err_vc_cpe3']} |")
        w(f"| ccx, CPE3 triangles | SPOOLES, {r.get('ccx_threads', '?')} thread(s) | {r['ccx_wall_s']:.2f} s | {r['ccx_walls']} | "
          f"{r['ccx_peak_MB']:.0f} MB | 1 | 1 | {r['tip_ccx']} | {r['tip_rel_err_ccx']} |")
        w("")
        ok_t = r["time_ratio_vpe"] >= 5
        ok_m = r["memory_ratio_vpe"] >= 5
        w(f"Target (at least 5 x faster, at most 1/5 of the memory): vemcontact on the polygons "
          f"against ccx on the triangles: {r['time_ratio_vpe']:.1f} x in time "
          f"({'met' if ok_t else 'NOT met'}), 1/{r['memory_ratio_vpe']:.1f} of the memory "
          f"({'met' if ok_m else 'NOT met'}); like for like on the triangles "
          f"{r['time_ratio_cpe3']:.1f} x and 1/{r['memory_ratio_cpe3']:.1f}. The two codes' "
          f"displacements on the triangles differ by at most {r['cpe3_vc_ccx_max_diff_rel']} of max abs U "
          f"(ccx prints 7 digits): the same element. On the same nodes the VEM polygons' tip error is "
          f"{float(r['tip_rel_err_vc_cpe3']) / float(r['tip_rel_err_vc_vpe']):.1f} x smaller than the "
          f"constant-strain triangles'.")
        w("")


def report(lin, hz, vor, mach, when, elapsed, path):
    L = []
    w = L.append
    w("# vemcontact against CalculiX on the same decks")
    w("")
    w("Issue 6, part 4, and issue 15. Generated by `bash bench/calculix/run.sh` (one command:")
    w("installs the Debian packages `calculix-ccx` and `time`, builds vemcontact in Release if")
    w("needed, runs every case and rewrites this page; `compare.py --help` for a subset). Raw")
    w("numbers: `bench/results/calculix_linear.csv`, `calculix_voronoi.csv`,")
    w("`calculix_hertz.csv`, every timed run with its load in `calculix_runs.csv`, and")
    w("vemcontact's phases (its `JOB_phases.csv`) of its fastest run of each cantilever case")
    w("in `calculix_phases.csv`; plot: `bench/calculix/figures/calculix_scaling.png`.")
    w("Timings are benchmark output, not tests: the machine is shared and noisy, so the")
    w("ratios are taken within one run, each table names its run (UTC, commit) and the load.")
    w("")
    w(f"**Machine:** {mach}.")
    w("")
    w("Wall time is that of the whole process (read the deck, assemble, factorize or set up")
    w("and solve, write the results), peak memory its maximum resident set size")
    w("(`/usr/bin/time -f %M`); the load is the 1-minute load average before and after each")
    w("run. vemcontact writes VTU + HDF5 (+ contact CSV), ccx its `.dat` print of the")
    w("requested nodes. Threads: each program with its own documented setting, vemcontact")
    w("with its defaults (one BLAS thread; `--solver auto`, whose choice the tables give from")
    w("the HDF5 root attribute `solver`: CHOLMOD below 200 000 unknowns, CG + GAMG above),")
    w("ccx with `OMP_NUM_THREADS` = 1 (its default: one thread unless `OMP_NUM_THREADS` or")
    w(f"`CCX_NPROC_EQUATION_SOLVER` says more) and = {NPROC}, the number of cores, both in every round; the")
    w("faster setting counts in the ratios (its thread count in brackets), and the tables")
    w("list every run. The programs run alternately, `--rounds` times; the tables give the")
    w("minimum of each.")
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
    runs = {}
    for r in lin:
        runs.setdefault(r.get('run', '?'), []).append(r)
    if len(runs) == 1:
        w(f"Run {lin[0].get('run', '?')}, {lin[0].get('rounds', 1)} alternating rounds, load "
          f"{min(r.get('load_min', 0) for r in lin)}-{max(r.get('load_max', 0) for r in lin)}.")
    else:
        # rows kept from earlier runs (a run of a subset of the sizes replaces only its own)
        parts = [f"{', '.join(str(r['n']) + ' x ' + str(r['n']) for r in rows)}: run {run}, "
                 f"{rows[0].get('rounds', 1)} alternating rounds, load "
                 f"{min(r.get('load_min', 0) for r in rows)}-{max(r.get('load_max', 0) for r in rows)}"
                 for run, rows in runs.items()]
        w("Rows of more than one run: " + "; ".join(parts) + ".")
    w("")
    w("| n x n | unknowns | ccx equations | vemcontact (solver) | ccx (threads) | time ratio | vemcontact peak | ccx peak | memory ratio | load |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in lin:
        w(f"| {r['n']} x {r['n']} | {fmt_int(r['unknowns'])} | {fmt_int(r['ccx_equations'])} | "
          f"{r['vc_wall_s']:.2f} s ({r.get('vc_solver', '?').split(' ')[0]}) | "
          f"{r['ccx_wall_s']:.2f} s ({r.get('ccx_threads', '?')}) | **{r['time_ratio']:.1f}** | {r['vc_peak_MB']:.0f} MB | {r['ccx_peak_MB']:.0f} MB | "
          f"**{r['memory_ratio']:.1f}** | {r.get('load_min', '?')}-{r.get('load_max', '?')} |")
    big = lin[-1]
    ok_t = big["time_ratio"] >= 5
    ok_m = big["memory_ratio"] >= 5
    w("")
    w(f"Target at equal unknowns: at least 5 times faster and at most one fifth of the memory. At")
    w(f"{big['n']} x {big['n']} ({fmt_int(big['unknowns'])} unknowns): ccx / vemcontact = "
      f"{big['time_ratio']:.1f} in time ({'met' if ok_t else 'NOT met'}) and {big['memory_ratio']:.1f} in "
      f"memory ({'met' if ok_m else 'NOT met'}). Every run's wall time: vemcontact "
      f"{big.get('vc_walls', '?')} s; ccx with {big.get('ccx_walls', '?')} s.")
    w("")
    w("### Agreement of the displacements")
    w("")
    w("| n x n | u_y(10, 5) vemcontact | u_y(10, 5) ccx | max abs U | max abs(U_vc - U_ccx) / max abs U | same, in half-units of ccx's last printed digit | residual of U_vc in ccx | K^-1 residual / max abs U |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in lin:
        w(f"| {r['n']} x {r['n']} | {r.get('tip_uy_vc', '-')} | {r.get('tip_uy_ccx', '-')} | {r['u_max']} | "
          f"{r['max_abs_diff_rel']} | {float(r['diff_in_print_halfulps']):.3f} | {r['residual_rel'] or '-'} | {r['du_rel'] or '-'} |")
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
    w("Above 200 000 unknowns vemcontact's default is CG + GAMG, so its displacements carry")
    w("the iteration's error as well (true relative residual 1e-10, docs/performance.md); the")
    w("K^-1 r check is solved with CHOLMOD (`--solver cholmod`), since it measures the")
    w("residual, not the solver. The square has no closed-form solution; the tip deflection")
    w("u_y(10, 5) of the two codes is given for reference.")
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
    if vor:
        voronoi_report(w, vor)
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
    w(f"Run {hz[0].get('run', '?')}: vemcontact and ccx alternately, {hz[0].get('rounds', 1)} rounds, the minimum of each,")
    w("ccx with the faster of its thread settings (`ccx_threads` in the CSV); the run without")
    w("SMALL SLIDING once.")
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
    # the section on CalculiX's own test decks is written by hand (tests, not timings)
    w((pathlib.Path(__file__).resolve().parent / "test_decks_section.md").read_text().rstrip("\n"))
    w("")
    w("## Reproduce")
    w("")
    w("    bash bench/calculix/run.sh                   # everything, as above")
    w("    bash bench/calculix/run.sh --sizes 50 100 --voronoi 10000 --hertz 389 600   # a subset")
    w("    bash bench/calculix/run.sh --sizes --voronoi --hertz   # the page again from the CSVs")
    w("")
    w("The decks can be written on their own: `python bench/calculix/make_cantilever.py N DIR`")
    w("(`DIR/vc.inp`, `DIR/ccx.inp`, shared `DIR/mesh.inp`; run ccx as `ccx ccx` inside DIR)")
    w("and `python bench/calculix/make_hertz.py inputs/hertz_389_fem.inp DIR`;")
    w("`python bench/calculix/make_voronoi.py DIR --cells 125000 --seed 1` writes the Voronoi")
    w("decks (`DIR/vc_vpe.inp`, `DIR/vc_cpe3.inp`, `DIR/ccx.inp`).")
    path.write_text("\n".join(L) + "\n")


def read_csv(path):
    """Rows of an earlier run's CSV, numbers as numbers (e-notation fields stay text)."""
    rows = []
    if not path.exists():
        return rows
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if v and "e" not in v.lower():
                    try:
                        r[k] = int(v)
                    except ValueError:
                        try:
                            r[k] = float(v)
                        except ValueError:
                            pass
            rows.append(r)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="*", default=[50, 100, 200, 500])
    ap.add_argument("--voronoi", type=int, nargs="*", default=[125000],
                    help="Lloyd-Voronoi cells of the Voronoi cantilever (none: keep the last run's rows)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the Voronoi mesh's random points")
    ap.add_argument("--lloyd", type=int, default=20, help="Lloyd iterations of the Voronoi mesh")
    ap.add_argument("--hertz", nargs="*", default=["389", "600", "1155", "h5k", "h20k", "h100k"])
    ap.add_argument("--rounds", type=int, default=2,
                    help="alternating runs of each program on every case; the tables give the minimum")
    ap.add_argument("--ccx-threads", type=int, nargs="+", default=CCX_THREADS,
                    help="OMP_NUM_THREADS settings of ccx, each run every round; the fastest counts")
    ap.add_argument("--residual-max", type=int, default=500,
                    help="largest n for the residual check (one more untimed ccx run each)")
    ap.add_argument("--no-report", action="store_true", help="write the CSVs only")
    a = ap.parse_args()
    CCX_THREADS[:] = a.ccx_threads
    t0 = datetime.datetime.now(datetime.timezone.utc)
    stamp = f"{t0:%Y-%m-%d %H:%M} UTC, {commit()}"
    work = pathlib.Path(tempfile.mkdtemp(prefix="vc_ccx_"))
    lin, hz, vor = [], [], []
    try:
        for n in a.sizes:
            r = linear_case(n, work, n <= a.residual_max, a.rounds)
            print(f"cantilever {n}x{n}: vc ({r['vc_solver']}) {r['vc_walls']} s {r['vc_peak_MB']} MB, "
                  f"ccx {r['ccx_walls']} s {r['ccx_peak_MB']} MB, ratios {r['time_ratio']} / {r['memory_ratio']}, "
                  f"load {r['load_min']}-{r['load_max']}, diff {r['max_abs_diff_rel']} "
                  f"({r['diff_in_print_halfulps']} half-ulps), residual {r['residual_rel']}, du {r['du_rel']}", flush=True)
            lin.append(r)
        for cells in a.voronoi:
            r = voronoi_case(cells, a.seed, a.lloyd, work, a.rounds)
            print(f"voronoi {cells}: " + ", ".join(f"{k} {v}" for k, v in r.items()), flush=True)
            vor.append(r)
        for name in a.hertz:
            r = hertz_case(name, work, a.rounds)
            print(f"hertz {name}: vc {r['vc_wall_s']} s {r['vc_peak_MB']} MB, ccx {r['ccx_wall_s']} s "
                  f"{r['ccx_peak_MB']} MB, ratios {r['time_ratio']} / {r['memory_ratio']}, peaks "
                  f"{r['peak_vc']} / {r['peak_ccx']} (finite sliding {r['peak_ccx_finite_sliding']})", flush=True)
            hz.append(r)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    mach = machine()
    for r in lin + hz + vor:
        r["run"] = stamp
        r["machine"] = mach
    res = ROOT / "bench" / "results"
    res.mkdir(parents=True, exist_ok=True)
    for name, rows in (("calculix_linear.csv", lin), ("calculix_hertz.csv", hz), ("calculix_voronoi.csv", vor)):
        if rows:
            write_csv(res / name, rows)
    # every run and phase table: this run's rows are added to those of the earlier runs
    # (each row names its run), so that the runs the docs quote stay on record
    for name, new in (("calculix_runs.csv", RUNS), ("calculix_phases.csv", PHASES)):
        if new:
            write_csv(res / name, read_csv(res / name) + [dict(run=stamp, **r) for r in new])
    if a.no_report:
        return
    lin = lin or read_csv(res / "calculix_linear.csv")
    hz = hz or read_csv(res / "calculix_hertz.csv")
    vor = vor or read_csv(res / "calculix_voronoi.csv")
    if lin and hz:
        plot(lin, hz, HERE / "figures" / "calculix_scaling.png")
        elapsed = (datetime.datetime.now(datetime.timezone.utc) - t0).total_seconds()
        report(lin, hz, vor, mach, stamp, elapsed, ROOT / "docs" / "calculix-comparison.md")
    print("machine:", mach)


if __name__ == "__main__":
    main()
