"""SIGTERM and SIGINT at random points of a 20-step run (fixed seed) keep what
finished (docs/output-format.md, "Stopping a run"):

    usage: interrupt_run.py EXE OUTDIR [--mpi LAUNCHER] [--trials N]

Serial: the 20-step dam (contact: the run also stops between contact iterations).
With --mpi: a 20-step self-weight block on `LAUNCHER` (e.g. "mpiexec -n 2") with
--solver gamg; the signal goes to every process of the run (the launcher's
children), as a batch system's cancel sends it (Open MPI's mpirun, signalled
itself, ends the processes its own way: docs/output-format.md).

Each trial sends SIGTERM or SIGINT (alternately) after a random fraction of a full
run's time and asserts, reading the files as data:
- exit status 128 + the signal (143, 130), within the time limit;
- JOB.h5 exists with root attributes complete = 0 and interrupted = the signal;
  its steps are 1..k without a gap, every dataset of every step reads, and each
  step's U equals the full run's (same executable, same deck: to round-off of a
  possibly different summation order under MPI, 1e-9 relative);
- the .pvd lists exactly steps 1..k and every file it names exists;
- the log has the note of the interruption (its presence only).
At least half of the trials must land inside the run (a signal after the end
interrupts nothing and is not counted).
"""
from __future__ import annotations

import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# a full run takes about 10 s (Debug, serial dam); a hang is far beyond
LIMIT_S = 120.0
NSTEP = 20


def dam_deck(path: str) -> None:
    """The dam of inputs/dam_joint.inp: self-weight, then 19 reservoir levels."""
    lines = Path(ROOT, "inputs", "dam_joint.inp").read_text().split("\n")
    start = lines.index("*HEADING")
    end = next(i for i, l in enumerate(lines) if l.startswith("*STEP"))
    mesh = os.path.join(ROOT, "inputs", "meshes", "ex4_dam.inp")
    text = "\n".join(lines[start:end]).replace("INPUT=meshes/ex4_dam.inp", "INPUT=" + mesh) + "\n"
    text += ("*STEP, NAME=SELF-WEIGHT\n*GEOSTATIC\n*DLOAD\nFOUNDATION, GRAV, 9.81, 0., -1.\n"
             "DAM, GRAV, 9.81, 0., -1.\n*END STEP\n")
    for k in range(2, NSTEP + 1):
        h = 10.0 + 5.0 * (k - 1) / (NSTEP - 1)
        text += (f"*STEP, NAME=LEVEL-{k}\n*STATIC\n*DSLOAD\nUPSTREAM, HP, {9810.0 * (h - 10.0):.6g}, "
                 f"{h:.6g}, 10.\n*END STEP\n")
    with open(path, "w") as f:
        f.write(text)


def block_deck(path: str) -> None:
    """inputs/block_selfweight.inp with its gravity scaled by 1..20 in 20 steps."""
    text = Path(ROOT, "inputs", "block_selfweight.inp").read_text()
    head = text[:text.index("*STEP")]
    for k in range(1, NSTEP + 1):
        head += f"*STEP\n*STATIC\n*DLOAD\nALL, GRAV, {9.81 * k:.6g}, 0., -1.\n*END STEP\n"
    with open(path, "w") as f:
        f.write(head)


def h5_steps(path: str) -> tuple[dict, dict]:
    """Root attributes and {step number: U} of a results file, every dataset read."""
    with h5py.File(path, "r") as f:
        attrs = {k: np.asarray(v).reshape(-1)[0] for k, v in f.attrs.items() if k in ("complete", "interrupted")}
        steps = {}
        for key in sorted(f["steps"]):
            g = f["steps"][key]
            g.visititems(lambda _n, o: o[...] if isinstance(o, h5py.Dataset) else None)
            steps[int(key)] = g["U"][...]
        return attrs, steps


def pvd_steps(path: str) -> list[int]:
    root = ET.parse(path).getroot()
    steps = []
    for ds in root.iter("DataSet"):
        assert os.path.exists(os.path.join(os.path.dirname(path), ds.get("file"))), ds.get("file")
        if ds.get("part", "0") == "0":
            steps.append(round(float(ds.get("timestep"))))
    return steps


