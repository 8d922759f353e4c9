"""Every command example of README.md and docs/*.md runs (issue 26).

The commands are extracted from the markdown (indented or fenced code lines starting
with one of the project's commands; continuation lines joined, `# comments` dropped),
optional `[...]` groups removed and the placeholders (RESULT.pvd, DECK, SCENE.toml, ...)
replaced by files of runs made here; each then runs and must exit 0 and write what it
says.  A command that cannot run inside the test suite (the suite itself, the
benchmarks, MPI with PETSc) is listed in NOT_RUN with the test that covers it or why;
a command in the docs that is neither run nor listed fails test_every_command_is_covered,
so a new example cannot go untested."""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys

import meshio
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ENV = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "postprocess"), MPLBACKEND="Agg")
DOCS = [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
# the module behind each console script (pyproject.toml's [project.scripts])
TOOLS = {"vc-plot": "vctools.plot", "vc-curves": "vctools.plot.curves", "vc-compare": "vctools.compare",
         "vc-adapt": "vctools.adapt", "vc-mesh": "vctools.mesh", "vc-paper": "vctools.paper"}
START = re.compile(r"^(vc-[a-z]+ |\./build/vemcontact|bash (scripts|bench)/|PYTHONPATH=postprocess |mpiexec |"
                   r"\.\.\. -m vctools)")

# commands that do not run here, by their first words: why, and what covers them
NOT_RUN = {
    "bash scripts/run-tests.sh": "the test suite itself (CTest runs this file)",
    "bash scripts/run-main.sh": "installs and builds Release; its run and its vc-plot command are mirrored by "
                                "test_run_main_mirror",
    "bash scripts/reproduce-paper.sh": "about 40 runs; test_paper.py::test_paper_quick runs python -m vctools.paper "
                                       "--quick with the same code",
    "mpiexec -n 2": "needs PETSc and MPI; tests/integration/tests.cmake runs the mpi_* cases when built with them",
    "bash bench/": "a benchmark (minutes to hours), not a test (DEVELOPERS.md)",
    "PYTHONPATH=postprocess .venv/bin/python bench/": "a benchmark (minutes to hours), not a test (DEVELOPERS.md)",
    "vc-mesh bench": "a benchmark of the mesher (1e3 to 1e6 cells)",
    "vc-mesh paper": "meshes every scene of the paper; test_deck.py::test_paper_scenes_write_consistent_decks runs it "
                     "into a temporary folder",
}


def doc_commands():
    """(file:line, command) of every command example in the markdown files."""
    out = []
    for path in DOCS:
        if path.endswith("status.md"):
            continue            # history, not instructions
        lines = open(path).read().splitlines()
        fenced = False
        i = 0
        while i < len(lines):
            line = lines[i]
            if line.strip().startswith("```"):
                fenced = not fenced
                i += 1
                continue
            code = fenced or line.startswith("    ")
            text = line.strip()
            if code and START.match(text):
                where = f"{os.path.relpath(path, ROOT)}:{i + 1}"
                # continuation: a trailing backslash, or a usage line going on with "[..."
                while i + 1 < len(lines) and (text.endswith("\\") or lines[i + 1].strip().startswith("[")):
                    i += 1
                    text = text.removesuffix("\\").rstrip() + " " + lines[i].strip()
                out.append((where, text.split(" #")[0].strip()))
            i += 1
    return out


def not_run(cmd):
    for k, why in NOT_RUN.items():
        if cmd.startswith(k):
            return why
    return None


def strip_optional(cmd):
    """Remove [...] groups (nested ones too)."""
    prev = None
    while prev != cmd:
        prev = cmd
        cmd = re.sub(r"\s*\[[^\[\]]*\]", "", cmd)
    return " ".join(cmd.split())


def argv(cmd, exe):
    """The command as an argument list run by this Python and the executable under test."""
    words = shlex.split(cmd)
    if words[0].startswith("PYTHONPATH="):
        words = words[1:]
    if words[0] == "...":
        words = ["python"] + words[1:]
    if words[0] in TOOLS:
        return [sys.executable, "-m", TOOLS[words[0]]] + words[1:]
    if words[0].endswith("python"):
        return [sys.executable] + words[1:]
    if words[0] == "./build/vemcontact":
        return [exe] + words[1:]
    raise AssertionError(f"no way to run {cmd}")


@pytest.fixture(scope="module")
def runs(vemcontact, tmp_path_factory):
    out = tmp_path_factory.mktemp("doccmd")
    for deck in ("dam_joint", "hertz_389_vem", "hertz_329_fem2", "block_selfweight", "rock_block_crack3"):
        subprocess.run([vemcontact, "-q", "-o", str(out / deck), os.path.join(ROOT, "inputs", deck + ".inp")], check=True)
    return out


def test_every_command_is_covered():
    """Each command example either runs below (its tool is known) or is in NOT_RUN."""
    cmds = doc_commands()
    assert len(cmds) >= 20
    for where, cmd in cmds:
        if not_run(cmd):
            continue
        first = shlex.split(cmd)[0]
        assert first in TOOLS or first in ("./build/vemcontact", "...") or first.startswith("PYTHONPATH="), \
            f"{where}: {cmd}: neither run by this test nor listed in NOT_RUN"


def substitutions(runs, tmp, model):
    """Placeholders -> files of the runs ('model' chooses the result of a picture command)."""
    pvd = {"dam": runs / "dam_joint" / "dam_joint.pvd", "hertz": runs / "hertz_389_vem" / "hertz_389_vem.pvd",
           "cpe8": runs / "hertz_329_fem2" / "hertz_329_fem2.pvd"}[model]
    line = {"dam": "4,10,10,4", "hertz": "0,10,5,10", "cpe8": "0,10,5,10"}[model]
    tip = {"dam": "10,4,0.5", "hertz": "0,10,0.5", "cpe8": "0,10,0.5"}[model]
    deck = tmp / "block_selfweight.inp"
    if not deck.exists():
        shutil.copy(os.path.join(ROOT, "inputs", "block_selfweight.inp"), deck)
    scene = tmp / "ex1_cantilever.toml"
    if not scene.exists():
        shutil.copy(os.path.join(ROOT, "postprocess", "scenes", "ex1_cantilever.toml"), scene)
    msh = tmp / "square.msh"
    if not msh.exists():
        pts = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]])
        meshio.write_points_cells(str(msh), pts, [("triangle", np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))],
                                  file_format="gmsh22", binary=False)
    ref = os.path.join(ROOT, "tests", "reference", "hertz_389_vem.h5")
    return [("RESULT.pvd", str(pvd)), ("x1,y1,x2,y2", line), ("X,Y", tip),
            ("OUT_DIR_OR_CSV", str(runs / "hertz_389_vem")),
            ("RUN.h5", str(runs / "hertz_389_vem" / "hertz_389_vem.h5")),
            ("RESULT.h5", str(runs / "hertz_389_vem" / "hertz_389_vem.h5")), ("REFERENCE.h5", ref),
            ("SRM.h5", str(runs / "rock_block_crack3" / "rock_block_crack3.h5")),
            ("SCENE.toml", str(scene)), ("DECK.inp", str(deck)), ("FILE.msh", str(msh)),
            ("postprocess/examples/", os.path.join(ROOT, "postprocess", "examples") + "/")]


