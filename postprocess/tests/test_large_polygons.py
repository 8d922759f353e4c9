"""Polygons beyond the element vertex limit (2000, src/driver/validate.f90,
docs/deck-reference.md) are refused with file:line before any quadratic check
or dense element matrix, and reading a long continued element line is linear."""
from __future__ import annotations

import math
import subprocess

import pytest


def polygon_deck(n: int) -> str:
    """A regular n-gon as one VPE element, its node ids 12 to a continued line."""
    lines = ["*NODE"]
    lines += [f"{k + 1}, {math.cos(2 * math.pi * k / n):.17g}, {math.sin(2 * math.pi * k / n):.17g}"
              for k in range(n)]
    lines.append("*ELEMENT, TYPE=VPE, ELSET=P")
    ids = ["1"] + [str(k + 1) for k in range(n)]
    lines.append(",\n".join(", ".join(ids[i:i + 12]) for i in range(0, len(ids), 12)))
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", "1e3, 0.3", "*SOLID SECTION, ELSET=P, MATERIAL=M",
              "*BOUNDARY", "1, 1, 2", "2, 2", "*STEP", "*STATIC", "*CLOAD", "3, 2, -1.", "*END STEP"]
    return "\n".join(lines) + "\n"


def test_10000_vertex_polygon_refused(exe, tmp_path):
    deck = tmp_path / "poly.inp"
    deck.write_text(polygon_deck(10000))
    p = subprocess.run([exe, "-q", "-o", str(tmp_path / "out"), str(deck)], capture_output=True, text=True,
                       timeout=60)
    assert p.returncode == 1
    # the element's line: 1 *NODE line, 10000 node lines, the *ELEMENT line, then its first data line
    assert "poly.inp:10003: error: element 1 has 10000 nodes, more than the limit of 2000" in p.stderr
    assert "Backtrace" not in p.stderr


def test_memory_estimate_stops_before_assembly(exe, tmp_path):
    """Enough 2000-node polygons (all on the same nodes) that the bound of their
    dense blocks, 12 bytes * (2 * 2000)^2 each, exceeds this machine's memory:
    a clear message and exit status 3 before anything is assembled."""
    total = 0
    with open("/proc/meminfo") as fh:
        for line in fh:
            if line.startswith("MemTotal:"):
                total = int(line.split()[1]) * 1024
    per_element = 12 * (2 * 2000) ** 2
    count = total // per_element + 2
    if total == 0 or count > 3000:
        pytest.skip(f"MemTotal {total} bytes needs {count} polygons: too large a deck for a test")
    n = 2000
    lines = ["*NODE"]
    lines += [f"{k + 1}, {math.cos(2 * math.pi * k / n):.17g}, {math.sin(2 * math.pi * k / n):.17g}"
              for k in range(n)]
    lines.append("*ELEMENT, TYPE=VPE, ELSET=P")
    ids = ", ".join(str(k + 1) for k in range(n))
    lines += [f"{e + 1}, {ids}" for e in range(count)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", "1e3, 0.3", "*SOLID SECTION, ELSET=P, MATERIAL=M",
              "*BOUNDARY", "1, 1, 2", "1001, 2", "*STEP", "*STATIC", "*END STEP"]
    deck = tmp_path / "many.inp"
    deck.write_text("\n".join(lines) + "\n")
    p = subprocess.run([exe, "-q", "-o", str(tmp_path / "out"), str(deck)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 3, p.stderr
    assert "GB of memory of this machine" in p.stderr
    assert "Backtrace" not in p.stderr
