"""Run decks with CHOLMOD and with the PETSc solvers and compare the displacements.

    usage: compare_solvers.py [--launcher "mpiexec -n 2"] [--options "--ordering metis"]
                              [--rebuilds JOB[,JOB ...]] EXE OUTDIR DECK [DECK ...]

Every deck runs with --solver cholmod (the reference: a backward-stable direct
solve) and with gamg, hypre and mumps; the displacements U of every step (the
HDF5 results) must agree within a tolerance derived from the stopping rules:

- CG (gamg, hypre) stops at |b - A x| <= rtol |b| with rtol = 1e-10
  (src/solver/petsc.f90), so |x - x*| / |x*| <= cond(A) rtol.  cond(A) is computed
  here from the first step's matrix (--write-matrix, 2-norm condition number of the
  constrained stiffness by scipy's eigensolver), times 10 for the CHOLMOD answer's
  own round-off and the spread of conditioning between steps.
- MUMPS, backward stable like CHOLMOD: cond(A) eps, times 100 (the growth of the
  round-off with the size of these small matrices).
- With contact, both runs stop the contact iteration once its relative residual is
  below the deck's tolerance (1e-10 by default, *CONTACT CONTROLS); the
  difference of two such answers is bounded by cond(A) times the tolerance too,
  so the same bound holds with rtol replaced by max(rtol, 1e-10).

With --launcher the PETSc solvers run under that MPI launcher (the mesh partitioned,
each process assembling its own elements, the matrix and the solve distributed) and
must give the serial CHOLMOD answer within the same tolerances, from one set of result
files (no file of the other processes: nothing named JOB.rank*, and the same files as
the serial CHOLMOD run but its --write-matrix JOB.mtx); the HDF5 root
attributes `processes` and `elements_per_process` must show the partition: more than
one process, the elements per process adding up to the element count, and every
process with a fair share (at least a quarter of an even one; METIS balances the
nodes to within 3 %, and the elements follow them).  Serial runs must say one process
with every element.  --options are added to the PETSc solvers' command lines.

--rebuilds names decks (by job name) whose contact iteration must rebuild the matrix
pattern (the contact pairs move past the candidate pairs the pattern holds): every run
of them, serial CHOLMOD and each PETSc solver (under the launcher: the partition kept,
each process assembling its elements into the new pattern, the solver analysing it
again), must record at least one rebuild in the HDF5 iteration records
(/steps/NNNN/contact/iterations/rebuilt), and its answer is compared as above.

Exit status 0 when every comparison holds, 1 otherwise; each comparison is printed.
"""
from __future__ import annotations

import os
import subprocess
import sys

import h5py
import numpy as np
import scipy.io
import scipy.sparse
import scipy.sparse.linalg

RTOL = 1.0e-10            # CG's stopping rule (src/solver/petsc.f90 default_rtol)
EPS = np.finfo(float).eps


def run(exe, deck, out, solver, extra=(), launcher=(), rebuild=False):
    cmd = [*launcher, exe, "-q", "--solver", solver, "-o", out, *extra, deck]
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        print(f"FAIL {os.path.basename(deck)} {solver}: exit {res.returncode}\n{res.stderr}")
        return None
    job = os.path.splitext(os.path.basename(deck))[0]
    left = [f for f in os.listdir(out) if f.startswith(job + ".rank")]
    if left:
        print(f"FAIL {os.path.basename(deck)} {solver}: files of other processes left: {left}")
        return None
    with h5py.File(os.path.join(out, job + ".h5"), "r") as f:
        if not partition_ok(f, os.path.basename(deck), solver, bool(launcher)):
            return None
        if rebuild and not rebuilt(f, os.path.basename(deck), solver):
            return None
        return ({k: f["steps"][k]["U"][()] for k in f["steps"]}, os.path.join(out, job + ".mtx"),
                sorted(f for f in os.listdir(out) if not f.endswith(".mtx")))


def partition_ok(f, deck, solver, launched):
    """The partition the results record: several processes with fair shares under the launcher."""
    nelem = f["mesh/element_type"].shape[0]
    nproc = int(f.attrs["processes"])
    per = np.asarray(f.attrs["elements_per_process"]).ravel()
    good = len(per) == nproc and per.sum() == nelem
    if launched:
        good &= nproc > 1 and per.min() >= 0.25 * nelem / nproc
    else:
        good &= nproc == 1
    print(f"{'ok  ' if good else 'FAIL'} {deck} {solver}: {nproc} processes, elements per process "
          f"{per.tolist()} of {nelem}")
    return bool(good)


def rebuilt(f, deck, solver):
    """At least one contact iteration of the run rebuilt the matrix pattern."""
    per_step = [int(np.sum(f["steps"][k]["contact/iterations"].get("rebuilt", [-1])))
                for k in sorted(f["steps"]) if "contact/iterations" in f["steps"][k]]
    # -1: the step's records have no `rebuilt` (written by an older vemcontact)
    good = sum(per_step) > 0 and min(per_step) >= 0
    print(f"{'ok  ' if good else 'FAIL'} {deck} {solver}: matrix pattern rebuilds per step {per_step}")
    return good


def condition(mtx):
    """2-norm condition number of the symmetric matrix in the Matrix Market file."""
    a = scipy.io.mmread(mtx).tocsc()
    if a.shape[0] <= 2000:
        w = np.linalg.eigvalsh(a.toarray())
        return w[-1] / w[0]
    lmax = scipy.sparse.linalg.eigsh(a, k=1, which="LA", return_eigenvectors=False)[0]
    lmin = scipy.sparse.linalg.eigsh(a, k=1, sigma=0, which="LM", return_eigenvectors=False)[0]
    return lmax / lmin


def main(argv):
    launcher, options, rebuilds = [], [], []
    while len(argv) > 2 and argv[1] in ("--launcher", "--options", "--rebuilds"):
        if argv[1] == "--launcher":
            launcher = argv[2].split()
        elif argv[1] == "--rebuilds":
            rebuilds = argv[2].split(",")
        else:
            options = argv[2].split()
        argv = argv[:1] + argv[3:]
    exe, outdir, decks = argv[1], argv[2], argv[3:]
    ok = True
    for deck in decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        ref = run(exe, deck, os.path.join(outdir, name, "cholmod"), "cholmod", ["--write-matrix"],
                  rebuild=name in rebuilds)
        if ref is None:
            ok = False
            continue
        uref, mtx, files_ref = ref
        kappa = condition(mtx)
        for solver in ("gamg", "hypre", "mumps"):
            got = run(exe, deck, os.path.join(outdir, name, solver), solver, options, launcher=launcher,
                      rebuild=name in rebuilds)
            if got is None:
                ok = False
                continue
            u, _, files = got
            if launcher:
                same = files == files_ref
                ok &= same
                print(f"{'ok  ' if same else 'FAIL'} {name} {solver}: the files of the serial run"
                      + ("" if same else f": {files} against {files_ref}"))
            tol = 100 * kappa * EPS if solver == "mumps" else 10 * kappa * RTOL
            for step in uref:
                scale = np.max(np.abs(uref[step]))
                diff = np.max(np.abs(u[step] - uref[step])) / scale if scale > 0 else 0.0
                good = diff <= tol
                ok &= bool(good)
                print(f"{'ok  ' if good else 'FAIL'} {name} step {step} {solver}: |u - u_cholmod| / |u_cholmod| = "
                      f"{diff:.2e} <= {tol:.2e} (cond {kappa:.2e})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
