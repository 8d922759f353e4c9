"""Results that never mislead (docs/output-format.md, "Writing results safely"):
full disks, a second run into the same folder, reruns after a failure, planted
symbolic links and kills leave every result file either complete and from the
latest run, or absent.  Every file is opened as data (h5py, meshio, the CSV
module), never judged by the log's text."""
from __future__ import annotations

import csv
import fcntl
import os
import random
import subprocess
import time
import xml.etree.ElementTree as ET

import h5py
import meshio
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DAM = os.path.join(ROOT, "inputs", "dam_joint.inp")   # two steps, one contact pair
STEP_FIELDS = ("U", "S_element", "S_node")


def run(exe, deck, out, **kw):
    return subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True, **kw)


def h5_state(path):
    """(complete attribute, sorted step numbers) of a results file, every dataset read."""
    with h5py.File(path, "r") as f:
        complete = int(f.attrs["complete"])
        steps = []
        for key in sorted(f["steps"]):
            g = f["steps"][key]
            for name in STEP_FIELDS:
                assert g[name][...].size > 0, f"{path}: /steps/{key}/{name} empty"
            if "contact" in g:
                for pg in g["contact"].values():
                    for name in pg:
                        pg[name][...]
            steps.append(int(key))
        return complete, steps


def pvd_steps(path):
    """Step numbers (part 0) and all files listed by a .pvd."""
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    steps, files = [], []
    for ds in root.iter("DataSet"):
        files.append(os.path.join(folder, ds.get("file")))
        if ds.get("part", "0") == "0":
            steps.append(round(float(ds.get("timestep"))))
    return steps, files


def check_folder(out, job, contact=True, allow_temporaries=False):
    """Every result file of `job` in `out` opens and reads in full; the .pvd
    lists only existing files, and the same steps as a JOB.h5 beside it.
    Returns (complete or None when JOB.h5 is absent, steps of the .pvd)."""
    names = sorted(os.listdir(out))
    temporaries = [n for n in names if n.startswith(".") and n.endswith(".tmp")]
    if not allow_temporaries:
        assert not temporaries, f"temporaries left in {out}: {temporaries}"
    for n in names:
        p = os.path.join(out, n)
        assert not os.path.islink(p), f"{p} is a symbolic link"
        if n.endswith(".vtu"):
            m = meshio.read(p, file_format="vtu")
            assert len(m.points) > 0
        elif n.endswith(".csv"):
            with open(p, newline="") as fh:
                text = fh.read()
            assert text.endswith("\n"), f"{p} ends in the middle of a line"
            rows = list(csv.reader(text.splitlines()))
            # JOB_print_NNNN.csv, JOB_phases.csv or a contact CSV
            first = "variable" if "_print_" in n else "step" if n.endswith("_phases.csv") else "node"
            assert rows[0][0] == first and all(len(r) == len(rows[0]) for r in rows), p
    complete, h5steps = None, None
    h5 = os.path.join(out, job + ".h5")
    if os.path.exists(h5):
        complete, h5steps = h5_state(h5)
    steps = []
    pvd = os.path.join(out, job + ".pvd")
    if os.path.exists(pvd):
        steps, files = pvd_steps(pvd)
        for f in files:
            assert os.path.exists(f), f"{pvd} lists the missing {f}"
        if contact:
            assert len(files) == 2 * len(steps)
    if h5steps is not None:
        assert h5steps == steps, f"JOB.h5 has steps {h5steps}, the .pvd {steps}"
    return complete, steps


# ------------------------------------------------------------------ full disk

