"""Cost of a run against its number of steps (issue 25: linear, not quadratic).

usage: python bench/many_steps.py [--exe build/vemcontact] [--steps 200 2000] [--parse 100000]

Runs the same two-element model with N steps (each changes a load) and reports the
wall time per step; the ratio of the times of the largest and smallest N over the
ratio of the N must stay near 1 (the target: 2 000 steps in at most 25 x the time of
200 steps).  --parse N times a deck of N steps whose model has no element (refused
after reading, so the time is the deck reader's alone).  Run it with the Release and
the Debug executable.  Not a test: tests never check wall time.
"""
import argparse
import os
import resource
import subprocess
import tempfile
import time

HEAD = """*NODE, NSET=ALL
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 0., 1.
5, 1., 1.
6, 2., 1.
*ELEMENT, TYPE=CPE4, ELSET=PLATE
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*NSET, NSET=BASE
1, 2, 3
*MATERIAL, NAME=ROCK
*ELASTIC
1.0e9, 0.25
*SOLID SECTION, ELSET=PLATE, MATERIAL=ROCK
1.0
*BOUNDARY
BASE, 2
1, 1
"""


def deck(n, elements=True):
    parts = [HEAD if elements else HEAD.split("*ELEMENT")[0]]
    for k in range(n):
        out = "*NODE FILE\nU\n" if k == 0 else ""
        parts.append(f"*STEP\n*STATIC\n{out}*CLOAD\n6, 1, {1.0e3 * (k + 1)!r}\n*END STEP\n")
    return "".join(parts)


def run(exe, text, out):
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "steps.inp")
    with open(path, "w") as f:
        f.write(text)
    t0 = time.perf_counter()
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run([exe, "-q", "-o", out, path], capture_output=True, text=True)
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    return time.perf_counter() - t0, cpu, r.returncode


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", default="build/vemcontact")
    ap.add_argument("--steps", type=int, nargs="+", default=[200, 2000])
    ap.add_argument("--parse", type=int, default=100000)
    a = ap.parse_args()
    times = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.steps:
            t, cpu, rc = run(a.exe, deck(n), os.path.join(tmp, f"run{n}"))
            times[n] = (t, cpu)
            print(f"{n:7d} steps: wall {t:8.2f} s ({1e3 * t / n:.2f} ms per step), "
                  f"cpu {cpu:8.2f} s ({1e3 * cpu / n:.2f} ms per step), exit {rc}")
        lo, hi = min(a.steps), max(a.steps)
        print(f"wall({hi}) / wall({lo}) = {times[hi][0] / times[lo][0]:.1f}, cpu({hi}) / cpu({lo}) = "
              f"{times[hi][1] / times[lo][1]:.1f} for {hi / lo:.0f} x the steps (target at most 25 for 2000/200; "
              "the wall time includes the fsync of every file, which depends on the disk's load)")
        if a.parse:
            t, cpu, rc = run(a.exe, deck(a.parse, elements=False), os.path.join(tmp, "parse"))
            print(f"reading {a.parse} steps (a deck without elements, refused after reading): wall {t:.2f} s, "
                  f"cpu {cpu:.2f} s, exit {rc}")


if __name__ == "__main__":
    main()
