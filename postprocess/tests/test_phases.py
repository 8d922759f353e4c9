"""The phase times a run writes as data (JOB_phases.csv, docs/output-format.md
"Phase times"): every phase of the run is there and the phases add up to the
run's total.  Read with the csv module, never from the log's text."""
from __future__ import annotations

import csv
import os
import subprocess
import time

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# the phases of every run, in the order logged, outside the steps and per step
SETUP = ["start", "read", "validate", "pattern", "assemble", "analyze", "set-up", "write mesh"]
PER_STEP = ["solve", "system", "stresses", "write"]


def phases(exe, deck, out):
    """Rows of JOB_phases.csv of a run of `deck`, and the run's wall time seen from outside."""
    t0 = time.perf_counter()
    r = subprocess.run([exe, "-q", "-o", str(out), deck], capture_output=True, text=True)
    elapsed = time.perf_counter() - t0
    assert r.returncode == 0, r.stderr
    job = os.path.splitext(os.path.basename(deck))[0]
    with open(os.path.join(out, f"{job}_phases.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        row["step"] = int(row["step"])
        row["seconds"] = float(row["seconds"])
    return rows, elapsed


@pytest.mark.parametrize("deck, nsteps, contact", [
    ("inputs/example1_cantilever.inp", 1, False),
    ("inputs/dam_joint.inp", 2, True),
])
def test_phases_add_up_to_total(exe, tmp_path, deck, nsteps, contact):
    rows, elapsed = phases(exe, os.path.join(ROOT, deck), tmp_path)
    assert rows[-1]["phase"] == "total" and rows[-1]["within"] == "" and rows[-1]["step"] == 0
    total = rows[-1]["seconds"]
    top = [r for r in rows[:-1] if r["within"] == ""]
    # every phase of the run is there: the set-up phases once, the step phases once per step
    assert [r["phase"] for r in top if r["step"] == 0][:len(SETUP)] == SETUP
    assert [r["phase"] for r in top if r["step"] == 0][-1] == "finish"
    for step in range(1, nsteps + 1):
        names = [r["phase"] for r in top if r["step"] == step]
        assert all(p in names for p in PER_STEP), (step, names)
        if contact:
            assert "search" in names
    assert all(r["seconds"] >= 0.0 for r in rows)
    # sub-phases lie within their phase
    for r in rows:
        if r["within"]:
            outer = [o for o in top if o["phase"] == r["within"] and o["step"] == r["step"]]
            assert len(outer) == 1 and r["seconds"] <= outer[0]["seconds"]
    if contact:
        assert any(r["phase"] == "candidates" and r["within"] == "pattern" for r in rows)
    # The phases are consecutive laps of one wall clock from the run's first
    # reading to the last before `total` (vemcontact_log), so their sum misses
    # only the return from the analysis to the `total` reading (microseconds)
    # and rounding in the last digits: the 3 % of issue 15 is a loose bound
    # that still fails when a phase of even 3 % of the run is not logged.
    assert total > 0.0
    assert abs(sum(r["seconds"] for r in top) - total) <= 0.03 * total
    # the total is the process's own time, so within what the caller waited
    assert total <= elapsed
