"""An error met by one MPI process alone ends every process of the run, and an error
of the model that every process meets is reported once.

    usage: mpi_error_ends_all.py LAUNCHER EXE OUTDIR DECK
           mpi_error_ends_all.py --model-error LAUNCHER EXE OUTDIR FLOATING_DECK
           mpi_error_ends_all.py --solver-error LAUNCHER EXE OUTDIR DECK

Only rank 0 takes the job's lock (JOB.lock, flock): with the lock held by this
script, rank 0 stops with exit status 2 ("another vemcontact run is writing these
results") while the other ranks, which do not touch the lock, go on to the
solver's collective operations.  Unless rank 0 ends them all (MPI_Abort), they wait
for it forever.  Asserted: the launcher returns within the time limit with status 2,
the message names the lock, and the results folder holds no result file.

With --model-error the deck has a floating part (exit status 3), an error every
process meets during the analysis, after the collective phase: asserted are the
status, the launcher's return within the time limit, and the message on stderr
exactly once, from rank 0 (no "MPI rank N:" prefix).

With --solver-error CG + GAMG is allowed 2 iterations (`-ksp_max_it 2`), too few for
any deck: every process meets the same failure (PETSc's convergence test is
collective), so the same holds with exit status 4 (solver failure).
"""
from __future__ import annotations

import fcntl
import os
import shlex
import subprocess
import sys

# a run of this small deck takes under a second; 60 s only fails on a hang
LIMIT_S = 60.0


def error_once(launcher: str, exe: str, outdir: str, deck: str, extra: list[str], status: int,
               message: str) -> int:
    """The run ends with `status` and `message` on stderr exactly once, from rank 0."""
    cmd = shlex.split(launcher) + [exe, "-q", "--solver", "gamg", *extra, "-o", outdir, deck]
    try:
        run = subprocess.run(cmd, check=False, capture_output=True, text=True, timeout=LIMIT_S)
    except subprocess.TimeoutExpired:
        print(f"FAIL: the processes still ran after {LIMIT_S} s")
        return 1
    ok = run.returncode == status
    if not ok:
        print(f"FAIL: exit status {run.returncode}, expected {status}\n{run.stderr}")
    count = run.stderr.count(message)
    if count != 1 or "MPI rank" in run.stderr:
        print(f"FAIL: the message {count} times (expected once, from rank 0):\n{run.stderr}")
        ok = False
    if ok:
        print(f"ok: exit status {status}, the message once, from rank 0")
    return 0 if ok else 1


def main() -> int:
    if sys.argv[1] == "--model-error":
        # a floating part: exit status 3 (model not solvable)
        return error_once(*sys.argv[2:6], [], 3, "the model is not held")
    if sys.argv[1] == "--solver-error":
        # CG stopped after 2 iterations: exit status 4 (solver failure)
        return error_once(*sys.argv[2:6], ["--petsc-options", "-ksp_max_it 2"], 4, "did not converge")
    launcher, exe, outdir, deck = sys.argv[1:5]
    os.makedirs(outdir, exist_ok=True)
    job = os.path.splitext(os.path.basename(deck))[0]
    for name in os.listdir(outdir):
        os.remove(os.path.join(outdir, name))
    with open(os.path.join(outdir, job + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        cmd = shlex.split(launcher) + [exe, "--solver", "gamg", "-o", outdir, deck]
        try:
            run = subprocess.run(cmd, check=False, capture_output=True, text=True, timeout=LIMIT_S)
        except subprocess.TimeoutExpired:
            print(f"FAIL: the processes still ran after {LIMIT_S} s (an error on rank 0 left the others waiting)")
            return 1
    ok = True
    if run.returncode != 2:
        print(f"FAIL: exit status {run.returncode}, expected 2 (file error)\n{run.stderr}")
        ok = False
    if "another vemcontact run is writing these results" not in run.stderr:
        print(f"FAIL: the lock's message is missing from stderr:\n{run.stderr}")
        ok = False
    left = sorted(n for n in os.listdir(outdir) if n != job + ".lock")
    if left:
        print(f"FAIL: files written although the job was locked: {left}")
        ok = False
    if ok:
        print("ok: exit status 2 from all processes, no result files")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
