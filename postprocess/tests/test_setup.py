"""The Python set-up the README describes: the pinned set fits the package's ranges and
is what runs the tests, the console scripts are installed where the README says, and
the package has no import circle."""
import ast
import importlib.metadata as md
import os
import subprocess
import sys
import tomllib

import pytest
from packaging.requirements import Requirement

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PKG = os.path.join(ROOT, "postprocess", "vctools")
PYPROJECT = tomllib.load(open(os.path.join(ROOT, "postprocess", "pyproject.toml"), "rb"))
SCRIPTS = PYPROJECT["project"]["scripts"]
IN_PROJECT_VENV = os.path.realpath(sys.prefix) == os.path.realpath(os.path.join(ROOT, ".venv"))


def pins():
    out = {}
    for line in open(os.path.join(ROOT, "postprocess", "requirements.txt")):
        line = line.split("#")[0].strip()
        if line:
            name, version = line.split("==")
            out[name.lower()] = version
    return out


def test_pins_fit_the_ranges():
    """Every runtime dependency is pinned, inside pyproject.toml's range; numpy 2."""
    p = pins()
    for dep in PYPROJECT["project"]["dependencies"] + PYPROJECT["project"]["optional-dependencies"]["test"]:
        r = Requirement(dep)
        assert r.name.lower() in p, f"{r.name} not pinned"
        assert r.specifier.contains(p[r.name.lower()]), f"{r.name}=={p[r.name.lower()]} outside {r.specifier}"
    assert int(p["numpy"].split(".")[0]) >= 2


@pytest.mark.skipif(not IN_PROJECT_VENV, reason="not the project's .venv (scripts/install-deps.sh)")
def test_the_tests_run_on_the_pinned_set():
    for name, version in pins().items():
        assert md.version(name) == version, name


@pytest.mark.skipif(not IN_PROJECT_VENV, reason="not the project's .venv (scripts/install-deps.sh)")
def test_console_scripts_installed():
    """scripts/install-deps.sh installs vctools into .venv: every console script of
    pyproject.toml is in .venv/bin (on the PATH after `source .venv/bin/activate`,
    as the README says) and answers --help."""
    eps = {e.name: e.value for e in md.entry_points(group="console_scripts") if e.dist and e.dist.name == "vctools"}
    assert eps == SCRIPTS
    readme = open(os.path.join(ROOT, "README.md")).read()
    assert "source .venv/bin/activate" in readme
    for name in SCRIPTS:
        assert name in readme, f"{name} not in the README"
        exe = os.path.join(os.path.dirname(sys.executable), name)
        r = subprocess.run([exe, "--help"], capture_output=True, text=True)
        assert r.returncode == 0 and "usage" in r.stdout.lower(), (name, r.stderr)


def _imports(path, module):
    """Modules of vctools that `module` (dotted) imports, at any depth of its code."""
    tree = ast.parse(open(path).read())
    pkg = module.rsplit(".", 1)[0] if not path.endswith("__init__.py") else module
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            names = [target] + [f"{target}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        out |= {n for n in names if n.startswith("vctools")}
    return out


def test_no_import_circle():
    """No module of vctools imports, through others, itself (vctools.paper's document
    and reproduce imported each other: now document -> reproduce only)."""
    mods = {}
    for dirpath, _, files in os.walk(PKG):
        for f in files:
            if f.endswith(".py"):
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, os.path.dirname(PKG))[:-3].replace(os.sep, ".")
                mods[rel.removesuffix(".__init__")] = path
    graph = {m: {t for t in _imports(p, m) if t in mods and t != m} for m, p in mods.items()}
    # packages import their __init__ on the way: leave them out (they import nothing heavy)
    graph = {m: {t for t in ts if not os.path.basename(mods[t]) == "__init__.py"} for m, ts in graph.items()}
    seen, stack, cycles = set(), [], []

    def visit(m):
        if m in stack:
            cycles.append(stack[stack.index(m):] + [m])
            return
        if m in seen:
            return
        seen.add(m)
        stack.append(m)
        for t in sorted(graph[m]):
            visit(t)
        stack.pop()

    for m in sorted(graph):
        visit(m)
    assert not cycles, cycles
    assert "vctools.paper.reproduce" in graph["vctools.paper.document"]
    assert "vctools.paper.document" not in graph["vctools.paper.reproduce"]
