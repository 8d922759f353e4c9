"""PETSc's own options given by --petsc-options reach PETSc before it starts, under an
MPI launcher too: with `-log_view :FILE` every process must end normally (exit status
0) and FILE must hold PETSc's performance summary.  Before the options were read
ahead of PetscInitialize, -log_view set afterwards left PETSc's logging off and the
launcher reported the job as ended improperly (exit status 1).

    usage: mpi_petsc_options.py "LAUNCHER" EXE OUTDIR DECK
"""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys


def main(argv: list[str]) -> int:
    launcher, exe, outdir, deck = shlex.split(argv[1]), argv[2], argv[3], argv[4]
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    log = os.path.join(outdir, "petsc_log.txt")
    cmd = [*launcher, exe, "-q", "--solver", "gamg", "--petsc-options", f"-log_view :{log}",
           "-o", os.path.join(outdir, "run"), deck]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=300, check=False)
    ok = True
    if res.returncode != 0:
        print(f"FAIL exit status {res.returncode}\n{res.stdout}\n{res.stderr}")
        ok = False
    if not os.path.isfile(log) or os.path.getsize(log) == 0:
        print(f"FAIL no PETSc log written to {log}")
        ok = False
    if ok:
        print(f"ok: exit status 0, PETSc log of {os.path.getsize(log)} bytes")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
