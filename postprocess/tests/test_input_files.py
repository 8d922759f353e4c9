"""Inputs that cost more than they are worth (docs/deck-reference.md, "Deck files"):
a deck or *INCLUDE that is a FIFO, a pipe, a device, a folder or a /proc file is
refused at once; a binary file or a line beyond the documented limit is refused
after reading at most a piece of it, with a message under 1 kB naming the file and
line; a count a deck gives (MAXIT) is bounded before anything is sized by it.
Every outcome is asserted from the exit status and the process's own accounting
(wait4: peak resident memory, terminating signal); the message is checked for
its length and the file it names only."""
from __future__ import annotations

import os
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BLOCK = os.path.join(ROOT, "inputs", "block_selfweight.inp")
# a clear outcome comes in well under a second; 20 s only fails on a hang
LIMIT_S = 20.0
# the program's own resident size is about 40 MB (Debug); reading a 1 GB file whole
# would take 1 GB, a 100 MB line 100 MB more
MAX_RSS_KB = 100_000
# src/deck/file.f90's max_line_length
MAX_LINE = 65536


# Started from a fresh, small Python: a child's peak resident size (wait4's
# ru_maxrss) also counts the image of the process it was forked from, and the test
# process grows to hundreds of MB in a long pytest session.
LAUNCHER = """
import os, subprocess, sys
p = subprocess.Popen(sys.argv[1:], stdin=0, stdout=subprocess.DEVNULL)
_, status, usage = os.wait4(p.pid, 0)
code = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
print(code, usage.ru_maxrss)
"""


def run(exe, deck, out, stdin=None):
    """(exit status or -signal, stderr, peak resident kB) of one run."""
    p = subprocess.run([sys.executable, "-c", LAUNCHER, exe, "-q", "-o", str(out), str(deck)],
                       stdin=stdin or subprocess.DEVNULL, capture_output=True, timeout=LIMIT_S, check=False)
    code, rss = map(int, p.stdout.split())
    return code, p.stderr.decode(errors="replace"), rss


def including(tmp_path, target, name="deck.inp"):
    """A copy of the block deck whose first line includes `target`."""
    deck = tmp_path / name
    deck.write_text(f"*INCLUDE, INPUT={target}\n" + open(BLOCK).read())
    return deck


def assert_refused(code, err, status, name):
    assert code == status, f"exit status {code}, expected {status}: {err}"
    assert 0 < len(err.encode()) < 1024, f"message of {len(err.encode())} bytes"
    assert name in err


@pytest.mark.parametrize("as_include", [False, True])
def test_fifo_without_writer(exe, tmp_path, as_include):
    fifo = tmp_path / "stream.inp"
    os.mkfifo(fifo)
    deck = including(tmp_path, fifo) if as_include else fifo
    code, err, _ = run(exe, deck, tmp_path / "out")
    assert_refused(code, err, 1 if as_include else 2, "stream.inp")


def test_pipe_as_deck(exe, tmp_path):
    """`vemcontact /dev/stdin` with the deck piped in: refused, never "empty"."""
    r, w = os.pipe()
    os.write(w, open(BLOCK, "rb").read()[:4096])
    os.close(w)
    with os.fdopen(r, "rb") as f:
        code, err, _ = run(exe, "/dev/stdin", tmp_path / "out", stdin=f)
    assert_refused(code, err, 2, "/dev/stdin")
    assert "empty" not in err


@pytest.mark.parametrize("special", ["/dev/urandom", "/dev/zero", "/proc/self/mem", "/proc/cpuinfo"])
def test_device_and_proc_files(exe, tmp_path, special):
    code, err, _ = run(exe, special, tmp_path / "out")
    assert_refused(code, err, 2, special)
    code, err, _ = run(exe, including(tmp_path, special), tmp_path / "out")
    assert_refused(code, err, 1, special)


def test_one_gigabyte_include(exe, tmp_path):
    """A sparse 1 GB file (NUL bytes): refused after its first piece, in bounded memory."""
    big = tmp_path / "big.bin"
    with open(big, "wb") as f:
        f.truncate(1 << 30)
    code, err, rss = run(exe, including(tmp_path, big), tmp_path / "out")
    assert_refused(code, err, 1, "big.bin")
    assert rss < MAX_RSS_KB, f"peak resident {rss} kB"


def test_binary_include(exe, tmp_path):
    """10 MB of random bytes (fixed seed): a message under 1 kB, not the file echoed."""
    import random
    rng = random.Random(7)
    binary = tmp_path / "random.bin"
    binary.write_bytes(rng.randbytes(10 * 1024 * 1024))
    code, err, rss = run(exe, including(tmp_path, binary), tmp_path / "out")
    assert_refused(code, err, 1, "random.bin")
    assert rss < MAX_RSS_KB


def test_huge_line_without_nul(exe, tmp_path):
    """A 100 MB text line (no line end): refused at the line limit, without reading it all;
    a comment line exactly at the limit is read and skipped."""
    long_line = tmp_path / "long.inp"
    with open(long_line, "wb") as f:
        f.write(b"1" * (100 << 20))
    code, err, rss = run(exe, including(tmp_path, long_line), tmp_path / "out")
    assert_refused(code, err, 1, "long.inp")
    assert rss < MAX_RSS_KB
    # at the limit: read as a deck line (an error about its content, not its length)
    at_limit = tmp_path / "limit.inp"
    at_limit.write_text("** " + "x" * (MAX_LINE - 3) + "\n")
    code, err, _ = run(exe, including(tmp_path, at_limit, "deck2.inp"), tmp_path / "out2")
    assert code == 0, err


def test_maxit_bounded(exe, tmp_path):
    """MAXIT = 2**31 - 1 is refused with the deck line, before anything is sized by it."""
    deck = tmp_path / "maxit.inp"
    text = open(os.path.join(ROOT, "inputs", "dam_joint.inp")).read()
    text = text.replace("INPUT=meshes/", "INPUT=" + os.path.join(ROOT, "inputs", "meshes") + "/")
    text = text.replace("*CONTACT PAIR", "*CONTACT CONTROLS, MAXIT=2147483647\n*CONTACT PAIR", 1)
    deck.write_text(text)
    code, err, rss = run(exe, deck, tmp_path / "out")
    assert code == 1, err
    assert "maxit.inp:" in err and len(err) < 1024
    assert rss < MAX_RSS_KB


def test_long_name_quoted_briefly(exe, tmp_path):
    """A 60 000-character interaction name (within the line limit) quoted in a message:
    the message line is cut at 400 characters (src/text.f90, cap_lines)."""
    text = open(os.path.join(ROOT, "tests", "integration", "decks", "sliding_rebuild.inp")).read()
    deck = tmp_path / "longname.inp"
    deck.write_text(text.replace("*CONTACT PAIR, INTERACTION=SLIDE", "*CONTACT PAIR, INTERACTION=SLIDE" + "Y" * 60000, 1))
    code, err, _ = run(exe, deck, tmp_path / "out")
    assert_refused(code, err, 1, "longname.inp")
    assert "more characters)" in err
