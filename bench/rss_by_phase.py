"""Peak resident memory per phase of one run: joins the samples of bench/rss_sampler.sh
("seconds pid kB" lines) with the run's JOB_phases.csv (phases in order, top level only),
taking the process's first sample (default: the longest-sampled process) as the run's start (error up to the 0.5 s sampling
step).  usage: .venv/bin/python bench/rss_by_phase.py RSS.txt JOB_phases.csv [PID]"""
import csv
import sys

samples = [line.split() for line in open(sys.argv[1]) if line.strip()]
pids = [p for _, p, _ in samples]   # default: the process sampled longest (others' runs too)
pid = sys.argv[3] if len(sys.argv) > 3 else max(set(pids), key=pids.count)
s = [(float(t), int(kb) / 1024 ** 2) for t, p, kb in samples if p == pid]
t0 = s[0][0]
t = 0.0
print("| phase | seconds | RSS at end GB | peak RSS within GB |")
print("|---|---:|---:|---:|")
for row in csv.DictReader(open(sys.argv[2])):
    if row["within"] or row["phase"] == "total":
        continue
    dt = float(row["seconds"])
    inside = [gb for (ts, gb) in s if t <= ts - t0 <= t + dt]
    end = [gb for (ts, gb) in s if ts - t0 <= t + dt]
    print(f"| {row['phase']} | {dt:.2f} | {end[-1] if end else 0:.2f} | {max(inside) if inside else float('nan'):.2f} |")
    t += dt
