"""The plot command and the default example's physics."""
import os
import subprocess
import sys

import h5py
import meshio
import numpy as np
import pytest

ENV = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))




@pytest.fixture(scope="module")
def block_result(vemcontact, tmp_path_factory):
    """The default example deck run once: its output folder."""
    out = tmp_path_factory.mktemp("block")
    subprocess.run([vemcontact, "-q", "-o", str(out), os.path.join(ROOT, "inputs", "block_selfweight.inp")],
                   check=True)
    return out


def run_plot(*args):
    return subprocess.run([sys.executable, "-m", "vctools.plot", *args], capture_output=True, text=True, env=ENV)


def test_block_section_equilibrium(block_result):
    """Equilibrium of the part above a horizontal cut: the mean of sigma_yy across
    the cut is -rho g depth (1 m wide block, density 2400, g = 9.81), whatever the
    lateral restraint of the base does to its distribution.  Approximated by the
    area-weighted mean over the cells of a thin band around the cut; the band's
    own weight and the constant-per-cell stress leave an O(h^2) error, 1% here."""
    with h5py.File(block_result / "block_selfweight.h5") as f:
        xy = f["mesh/coordinates"][()]
        off = f["mesh/element_offsets"][()]
        conn = f["mesh/element_connectivity"][()]
        s = f["steps/0001/S_element"][()]
    for cut in (0.3, 0.5, 0.7):
        num = den = ycen = 0.0
        for e in range(len(off) - 1):
            p = xy[conn[off[e]:off[e + 1]]]
            a = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
            cy = np.sum((p[:, 1] + np.roll(p[:, 1], -1)) * (p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])) / (6 * a)
            if abs(cy - cut) < 0.05:
                num += a * s[e, 1]
                den += a
                ycen += a * cy
        mean, ybar = num / den, ycen / den
        expected = -2400 * 9.81 * (1.0 - ybar)
        assert abs(mean - expected) < 0.01 * abs(expected), (cut, mean, expected)


def test_plot_writes_pictures(block_result, tmp_path):
    r = run_plot(str(block_result / "block_selfweight.pvd"), "--deformed", "auto", "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    files = r.stdout.split()
    assert len(files) == 5
    for f in files:
        assert os.path.getsize(f) > 10000
        with open(f, "rb") as fh:
            assert fh.read(8) == b"\x89PNG\r\n\x1a\n"


def test_plot_pdf_and_cell_field(block_result, tmp_path):
    r = run_plot(str(block_result / "block_selfweight_0001.vtu"), "--field", "cell:S:yy", "--format", "pdf",
                 "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    with open(r.stdout.split()[0], "rb") as fh:
        assert fh.read(4) == b"%PDF"


def one_line_error(r, *words):
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    for w in words:
        assert w in lines[0], lines[0]


def test_missing_file(tmp_path):
    one_line_error(run_plot(str(tmp_path / "nothing.pvd")), "nothing.pvd", "no such file")


def test_unknown_field_and_step(block_result):
    one_line_error(run_plot(str(block_result / "block_selfweight.pvd"), "--field", "TEMP"), "no point field TEMP")
    one_line_error(run_plot(str(block_result / "block_selfweight.pvd"), "--field", "S"), "say which")
    one_line_error(run_plot(str(block_result / "block_selfweight.pvd"), "--step", "3"), "no step 3")


def test_foreign_vtu(tmp_path):
    p = tmp_path / "other.vtu"
    meshio.write_points_cells(str(p), np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]), [("triangle", np.array([[0, 1, 2]]))])
    one_line_error(run_plot(str(p)), "other.vtu", "not written by vemcontact")


