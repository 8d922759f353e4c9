"""vc-paper: reproduce the tables and figures of Sun et al. (2022).

  python -m vctools.paper [--out DIR] [--work DIR] [--exe PATH] [--quick] [-j N]

Runs the paper's four examples with vemcontact in a work folder (default
out/paper), draws the figures into DIR/figures and writes DIR/paper-reproduction.md
with each table and figure regenerated, the paper's numbers beside ours and, where
they differ, by how much and why.  DIR is the work folder unless --out says
otherwise, so that a run changes no tracked file; --out docs updates the
repository's docs/paper-reproduction.md and docs/figures/.



  example 1  two-element cantilever, 2d/b = 0, 0.5, ..., 4, VEM and FEM, first
             and second order (k = 2 VEM, 8-node quad) (Fig. 4)
  example 2  Hertz contact, 389/600/1155 elements, VEM and FEM (Figs. 6-8), and
             the 600-element VEM mesh with K = 1e5, 1e4, 1e3 (Table 1); each mesh
             also with HARD contact, NODE TO SURFACE and (VEM) SURFACE TO SURFACE
  example 3  horizontal interface, quad/tri/Voronoi 50-500 meshes (Figs. 10, 11),
             and node by node NODE TO SURFACE against SURFACE TO SURFACE (HARD),
             in the decks as they are and with the top and bottom on rollers
             (the contact patch test: exact uniform pressure)
  example 4  dam on a jointed foundation (Figs. 13, 14), NODE TO SURFACE with
             the penalty and SURFACE TO SURFACE with HARD along the joint

Variants of the decks in inputs/ are written to the work folder's decks/ by text
substitution (TYPE=SURFACE TO SURFACE, PRESSURE-OVERCLOSURE=HARD, rollers).

--quick runs a subset (2d/b = 0 and 2, the 389-element Hertz meshes, Table 1 on
the 389-element mesh, two interface meshes, no dam) for tests, with the same
variants.  Exit status:
0 done, 1 a run failed or bad input (the document is still written, naming the
failed runs).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import os
import sys
import time

from vctools.cli import entry
from vctools.plot.results import ResultError
from .document import write_document
from .reproduce import ROOT, make_plan, run_job, write_jobs


@entry("vc-paper")
def main(argv=None) -> int:
    doc = __doc__.split("\n\n")
    p = argparse.ArgumentParser(prog="vc-paper", description=doc[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog="\n\n".join(doc[1:]))
    p.add_argument("--out", default=None,
                   help="folder of paper-reproduction.md and figures/ (default: the work folder; "
                        "--out docs updates the repository's docs/paper-reproduction.md)")
    p.add_argument("--work", default=None, help="folder for the decks and runs (default: out/paper, or out/paper-quick)")
    p.add_argument("--exe", default=None, help="vemcontact executable (default: $VEMCONTACT_EXE, else build/vemcontact)")
    p.add_argument("--quick", action="store_true", help="a small subset, for tests")
    p.add_argument("-j", "--jobs", type=int, default=2, help="runs at the same time (default 2)")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    try:
        exe = a.exe or os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build", "vemcontact")
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            raise ResultError(f"{exe}: no vemcontact executable (build it: bash scripts/build.sh Release, or give --exe)")
        exe = os.path.abspath(exe)
        work = os.path.abspath(a.work or os.path.join(ROOT, "out", "paper-quick" if a.quick else "paper"))
        out = os.path.abspath(a.out or work)
        figs = os.path.join(out, "figures")
        os.makedirs(figs, exist_ok=True)
        plan = make_plan(a.quick)
        write_jobs(plan, work)
        with cf.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            # the largest runs first so that two workers finish together
            order = sorted(plan.jobs.values(), key=lambda j: ("dam" not in j.key, "1155" not in j.key, j.key))
            list(pool.map(lambda j: run_job(exe, j), order))
        t_runs = time.perf_counter() - t0
        failed = [j for j in plan.jobs.values() if not j.ok]
        for j in failed:
            print(f"vc-paper: warning: {j.key} failed (status {j.rc}): {j.message}", file=sys.stderr)
        path = write_document(plan, work, out, figs, t_runs)
    except ResultError as exc:
        print(f"vc-paper: error: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"vc-paper: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 1
    print(f"{path}  ({len(plan.jobs)} runs, {len(failed)} failed, {time.perf_counter() - t0:.1f} s)")
    return 1 if failed else 0