def _substitute(cmd, subs):
    for a, b in subs:
        cmd = cmd.replace(a, b)
    return cmd


RUNNABLE = [(w, c) for w, c in doc_commands() if not not_run(c)]


@pytest.mark.parametrize("where,cmd", RUNNABLE, ids=[w for w, _ in RUNNABLE])
def test_command_runs(where, cmd, runs, vemcontact, tmp_path):
    base = strip_optional(cmd)
    first = shlex.split(base)[0]
    models = ["dam", "hertz", "cpe8"] if "vc-plot" in base or "vctools.plot " in base + " " else ["dam"]
    for model in models:
        c = _substitute(base, substitutions(runs, tmp_path, model))
        words = shlex.split(c)
        if first == "vc-adapt" or "vctools.adapt" in c:
            # test_adapt.py's L-shape (deck and scene), on a small budget: a 1 % target
            # would run many cycles; the command as written otherwise
            from test_adapt import DECK, SCENE
            (tmp_path / "lshape.toml").write_text(SCENE)
            (tmp_path / "lshape.inp").write_text(DECK)
            words[words.index("DECK")] = str(tmp_path / "lshape.inp")
            words[words.index("--scene") + 1] = str(tmp_path / "lshape.toml")
            words += ["--max-unknowns", "400", "-o", str(tmp_path / "adapt"), "--exe", vemcontact]
        if "DECK" in words:
            words[words.index("DECK")] = str(tmp_path / "block_selfweight.inp")
        if first in TOOLS and "-o" not in words and first in ("vc-plot", "vc-curves"):
            words += ["-o", str(tmp_path / f"out_{model}" / ("contact.png" if first == "vc-curves" else ""))]
        if words[:2] == ["vc-mesh", "scene"]:
            words += ["-o", str(tmp_path / "mesh") + "/"]
        r = subprocess.run(argv(shlex.join(words), vemcontact), capture_output=True, text=True, env=ENV,
                           cwd=ROOT, timeout=600)
        assert r.returncode == 0, f"{where}: {shlex.join(words)}\n{r.stderr[-2000:]}"


