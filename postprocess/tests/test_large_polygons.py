"""Polygons beyond the element vertex limit (2000, src/driver/validate.f90,
docs/deck-reference.md) are refused with file:line before any quadratic check
or dense element matrix, and reading a long continued element line is linear."""
from __future__ import annotations

import math
import subprocess


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