def children(pid: int) -> list[int]:
    """Process ids whose parent is `pid` (Linux /proc)."""
    found = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            found.append(int(name))
    return found


def main() -> int:
    args = sys.argv[1:]
    launcher = []
    trials = 4
    if "--mpi" in args:
        i = args.index("--mpi")
        launcher = shlex.split(args[i + 1])
        del args[i:i + 2]
    if "--trials" in args:
        i = args.index("--trials")
        trials = int(args[i + 1])
        del args[i:i + 2]
    exe, outdir = args
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    deck = os.path.join(outdir, "run20.inp")
    extra = []
    if launcher:
        block_deck(deck)
        extra = ["--solver", "gamg"]
    else:
        dam_deck(deck)
    job = "run20"

    def command(out: str) -> list[str]:
        return launcher + [exe, "-q", *extra, "-o", out, deck]

    t0 = time.perf_counter()
    ref = subprocess.run(command(os.path.join(outdir, "full")), capture_output=True, text=True,
                         timeout=LIMIT_S, check=False)
    duration = time.perf_counter() - t0
    if ref.returncode != 0:
        print(f"FAIL: the full run ended with {ref.returncode}\n{ref.stderr}")
        return 1
    ref_attrs, ref_steps = h5_steps(os.path.join(outdir, "full", job + ".h5"))
    assert ref_attrs["complete"] == 1 and sorted(ref_steps) == list(range(1, NSTEP + 1))

    rng = random.Random(25)
    failures = 0
    landed = 0
    for trial in range(trials):
        sig = (signal.SIGTERM, signal.SIGINT)[trial % 2]
        out = os.path.join(outdir, f"trial{trial}")
        p = subprocess.Popen(command(out), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(rng.uniform(0.1, 0.6) * duration)
        if launcher:
            for pid in children(p.pid):
                os.kill(pid, sig)
        else:
            p.send_signal(sig)
        try:
            _, err = p.communicate(timeout=LIMIT_S)
        except subprocess.TimeoutExpired:
            p.kill()
            print(f"FAIL: trial {trial}: still running {LIMIT_S} s after {sig.name}")
            return 1
        if p.returncode == 0:
            print(f"trial {trial}: {sig.name} came after the end of the run")
            continue
        landed += 1
        problems = []
        if p.returncode != 128 + sig:
            problems.append(f"exit status {p.returncode}, expected {128 + sig}: {err}")
        h5 = os.path.join(out, job + ".h5")
        if not os.path.exists(h5):
            # stopped before the results files were opened (an MPI start can take longer
            # than the serial reference run): nothing finished, so nothing is kept
            with open(os.path.join(out, job + ".log")) as f:
                if "no step was complete" not in f.read():
                    problems.append("no JOB.h5, and the log does not say that no step was complete")
            print(f"trial {trial}: {sig.name}, exit {p.returncode}, stopped before the results files")
            for msg in problems:
                print(f"FAIL: trial {trial}: {msg}")
            failures += bool(problems)
            continue
        attrs, steps = h5_steps(h5)
        if attrs.get("complete") != 0 or attrs.get("interrupted") != sig:
            problems.append(f"root attributes {attrs}, expected complete 0, interrupted {int(sig)}")
        k = len(steps)
        if sorted(steps) != list(range(1, k + 1)):
            problems.append(f"steps {sorted(steps)} are not 1..{k}")
        for n, u in steps.items():
            scale = np.abs(ref_steps[n]).max()
            if np.abs(u - ref_steps[n]).max() > 1e-9 * scale:
                problems.append(f"step {n}: U differs from the full run's")
        if k > 0 and pvd_steps(os.path.join(out, job + ".pvd")) != list(range(1, k + 1)):
            problems.append(f"the .pvd does not list steps 1..{k}")
        with open(os.path.join(out, job + ".log")) as f:
            if f"interrupted by {sig.name}" not in f.read():
                problems.append("no note of the interruption in the log")
        print(f"trial {trial}: {sig.name}, exit {p.returncode}, {k} of {NSTEP} steps kept")
        for msg in problems:
            print(f"FAIL: trial {trial}: {msg}")
        failures += bool(problems)
    if landed < (trials + 1) // 2:
        print(f"FAIL: only {landed} of {trials} signals came during the run")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
