"""Friction with the finite sliding of NODE TO SURFACE (issue 23 item 1).

The combination is still refused: its kinematics (the slip as the reference arc length
of the point along the reference normal) and its Newton steps are in place, and the
inclined block of test_friction_limit.py and a block slid over several master
segments converge with it, but the pad of F1 (test_friction_limit.py's pad_deck with
TYPE=NODE TO SURFACE and its base extended to x = 60) does not converge at the onset of
slip when the step is cut into increments (docs/contact-formulation.md, "Friction with
finite sliding").  This file holds the refusal: one message naming the pair's file:line
and the remedy, exit 1, no results.
"""
import subprocess

from test_friction_limit import MU, deck


def test_finite_sliding_refused(exe, tmp_path):
    """*FRICTION on a NODE TO SURFACE pair without SMALL SLIDING: one message naming
    the pair's file:line and the remedy, exit 1, no results."""
    path, _ = deck(tmp_path, "finite", "CPE4", "NODE TO SURFACE", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD",
                   f"*FRICTION\n{float(MU)!r}")
    r = subprocess.run([exe, "-q", "-o", str(tmp_path / "o"), str(path)], capture_output=True, text=True)
    assert r.returncode == 1
    assert "friction (*FRICTION) on a NODE TO SURFACE pair needs SMALL SLIDING" in r.stderr
    assert "finite.inp:" in r.stderr and r.stderr.count("error:") == 1
    assert not list((tmp_path / "o").glob("*.h5")) if (tmp_path / "o").exists() else True
