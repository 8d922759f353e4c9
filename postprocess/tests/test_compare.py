"""vc-compare (python -m vctools.compare): passes on identical results, fails with
the right table entry on a perturbed field, a missing or extra step, a changed
mesh and changed contact results, and reports unreadable input in one line with
exit status 2 and no traceback.  Test files are copies of the references under
tests/reference/ edited with h5py."""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

from vctools.compare.__main__ import main

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
REFDIR = os.path.join(ROOT, "tests", "reference")
DAM = os.path.join(REFDIR, "dam_joint.h5")                 # 2 steps, a contact pair
CANTILEVER = os.path.join(REFDIR, "example1_cantilever.h5")  # 1 step, no contact


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return rc, out, err


def rows(out):
    """The table rows as lists of columns (after the header line)."""
    lines = out.splitlines()
    start = next(i for i, l in enumerate(lines) if l.split()[:2] == ["step", "field"]) + 1
    return [l.split() for l in lines[start:] if not l.startswith("compare:") and not l.startswith("MISMATCH")]


def summary(out):
    return [l for l in out.splitlines() if l.startswith("compare: ")][-1]


@pytest.fixture
def dam(tmp_path):
    p = tmp_path / "result.h5"
    shutil.copy(DAM, p)
    return p


def assert_error(rc, out, err, path, what):
    assert rc == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"vc-compare: error: {path}: "), lines[0]
    assert re.search(what, lines[0]), lines[0]
    assert "Traceback" not in err


# ------------------------------------------------------------------ every reference
def test_every_deck_has_a_reference():
    decks = sorted(os.path.splitext(f)[0] for f in os.listdir(os.path.join(ROOT, "inputs")) if f.endswith(".inp"))
    refs = sorted(os.path.splitext(f)[0] for f in os.listdir(REFDIR) if f.endswith(".h5"))
    assert decks == refs


def test_identical_files_pass(dam, capsys):
    rc, out, err = run(capsys, dam, DAM)
    assert rc == 0, out + err
    m = re.fullmatch(r"compare: OK \((\d+) values within tolerance\)", summary(out))
    assert m, summary(out)
    # at least the two steps' displacements of every node are compared
    with h5py.File(DAM) as f:
        nnode = f["mesh/node_ids"].size
    assert int(m.group(1)) >= 2 * 2 * nnode
    assert "no value differs from the reference" in out


def test_fresh_run_matches_reference(tmp_path, capsys):
    """The executable under test (usually the Debug build) reproduces the
    Release-built reference within the default tolerances."""
    exe = os.environ.get("VEMCONTACT_EXE") or os.path.join(ROOT, "build-debug", "vemcontact")
    if not os.path.exists(exe):
        pytest.skip("no vemcontact executable (set VEMCONTACT_EXE)")
    subprocess.run([exe, "-q", "-o", str(tmp_path), os.path.join(ROOT, "inputs", "dam_joint.inp")], check=True)
    rc, out, err = run(capsys, tmp_path / "dam_joint.h5", DAM)
    assert rc == 0, out + err


# ------------------------------------------------------------------ mismatches
def test_perturbed_displacement(dam, capsys):
    """One node's U_x changed by 1e-6 relative: the only failing value, first in the table."""
    with h5py.File(dam, "r+") as f:
        u = f["steps/0002/U"][()]
        i = int(np.argmax(np.abs(u[:, 0])))
        u[i, 0] *= 1 + 1e-6
        f["steps/0002/U"][...] = u
        nid = int(f["mesh/node_ids"][i])
        x, y = f["mesh/coordinates"][i]
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    first = rows(out)[0]
    assert first[:4] == ["2", "U", "x", "node"] and first[4] == str(nid)
    assert float(first[5]) == pytest.approx(x, rel=1e-5) and float(first[6]) == pytest.approx(y, rel=1e-5)
    assert float(first[10]) == pytest.approx(1e-6, rel=1e-3)           # rel diff
    assert float(first[11]) > 1                                         # ratio: fails
    assert all(float(r[11]) <= 1 for r in rows(out)[1:])                # round-off only elsewhere
    assert summary(out) == f"compare: MISMATCH in step 2 U (1 of {u.size} values)"
    # a looser relative tolerance accepts it: |a - b| <= atol + rtol |b|
    rc, out, _ = run(capsys, dam, DAM, "--rtol", "2e-6")
    assert rc == 0 and summary(out).startswith("compare: OK")