def test_full_disk(exe, tmp_path):
    """A tmpfs too small for the results at sizes from 5 % to 99 % of what a
    run writes: exit status 2 naming a file and "No space left on device",
    never a crash; what is left is complete; twice the size succeeds."""
    ref = tmp_path / "ref"
    assert run(exe, DAM, ref).returncode == 0
    need = sum(-(-os.path.getsize(ref / n) // 4096) * 4 for n in os.listdir(ref))   # KiB in whole pages
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    failures = 0
    for frac in (0.05, 0.2, 0.4, 0.55, 0.7, 0.85, 0.95, 0.99, 2.0):
        kib = max(8, int(need * frac))
        m = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kib}k", "tmpfs", str(mnt)],
                           capture_output=True, text=True)
        if m.returncode != 0:
            pytest.skip(f"cannot mount a tmpfs here ({m.stderr.strip()}): full-disk test skipped")
        try:
            out = mnt / "r"
            p = run(exe, DAM, out)
            err = p.stderr
            assert "Backtrace" not in err and "Segmentation" not in err, err
            if frac >= 2.0:
                assert p.returncode == 0, err
            assert p.returncode in (0, 2), f"size {kib}k: exit {p.returncode}\n{err}"
            complete, steps = check_folder(out, "dam_joint")
            if p.returncode == 2:
                failures += 1
                assert "No space left on device" in err and str(out) in err, err
                assert complete in (None, 0), f"size {kib}k: a failed run marked complete"
            else:
                assert complete == 1 and steps == [1, 2]
        finally:
            subprocess.run(["umount", str(mnt)], check=True)
    assert failures >= 5


# ------------------------------------------------------------- concurrent runs

def snapshot(folder):
    return {n: (os.path.getsize(os.path.join(folder, n)), os.stat(os.path.join(folder, n)).st_mtime_ns)
            for n in os.listdir(folder)}


def test_second_run_refused_while_locked(exe, tmp_path):
    """While another process holds JOB.lock, a run stops with exit status 2 and
    a clear message, and changes nothing in the folder."""
    out = tmp_path / "out"
    assert run(exe, DAM, out).returncode == 0
    before = snapshot(out)
    with open(out / "dam_joint.lock", "r+") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        p = run(exe, DAM, out)
    assert p.returncode == 2
    assert "another vemcontact run is writing these results" in p.stderr
    assert snapshot(out) == before
    assert check_folder(out, "dam_joint") == (1, [1, 2])


