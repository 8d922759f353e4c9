"""Progress of long meshing runs on a terminal: one self-overwriting line on stderr.

Shown only when stderr is a terminal and the work has run for more than `after`
seconds, so that short runs, pipes, logs and tests see nothing.
"""
from __future__ import annotations

import sys
import time


class Progress:
    def __init__(self, what: str, after: float = 2.0, stream=None):
        self.what = what
        self.after = after
        self.stream = stream if stream is not None else sys.stderr
        self.t0 = time.time()
        self.shown = False

    def active(self) -> bool:
        isatty = getattr(self.stream, "isatty", None)
        return bool(isatty and isatty()) and time.time() - self.t0 > self.after

    def update(self, done: int, total: int) -> None:
        if not self.active():
            return
        self.stream.write(f"\r  {self.what} {done}/{total} ({time.time() - self.t0:.0f} s)")
        self.stream.flush()
        self.shown = True

    def done(self) -> None:
        if self.shown:
            self.stream.write("\n")
            self.stream.flush()
            self.shown = False