@pytest.mark.parametrize("change, fails", [(1e-4, True), (1e-6, False)])
def test_perturbed_contact_pressure(dam, capsys, change, fails):
    """CPRESS is the penalty (1e13 in the dam) times the overclosure: its tolerance is
    K times the COPEN tolerance, 1e13 x 1e-8 x 6.8e-5 = 6.8 Pa at pressures of
    about 1e5 Pa, so a change of 1e-4 fails and one of 1e-6 is round-off."""
    with h5py.File(dam, "r+") as f:
        p = f["steps/0001/contact/pair_1/CPRESS"][()]
        i = int(np.argmax(p))
        p[i] *= 1 + change
        f["steps/0001/contact/pair_1/CPRESS"][...] = p
        nid = int(f["steps/0001/contact/pair_1/node_ids"][i])
    rc, out, _ = run(capsys, dam, DAM)
    assert "atol CPRESS pair_1: 6.82 = max(stress atol, penalty 1e+13 x COPEN atol)" in out
    if not fails:
        assert rc == 0 and summary(out).startswith("compare: OK")
        return
    assert rc == 1
    first = rows(out)[0]
    assert first[:6] == ["1", "CPRESS", "-", "pair_1", "slave", str(nid)]
    assert summary(out) == f"compare: MISMATCH in step 1 contact pair_1 CPRESS (1 of {p.size} values)"


def test_changed_contact_status(dam, capsys):
    with h5py.File(dam, "r+") as f:
        st = f["steps/0002/contact/pair_1/STATUS"][()]
        st[0] = 1 - st[0]
        f["steps/0002/contact/pair_1/STATUS"][...] = st
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert rows(out)[0][:2] == ["2", "STATUS"]
    assert "step 2 contact pair_1 STATUS (1 of 43 values)" in summary(out)


def test_missing_step(dam, capsys):
    with h5py.File(dam, "r+") as f:
        del f["steps/0002"]
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert summary(out) == "compare: MISMATCH in step 2 (RESERVOIR) missing in the result"


def test_extra_step(dam, capsys):
    with h5py.File(dam, "r+") as f:
        f.copy("steps/0002", "steps/0003")
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert summary(out) == "compare: MISMATCH in step 3 (RESERVOIR) not in the reference (extra step)"
    # the reverse: the reference has a step the result lacks
    rc, out, _ = run(capsys, DAM, dam)
    assert rc == 1 and "step 3 (RESERVOIR) missing in the result" in summary(out)


def test_missing_field_in_a_step(dam, capsys):
    """A step cut short (the run died while writing it) lacks a dataset."""
    with h5py.File(dam, "r+") as f:
        del f["steps/0002/S_node"]
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert summary(out) == "compare: MISMATCH in step 2: S_node missing in the result"


def test_moved_node_is_a_changed_mesh(dam, capsys):
    with h5py.File(dam, "r+") as f:
        x = f["mesh/coordinates"][()]
        x[10, 1] += 1e-6 * np.ptp(x[:, 1])
        f["mesh/coordinates"][...] = x
        nid = int(f["mesh/node_ids"][10])
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert summary(out).startswith(f"compare: MISMATCH in mesh (mesh changed: 1 nodes moved (node id {nid} at")
    assert "fields not compared: the mesh changed" in out


def test_changed_connectivity_is_a_changed_mesh(dam, capsys):
    with h5py.File(dam, "r+") as f:
        off = f["mesh/element_offsets"][()]
        con = f["mesh/element_connectivity"][()]
        e = 7
        con[off[e]:off[e + 1]] = np.roll(con[off[e]:off[e + 1]], 1)
        f["mesh/element_connectivity"][...] = con
        eid = int(f["mesh/element_ids"][e])
    rc, out, _ = run(capsys, dam, DAM)
    assert rc == 1
    assert summary(out).startswith(f"compare: MISMATCH in mesh (mesh changed: connectivity of element id {eid} is [")


def test_other_mesh_size(tmp_path, capsys):
    other = os.path.join(REFDIR, "hertz_389_vem.h5")
    rc, out, _ = run(capsys, other, os.path.join(REFDIR, "hertz_600_vem.h5"))
    assert rc == 1
    assert summary(out).startswith("compare: MISMATCH in mesh (mesh changed: 441 nodes, reference ")


def test_selected_fields_and_steps(dam, capsys):
    """--fields and --steps limit the comparison: a perturbed S_node is not seen
    when only U is compared, nor when only step 1 is."""
    with h5py.File(dam, "r+") as f:
        s = f["steps/0002/S_node"][()]
        s[3, 1] *= 1.01
        f["steps/0002/S_node"][...] = s
    assert run(capsys, dam, DAM)[0] == 1
    assert run(capsys, dam, DAM, "--fields", "U,S_element")[0] == 0
    assert run(capsys, dam, DAM, "--steps", "1")[0] == 0
    rc, out, _ = run(capsys, dam, DAM, "--steps", "2", "--fields", "S_node", "--top", "1")
    assert rc == 1 and len(rows(out)) == 1


