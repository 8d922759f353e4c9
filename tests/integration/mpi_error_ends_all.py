"""An error met by one MPI process alone ends every process of the run.

    usage: mpi_error_ends_all.py LAUNCHER EXE OUTDIR DECK

Only rank 0 takes the job's lock (JOB.lock, flock): with the lock held by this
script, rank 0 stops with exit status 2 ("another vemcontact run is writing these
results") while the other ranks, which do not touch the lock, go on to the
solver's collective operations.  Unless rank 0 ends them all (MPI_Abort), they wait
for it forever.  Asserted: the launcher returns within the time limit with status 2,
the message names the lock, and the results folder holds no result file.
"""
from __future__ import annotations

import fcntl
import os
import shlex
import subprocess
import sys

# a run of this small deck takes under a second; 60 s only fails on a hang
LIMIT_S = 60.0


def main() -> int:
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
