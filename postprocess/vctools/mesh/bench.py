"""Benchmark: a square of n Voronoi cells with Lloyd iterations (not a test: wall time)."""
from __future__ import annotations

import os
import time

from .polymesh import VBody, voronoi_group
from .quality import quality


def _cpu():
    """CPU seconds of this process and of its finished children (the worker processes)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def run(sizes, lloyd=10, processes=None, echo=print):
    rows = []
    echo(f"{'cells':>10} {'lloyd':>5} {'seconds':>9} {'cells/s':>10} {'cpu s':>8}  min angle  short edge")
    for n in sizes:
        n = int(n)
        t0 = time.perf_counter()
        c0 = _cpu()
        m = voronoi_group([VBody("B", [[0, 0], [1, 0], [1, 1], [0, 1]], n)], seed=1, lloyd=lloyd,
                          processes=processes)
        dt = time.perf_counter() - t0
        cpu = _cpu() - c0
        q = quality(m)
        echo(f"{m.ncell:>10d} {lloyd:>5d} {dt:>9.2f} {m.ncell / dt:>10.0f} {cpu:>8.1f}  {q['angle_min_deg']:9.2f}  "
             f"{q['short_edge_ratio_min']:.3g}")
        rows.append((m.ncell, dt))
    return rows