# ------------------------------------------------------------------ bad input: exit 2
def test_missing_file(tmp_path, capsys):
    missing = tmp_path / "nothing.h5"
    assert_error(*run(capsys, missing, DAM), missing, "no such file")
    assert_error(*run(capsys, DAM, missing), missing, "no such file")


def test_truncated_file(tmp_path, capsys):
    cut = tmp_path / "cut.h5"
    data = open(DAM, "rb").read()
    cut.write_bytes(data[: len(data) // 2])
    assert_error(*run(capsys, cut, DAM), cut, "truncated")


def test_not_hdf5(tmp_path, capsys):
    text = tmp_path / "result.h5"
    text.write_text("this is not HDF5\n")
    assert_error(*run(capsys, text, DAM), text, "not an HDF5 file")
    vtu = tmp_path / "other.vtu"        # a .vtu written by another program
    vtu.write_text('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1">'
                   '<UnstructuredGrid><Piece NumberOfPoints="0" NumberOfCells="0"/></UnstructuredGrid></VTKFile>\n')
    assert_error(*run(capsys, vtu, DAM), vtu, "not an HDF5 file")
    empty = tmp_path / "empty.h5"
    empty.write_bytes(b"")
    assert_error(*run(capsys, DAM, empty), empty, "not an HDF5 file")


def test_hdf5_not_from_vemcontact(tmp_path, capsys):
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["data"] = np.arange(5.0)
    assert_error(*run(capsys, foreign, DAM), foreign, r"not a vemcontact results file \(no root attribute 'format'")
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f.attrs["format"] = np.bytes_("someone-elses-results")
    assert_error(*run(capsys, DAM, other), other, "root attribute format is 'someone-elses-results'")
    incomplete = tmp_path / "incomplete.h5"
    with h5py.File(incomplete, "w") as f:
        f.attrs["format"] = np.bytes_("vemcontact-results")
        f.attrs["format_version"] = np.int32(1)
    assert_error(*run(capsys, incomplete, DAM), incomplete, "no dataset /mesh/coordinates")


def test_requested_field_or_step_that_does_not_exist(tmp_path, capsys):
    assert_error(*run(capsys, CANTILEVER, CANTILEVER, "--fields", "CPRESS"), CANTILEVER, "no field CPRESS in any step")
    assert_error(*run(capsys, DAM, DAM, "--steps", "3"), DAM, r"no step 3 \(it has steps 1, 2\)")
    # present in the reference, not in the result
    short = tmp_path / "short.h5"
    shutil.copy(DAM, short)
    with h5py.File(short, "r+") as f:
        del f["steps/0002"]
    assert_error(*run(capsys, short, DAM, "--steps", "2"), short, r"no step 2 \(it has steps 1\)")
    rc, out, err = run(capsys, DAM, DAM, "--fields", "U,PRESSURE")
    assert rc == 2 and err.strip() == ("vc-compare: error: --fields: unknown field PRESSURE "
                                       "(fields: U, S_element, S_node, COPEN, CPRESS, STATUS)")


# ------------------------------------------------------------------ the command itself
def command(*args):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"))
    return subprocess.run([sys.executable, "-m", "vctools.compare", *map(str, args)],
                          capture_output=True, text=True, env=env)


def test_command_exit_status_and_help(tmp_path):
    r = command("--help")
    assert r.returncode == 0 and "usage: vc-compare" in r.stdout and "--atol-u" in r.stdout
    r = command(DAM, DAM)
    assert r.returncode == 0 and r.stdout.splitlines()[-1].startswith("compare: OK")
    r = command(tmp_path / "none.h5", DAM)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == f"vc-compare: error: {tmp_path / 'none.h5'}: no such file\n"
    bad = tmp_path / "cut.h5"
    bad.write_bytes(open(DAM, "rb").read()[:5000])
    r = command(bad, DAM)
    assert r.returncode == 2 and "Traceback" not in r.stderr and len(r.stderr.splitlines()) == 1


def test_repack_keeps_every_value(tmp_path):
    """References are stored compressed (python -m vctools.compare.repack):
    the values come back bit for bit."""
    from vctools.compare.repack import repack
    out = tmp_path / "packed.h5"
    repack(CANTILEVER, str(out))
    r = command("--rtol", "0", "--atol-u", "0", "--atol-s", "0", out, CANTILEVER)
    assert r.returncode == 0, r.stdout + r.stderr
    with h5py.File(out) as a, h5py.File(CANTILEVER) as b:
        assert a.attrs["format"] == b.attrs["format"]
        assert a["steps/0001"].attrs["name"] == b["steps/0001"].attrs["name"]
        assert a["steps/0001/U"][()].tobytes() == b["steps/0001/U"][()].tobytes()
