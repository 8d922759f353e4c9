"""Deck text as editors and terminals leave it: a UTF-8 byte-order mark and
CR-only (old Mac) or CR LF line ends read the same as plain LF; control
characters in a deck are shown escaped (\\xHH) in messages and the log, never
sent raw to the terminal."""
from __future__ import annotations

import os
import subprocess

import h5py
import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DECK = os.path.join(ROOT, "tests", "integration", "decks", "minimal_polygon.inp")


def displacements(exe, deck, out):
    p = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True)
    assert p.returncode == 0, p.stderr.decode(errors="replace")
    with h5py.File(out / (os.path.splitext(os.path.basename(deck))[0] + ".h5")) as f:
        return f["steps/0001/U"][...]


@pytest.mark.parametrize("form", ["bom", "cr", "crlf", "bom_cr"])
def test_line_ends_and_bom(exe, tmp_path, form):
    """The same deck in another encoding gives bit for bit the same displacements."""
    text = open(DECK, "rb").read()
    assert b"\r" not in text
    if "cr" in form:
        text = text.replace(b"\n", b"\r\n" if form == "crlf" else b"\r")
    if form.startswith("bom"):
        text = b"\xef\xbb\xbf" + text
    deck = tmp_path / "variant.inp"
    deck.write_bytes(text)
    u = displacements(exe, deck, tmp_path / "out")
    u_ref = displacements(exe, DECK, tmp_path / "ref")
    assert np.array_equal(u, u_ref)


def test_control_characters_escaped(exe, tmp_path):
    """A terminal escape sequence in a keyword is reported as \\x1B, in the
    message on stderr and in the log; no raw control byte reaches either."""
    deck = tmp_path / "esc.inp"
    deck.write_bytes(b"*NODE\n1, 0, 0\n*FOO\x1b[31mRED\x07\n")
    p = subprocess.run([exe, "-q", "-o", str(tmp_path / "out"), str(deck)], capture_output=True)
    assert p.returncode == 1
    assert b"esc.inp:3: error: unknown keyword" in p.stderr
    assert b"\\x1B[31m" in p.stderr and b"\\x07" in p.stderr
    log = (tmp_path / "out" / "esc.log").read_bytes()
    for stream in (p.stderr, p.stdout, log):
        assert not any(b < 32 and b not in (9, 10) for b in stream)
