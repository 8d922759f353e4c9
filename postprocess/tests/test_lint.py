"""The Python package passes ruff with the rules configured in postprocess/pyproject.toml."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parents[1]


def test_ruff_clean():
    ruff = shutil.which("ruff", path=str(Path(sys.executable).parent))
    if ruff is None:
        pytest.fail("ruff is not installed: it is pinned in postprocess/requirements.txt")
    r = subprocess.run([ruff, "check", "--no-cache", "."], cwd=HERE, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_pyproject_lists_every_requirement():
    """Every pinned runtime package of requirements.txt is a dependency in pyproject.toml."""
    import tomllib
    deps = tomllib.loads((HERE / "pyproject.toml").read_text())["project"]
    names = {d.split(">")[0].split("<")[0].split("=")[0].strip()
             for d in deps["dependencies"] + deps["optional-dependencies"]["test"]}
    pinned = {ln.split("==")[0].strip() for ln in (HERE / "requirements.txt").read_text().splitlines()
              if ln.strip() and not ln.startswith("#")}
    assert pinned <= names, pinned - names
