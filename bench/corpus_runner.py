"""Bad-input corpus and numeric fuzz mutants run through the Debug build (runtime
checks and FP traps on): every run must end with an exit status of the program
(0 .. 5) and no signal, trap or backtrace (issue 25, "every range check before first
use").

    python bench/corpus_runner.py [--exe build-debug/vemcontact] [--mutants N] [--seed S]
                                  [--quick] [--keep DIR]

The corpus: every deck of tests/integration/decks (the bad decks of the suite) and
of inputs/, as written, plus N mutants of each (default 6; fixed seed): a mutant
changes 1 to 3 numbers of the deck's own lines (the *INCLUDE'd meshes are kept) to
an extreme of the documented ranges or beyond it (times 10^k for k in -320..320,
0, a sign flip, NaN, 1e309, 2147483647, -1, ...).  A finding is a run that ends with
a signal, a status outside 0..5, "Backtrace" or "Floating-point exception" on
stderr, or no end within the time limit; each is printed with its deck (kept
under --keep) and the first lines of stderr.  --quick: only the small decks (for
the test suite).  Exit status 1 when anything was found.
"""
from __future__ import annotations

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIMIT_S = 120.0
QUICK = ["minimal_polygon.inp", "sliding_rebuild.inp", "example1_cantilever.inp", "block_selfweight.inp",
         "fails_in_step2.inp", "err_range_product.inp"]
NUMBER = re.compile(r"(?<![A-Za-z_])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?")
REAL_EXTREMES = [-320, -310, -300, -200, -150, -131, -129, -100, 100, 129, 131, 150, 200, 300, 308]
SPECIAL = ["0", "0.0", "nan", "inf", "1e309", "-1e309", "2147483647", "2147483648", "-1", "4.9e-324"]


def corpus_decks(quick: bool) -> list[Path]:
    decks = sorted((ROOT / "tests" / "integration" / "decks").glob("*.inp")) + sorted((ROOT / "inputs").glob("*.inp"))
    if quick:
        decks = [d for d in decks if d.name in QUICK]
    return decks


def absolute_includes(text: str, folder: Path) -> str:
    """*INCLUDE paths made absolute, so that a mutant can live elsewhere."""
    def fix(m):
        p = m.group(2).strip()
        return m.group(1) + (p if os.path.isabs(p) else str(folder / p))
    return re.sub(r"(?im)^(\*INCLUDE\s*,\s*INPUT\s*=\s*)(.*)$", fix, text)


def mutate(text: str, rng: random.Random) -> tuple[str, list[str]]:
    """1 to 3 numbers of data lines changed; returns the text and what was changed."""
    lines = text.split("\n")
    spots = [(i, m) for i, line in enumerate(lines) if line and not line.startswith("*")
             for m in NUMBER.finditer(line)]
    if not spots:
        return text, []
    changes = []
    for _ in range(rng.randint(1, 3)):
        i, m = rng.choice(spots)
        old = m.group(0)
        r = rng.random()
        if r < 0.55:
            try:
                value = float(old.replace("d", "e").replace("D", "e"))
            except ValueError:
                continue
            k = rng.choice(REAL_EXTREMES)
            new = f"{'-' if value < 0 else ''}{rng.choice([1, 1.5, 9.99])}e{k}"
        elif r < 0.7:
            new = old[1:] if old.startswith("-") else "-" + old
        else:
            new = rng.choice(SPECIAL)
        line = lines[i]
        # the match's span refers to the unchanged line: change it only if still there
        if line[m.start():m.end()] != old:
            continue
        lines[i] = line[:m.start()] + new + line[m.end():]
        changes.append(f"line {i + 1}: {old} -> {new}")
    return "\n".join(lines), changes


def finding(rc: int | None, err: str) -> str | None:
    if rc is None:
        return f"no end within {LIMIT_S:.0f} s"
    if rc < 0:
        return f"signal {-rc}"
    if rc > 5:
        return f"exit status {rc}"
    for word in ("Backtrace", "Floating-point exception", "Program received signal", "Fortran runtime error"):
        if word in err:
            return word
    return None


def run(exe: str, deck: Path, out: Path) -> tuple[int | None, str]:
    try:
        p = subprocess.run([exe, "-q", "-o", str(out), str(deck)], capture_output=True, text=True,
                           timeout=LIMIT_S, check=False, errors="replace")
    except subprocess.TimeoutExpired:
        return None, ""
    return p.returncode, p.stderr


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", default=str(ROOT / "build-debug" / "vemcontact"))
    ap.add_argument("--mutants", type=int, default=6, help="mutants per deck (default 6)")
    ap.add_argument("--seed", type=int, default=25)
    ap.add_argument("--quick", action="store_true", help="the small decks only (the test suite's subset)")
    ap.add_argument("--keep", default=None, help="folder for the decks of the findings")
    a = ap.parse_args(argv)
    rng = random.Random(a.seed)
    work = Path(tempfile.mkdtemp(prefix="vc-corpus-"))
    keep = Path(a.keep) if a.keep else work / "findings"
    runs = 0
    found = []
    t0 = time.perf_counter()
    for deck in corpus_decks(a.quick):
        text = absolute_includes(deck.read_text(errors="replace"), deck.parent)
        cases = [(deck.stem, text, ["as written"])]
        for k in range(a.mutants):
            mtext, changes = mutate(text, rng)
            if changes:
                cases.append((f"{deck.stem}_m{k}", mtext, changes))
        for name, body, changes in cases:
            path = work / f"{name}.inp"
            path.write_text(body)
            rc, err = run(a.exe, path, work / "out" / name)
            runs += 1
            why = finding(rc, err)
            if why:
                keep.mkdir(parents=True, exist_ok=True)
                (keep / path.name).write_text(body)
                found.append((name, why, changes, err))
                print(f"FINDING {name}: {why}; {'; '.join(changes)}\n    " +
                      "\n    ".join(err.strip().splitlines()[:6]), flush=True)
    print(f"{runs} runs ({'quick' if a.quick else 'full'} corpus, seed {a.seed}) in "
          f"{time.perf_counter() - t0:.0f} s: {len(found)} findings" + (f", decks in {keep}" if found else ""))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