def test_run_main_mirror(runs, tmp_path):
    """scripts/run-main.sh's picture command on its dam run (the README's picture)."""
    script = open(os.path.join(ROOT, "scripts", "run-main.sh")).read()
    m = re.search(r'"\$\{plot\[@\]\}" (--field U:x.*)', script)
    assert m, "run-main.sh's dam picture command"
    args = shlex.split(m.group(1))
    r = subprocess.run([sys.executable, "-m", "vctools.plot", str(runs / "dam_joint" / "dam_joint.pvd"),
                        "-o", str(tmp_path), *args], capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr
    assert len(r.stdout.split()) == 4


def test_python_api_examples(runs, vemcontact, tmp_path, monkeypatch):
    """The Python blocks of docs/python-api.md run: the reading example on the dam run (its
    paths replaced by the run's), the sliding pictures on the rock-block run, the
    deck-writing example as it is."""
    text = open(os.path.join(ROOT, "docs", "python-api.md")).read()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 3
    sliding = blocks.pop(1).replace('"out/rb/rock_block_crack3.h5"',
                                    repr(str(runs / "rock_block_crack3" / "rock_block_crack3.h5")))
    monkeypatch.setenv("VEMCONTACT_EXE", vemcontact)
    monkeypatch.chdir(tmp_path)
    read = blocks[0].replace('vctools.run("inputs/dam_joint.inp", out="out/dam")',
                             f'vctools.run({os.path.join(ROOT, "inputs", "dam_joint.inp")!r}, out="out/dam")')
    ns = {}
    exec(compile(read, "python-api.md", "exec"), ns)
    assert ns["s"].name == "RESERVOIR" and ns["pair"]["CPRESS"].max() > 0
    ns = {}
    exec(compile(sliding, "python-api.md", "exec"), ns)
    assert ns["d"]["factor_of_safety"] > 1 and (tmp_path / "fs.png").exists() and (tmp_path / "joint.png").exists()
    ns = {}
    exec(compile(blocks[1], "python-api.md", "exec"), ns)
    # the pentagon under a load of -1e3 at node 3 (index 2) moves that node down
    assert ns["res"].step("LOAD")["U"][2, 1] < 0