def test_two_runs_at_once(exe, tmp_path):
    """Two runs of one job started 0-40 ms apart: one waits for nothing and
    finishes, the other finishes too (it started after) or refuses with exit
    status 2; the results are complete and readable either way."""
    for delay in (0.0, 0.005, 0.01, 0.02, 0.04):
        out = tmp_path / f"d{delay}"
        a = subprocess.Popen([exe, "-q", "-o", str(out), DAM], stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        b = subprocess.Popen([exe, "-q", "-o", str(out), DAM], stderr=subprocess.PIPE, text=True)
        ra, ea = a.wait(), a.stderr.read()
        rb, eb = b.wait(), b.stderr.read()
        a.stderr.close()
        b.stderr.close()
        assert sorted([ra, rb]) in ([0, 0], [0, 2]), (ra, ea, rb, eb)
        for r, e in ((ra, ea), (rb, eb)):
            if r == 2:
                assert "another vemcontact run" in e
        assert check_folder(out, "dam_joint") == (1, [1, 2])


# -------------------------------------------------------------------- reruns

TWO_STEPS = """*NODE
1, 0, 0
2, 1, 0
3, 1, 1
4, 0, 1
*ELEMENT, TYPE=VPE, ELSET=ALL
1, 1, 2, 3, 4
*MATERIAL, NAME=M
*ELASTIC
100.0, 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
*STEP
*STATIC
*BOUNDARY
1, 1, 2
2, 2
*CLOAD
3, 2, -1.0
*END STEP
*STEP
*STATIC
*BOUNDARY, OP=NEW
1, {second}
2, 2
*END STEP
"""


def test_rerun_after_failure(exe, tmp_path):
    """A good two-step run, then a rerun of the same job that fails in step 2
    (exit 3): nothing of the first run is left; the .pvd and JOB.h5 hold step
    1 of the rerun only, JOB.h5 is marked incomplete, and vc-compare and
    vc-plot refuse it."""
    from vctools.compare.__main__ import main as compare_main
    from vctools.plot.__main__ import main as plot_main

    good, bad, out = tmp_path / "good", tmp_path / "bad", tmp_path / "out"
    good.mkdir()
    bad.mkdir()
    (good / "job.inp").write_text(TWO_STEPS.format(second="1, 2"))
    (bad / "job.inp").write_text(TWO_STEPS.format(second="2"))   # x free in step 2: floats
    assert run(exe, good / "job.inp", out).returncode == 0
    assert check_folder(out, "job", contact=False) == (1, [1, 2])
    with h5py.File(out / "job.h5") as f:
        u_first = f["steps/0001/U"][...]

    p = run(exe, bad / "job.inp", out)
    assert p.returncode == 3, p.stderr
    assert not os.path.exists(out / "job_0002.vtu")
    assert check_folder(out, "job", contact=False) == (0, [1])
    with h5py.File(out / "job.h5") as f:
        assert (f["steps/0001/U"][...] == u_first).all()   # step 1 is the same in both decks

    assert compare_main([str(out / "job.h5"), str(out / "job.h5")]) == 2
    assert plot_main([str(out / "job.pvd"), "-o", str(tmp_path / "pics")]) == 1
    assert plot_main([str(out / "job_0001.vtu"), "-o", str(tmp_path / "pics")]) == 1
    assert not os.path.exists(tmp_path / "pics") or not os.listdir(tmp_path / "pics")


def test_print_tables_rerun_and_links(exe, tmp_path):
    """JOB_print_NNNN.csv (*NODE PRINT, *EL PRINT) is written like every result:
    a link planted under its name is replaced, not written through; a rerun
    without PRINT requests removes the previous run's tables and their
    temporaries; a rerun failing in step 2 leaves step 1's table only."""
    prints = "*NODE PRINT, NSET=FIX, TOTALS=YES\nRF\n*EL PRINT, ELSET=ALL\nS\n*END STEP"
    with_print = TWO_STEPS.replace("*MATERIAL", "*NSET, NSET=FIX\n1, 2\n*MATERIAL")
    with_print = with_print.replace("*END STEP", prints)
    decks = {}
    for name, second in (("good", "1, 2"), ("bad", "2")):
        (tmp_path / name).mkdir()
        decks[name] = tmp_path / name / "job.inp"
        decks[name].write_text(with_print.format(second=second))
    (tmp_path / "plain").mkdir()
    decks["plain"] = tmp_path / "plain" / "job.inp"
    decks["plain"].write_text(TWO_STEPS.format(second="1, 2"))
    out = tmp_path / "out"
    out.mkdir()
    victim = tmp_path / "victim"
    victim.write_text("precious")
    os.symlink(victim, out / "job_print_0001.csv")

    p = run(exe, decks["good"], out)
    assert p.returncode == 0, p.stderr
    assert victim.read_text() == "precious"
    assert check_folder(out, "job", contact=False) == (1, [1, 2])
    for step in (1, 2):
        with open(out / f"job_print_{step:04d}.csv", newline="") as fh:
            rows = list(csv.DictReader(fh))
        # both supports' reactions balance the single load (0, -1) of the deck
        total = [float(r["value"]) for r in rows if r["entity"] == "total" and r["variable"] == "RF"]
        assert len(total) == 2 and abs(total[1] - 1.0) < 1e-12, total   # sums of 2 values: round-off only
        assert sum(r["variable"] == "S" for r in rows) == 4              # one element, 4 components

    (out / ".job_print_0002.csv.AAAAAAAAAAAA.tmp").write_text("left by a killed run")
    assert run(exe, decks["plain"], out).returncode == 0
    assert not [n for n in os.listdir(out) if "_print_" in n], os.listdir(out)

    assert run(exe, decks["good"], out).returncode == 0
    p = run(exe, decks["bad"], out)
    assert p.returncode == 3, p.stderr
    assert os.path.exists(out / "job_print_0001.csv") and not os.path.exists(out / "job_print_0002.csv")
    assert check_folder(out, "job", contact=False) == (0, [1])


def test_incomplete_messages(exe, tmp_path, capsys):
    """The refusals say what is wrong and what to do."""
    from vctools.compare.__main__ import main as compare_main
    from vctools.plot.__main__ import main as plot_main

    (tmp_path / "job.inp").write_text(TWO_STEPS.format(second="2"))
    out = tmp_path / "out"
    assert run(exe, tmp_path / "job.inp", out).returncode == 3
    capsys.readouterr()
    compare_main([str(out / "job.h5"), str(out / "job.h5")])
    assert "incomplete results" in capsys.readouterr().err
    plot_main([str(out / "job.pvd")])
    assert "incomplete results" in capsys.readouterr().err
    os.remove(out / "job.h5")
    plot_main([str(out / "job.pvd")])
    assert "job.h5 is missing" in capsys.readouterr().err


# --------------------------------------------------------------------- links

def test_planted_symbolic_links(exe, tmp_path):
    """Links planted under the names of the results, the log and a temporary
    are replaced (or removed), never written through; a link planted as
    JOB.lock stops the run with exit status 2."""
    victims = tmp_path / "victims"
    victims.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    names = ["dam_joint.log", "dam_joint.h5", "dam_joint.pvd", "dam_joint_0001.vtu",
             "dam_joint_contact_pair1_0002.csv", ".dam_joint.h5.AAAAAAAAAAAA.tmp"]
    for k, n in enumerate(names):
        (victims / f"v{k}").write_text("precious")
        os.symlink(victims / f"v{k}", out / n)
    p = run(exe, DAM, out)
    assert p.returncode == 0, p.stderr
    for k in range(len(names)):
        assert (victims / f"v{k}").read_text() == "precious"
    assert check_folder(out, "dam_joint") == (1, [1, 2])
    assert not os.path.lexists(out / names[-1])

    out2 = tmp_path / "out2"
    out2.mkdir()
    (victims / "lock").write_text("precious")
    os.symlink(victims / "lock", out2 / "dam_joint.lock")
    p = run(exe, DAM, out2)
    assert p.returncode == 2 and "dam_joint.lock" in p.stderr
    assert (victims / "lock").read_text() == "precious"
    assert sorted(os.listdir(out2)) == ["dam_joint.lock"]


# --------------------------------------------------------------------- kills

def test_kills_at_random_points(exe, tmp_path):
    """A two-step run killed at random points (fixed seed), each time in the
    folder the previous kill left: every file there opens and reads, the .pvd
    lists only existing files, JOB.h5 is absent or complete; a last full run
    leaves complete results and no temporaries."""
    out = tmp_path / "out"
    # the shorter of two full runs: the first can be slow (cold caches, a loaded
    # machine), and sleeps beyond a run's length kill nothing
    duration = float("inf")
    for _ in range(2):
        t0 = time.perf_counter()
        assert run(exe, DAM, out).returncode == 0
        duration = min(duration, time.perf_counter() - t0)
    rng = random.Random(11)
    kills = 0
    for _ in range(12):
        p = subprocess.Popen([exe, "-q", "-o", str(out), DAM], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.0, 0.9 * duration))
        p.kill()
        rc = p.wait()
        kills += rc == -9
        complete, steps = check_folder(out, "dam_joint", allow_temporaries=True)
        assert complete in (None, 1)
        if complete == 1:
            assert steps == [1, 2]
    assert kills >= 6
    assert run(exe, DAM, out).returncode == 0
    assert check_folder(out, "dam_joint") == (1, [1, 2])