def test_truncated_vtu(block_result, tmp_path):
    src = (block_result / "block_selfweight_0001.vtu").read_bytes()
    p = tmp_path / "cut.vtu"
    p.write_bytes(src[: len(src) // 2])
    one_line_error(run_plot(str(p)), "cut.vtu")


def test_plot_draws_contact_faces(vemcontact, tmp_path):
    """A contact run's pictures carry its slave nodes (the .pvd's part 1)."""
    subprocess.run([vemcontact, "-q", "-o", str(tmp_path), os.path.join(ROOT, "inputs", "hertz_389_vem.inp")],
                   check=True)
    from vctools.plot.results import contact_file, read_contact_points, step_files
    pvd = str(tmp_path / "hertz_389_vem.pvd")
    step = step_files(pvd)[-1]
    cfile = contact_file(pvd, step)
    assert cfile and cfile.endswith("hertz_389_vem_contact_0001.vtu")
    pts, status = read_contact_points(cfile)
    assert len(pts) == 17 and status.sum() > 0
    r = run_plot(pvd, "--field", "S:yy", "--deformed", "auto", "-o", str(tmp_path / "pics"))
    assert r.returncode == 0, r.stderr


def test_colour_range_excludes_and_clips():
    """A spike at a singular point no longer sets the colour range once excluded; a
    percentile clip gives numpy's percentiles of what is left; the note says both."""
    from vctools.plot.contour import colour_range
    rng = np.random.default_rng(1)
    pos = rng.uniform(0, 1, (1000, 2))
    v = pos[:, 0].copy()
    tip = 7
    pos[tip] = (0.5, 0.5)           # the singular point, alone within 0.01 (checked below)
    assert (np.hypot(*(pos - 0.5).T) <= 0.01).sum() == 1
    v[tip] = 1e6
    lo, hi, note = colour_range(v, pos)
    assert hi == 1e6 and note == ""
    lo, hi, note = colour_range(v, pos, exclude=[(0.5, 0.5, 0.01)])
    rest = np.delete(v, tip)
    assert hi == rest.max() and lo == rest.min() and "within 0.01 of (0.5, 0.5)" in note
    lo, hi, note = colour_range(v, pos, clip=99.0, exclude=[(0.5, 0.5, 0.01)])
    assert (lo, hi) == tuple(np.percentile(rest, [1.0, 99.0])) and "clipped at the percentiles 1 and 99" in note
    with pytest.raises(ValueError):
        colour_range(v, pos, clip=30.0)


def test_overlay_follows_the_deformed_shape():
    """A line given in undeformed coordinates is moved with the field's displacement:
    for a displacement linear in x and y the fan-triangle interpolation is exact."""
    from vctools.plot.contour import deformed_polyline
    from vctools.plot.results import PolyResult
    xs, ys = np.meshgrid(np.linspace(0, 2, 5), np.linspace(0, 1, 3))
    pts = np.column_stack([xs.ravel(), ys.ravel()])
    polys = [np.array([j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i]) for j in range(2) for i in range(4)]
    u = np.column_stack([0.01 * pts[:, 0] + 0.02 * pts[:, 1], -0.03 * pts[:, 0], np.zeros(len(pts))])
    res = PolyResult(points=pts, polygons=polys, point_data={"U": u}, cell_data={}, path="mem")
    line = [[0.0, 0.5], [2.0, 0.5], [2.0, 1.0]]     # along the middle and up the right edge
    got = deformed_polyline(res, line, 10.0)
    base = deformed_polyline(res, line, 0.0)
    assert np.allclose(base, line)
    # the sampled undeformed points p (40 per segment) moved by 10 u(p)
    t = np.linspace(0, 1, 41)
    p = np.vstack([np.outer(1 - t, line[0]) + np.outer(t, line[1]), np.outer(1 - t[1:], line[1]) + np.outer(t[1:], line[2])])
    up = np.column_stack([0.01 * p[:, 0] + 0.02 * p[:, 1], -0.03 * p[:, 0]])
    assert np.allclose(got, p + 10.0 * up, atol=1e-12)


def test_step_name_units_and_clipping_on_the_command_line(block_result, tmp_path):
    from vctools.plot.results import step_label
    assert step_label(str(block_result / "block_selfweight_0001.vtu")) == "step 1, Step-1"
    r = run_plot(str(block_result / "block_selfweight.pvd"), "--field", "S3", "--units", "m,Pa", "--deformed", "auto",
                 "--clip", "99", "--exclude", "0,0", "--line", "0,0.5,1,0.5", "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert os.path.getsize(r.stdout.split()[0]) > 10000
    one_line_error(run_plot(str(block_result / "block_selfweight.pvd"), "--exclude", "1,2,-3"), "--exclude")


def test_meshing_progress_only_on_a_terminal():
    import io
    from vctools.mesh.progress import Progress

    class Tty(io.StringIO):
        def isatty(self):
            return True
    tty, pipe = Tty(), io.StringIO()
    for s in (tty, pipe):
        p = Progress("meshing: Lloyd iteration", after=0.0, stream=s)
        p.update(3, 21)
        p.done()
    assert tty.getvalue() == "\r  meshing: Lloyd iteration 3/21 (0 s)\n" and pipe.getvalue() == ""
