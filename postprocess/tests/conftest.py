"""Shared fixtures: the vemcontact executable and the repository root."""
import os
import shutil
import subprocess

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="session")
def vemcontact():
    """Path of the built executable (CTest passes it in VEMCONTACT_EXE)."""
    exe = os.environ.get("VEMCONTACT_EXE")
    if not exe:
        for cand in ("build-debug/vemcontact", "build/vemcontact"):
            if os.path.exists(os.path.join(ROOT, cand)):
                exe = os.path.join(ROOT, cand)
                break
    if not exe or not os.path.exists(exe):
        pytest.fail("vemcontact executable not found: set VEMCONTACT_EXE or build first")
    return exe


@pytest.fixture(scope="session")
def block_result(vemcontact, tmp_path_factory):
    """The default example deck run once: its output folder."""
    out = tmp_path_factory.mktemp("block")
    subprocess.run([vemcontact, "-q", "-o", str(out), os.path.join(ROOT, "inputs", "block_selfweight.inp")],
                   check=True)
    return out
