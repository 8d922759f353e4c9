"""Warnings for valid but poor models (src/driver/validate.f90, element_warnings):
nearly incompressible plane-strain FEM sections lock (docs/stability-elements.md), the
VEM does not.  The run still answers (exit 0); the log and the screen carry the warning
with the file:line of the *SOLID SECTION."""
import subprocess

import pytest

DECK = """*NODE
1, 0, 0
2, 1, 0
3, 2, 0
4, 0, 1
5, 1, 1
6, 2, 1
*ELEMENT, TYPE={etype}, ELSET=ALL
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*MATERIAL, NAME=RUBBERY
*ELASTIC
100.0, {nu}
*SOLID SECTION, ELSET=ALL, MATERIAL=RUBBERY{form}
*BOUNDARY
1, 1, 2
4, 1
*STEP
*STATIC
*CLOAD
6, 2, -1.0
*END STEP
"""




def run(exe, tmp_path, etype, nu, form=""):
    deck = tmp_path / "lock.inp"
    deck.write_text(DECK.format(etype=etype, nu=nu, form=form))
    r = subprocess.run([exe, str(deck)], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    log = (tmp_path / "lock.log").read_text()
    return r, log


@pytest.mark.parametrize("etype", ["CPE4", "CPE4R"])
def test_fem_plane_strain_near_incompressible_warns(exe, tmp_path, etype):
    r, log = run(exe, tmp_path, etype, 0.49)
    if etype == "CPE4R":
        # no reduced-integration quad here: the deck is refused with a message instead
        assert r.returncode == 1 and "CPE4R" in r.stdout + r.stderr
        return
    assert r.returncode == 0, r.stderr
    line = [l for l in log.splitlines() if "warning:" in l]
    assert len(line) == 1
    assert "lock.inp:14: warning: element set ALL" in line[0]
    assert "nearly incompressible" in line[0] and "FORMULATION=VEM" in line[0]
    assert "warning:" in r.stdout


@pytest.mark.parametrize("etype,nu,form", [("CPE4", 0.3, ""), ("CPE4", 0.49, ", FORMULATION=VEM"),
                                           ("CPS4", 0.49, "")])
def test_no_warning_where_nothing_locks(exe, tmp_path, etype, nu, form):
    # nu = 0.3; the VEM (capped stabilisation); plane stress (no volumetric constraint)
    r, log = run(exe, tmp_path, etype, nu, form)
    assert r.returncode == 0, r.stderr
    assert "warning:" not in log
