"""What every vctools command line has in common: one-line errors and documented exit
statuses, as the solver has (README, "Python tools").

`entry(prog)` wraps a console entry point `main(argv=None) -> int`: whatever escapes
it becomes one line on stderr and a non-zero status instead of a traceback:

- 0 success; the command's own statuses for the errors it reports itself (bad input,
  a result it refuses);
- 1 a file that cannot be read or written (OSError: missing, unreadable, a folder, a
  full disk) or a malformed input file (TOML, XML, ...);
- 2 a bad command line (argparse's usage line and message);
- 5 an internal error (a bug): its type and message on one line; the environment
  variable VCTOOLS_TRACEBACK=1 shows the traceback instead;
- 130 interrupted (Ctrl-C).

`positive_int` is the argparse type of counts and 1-based indices (steps, pairs).
"""
from __future__ import annotations

import argparse
import functools
import os
import sys

STATUS_FILE = 1
STATUS_INTERNAL = 5
STATUS_INTERRUPTED = 130


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def entry(prog: str):
    """Decorator: `main` never ends in a traceback (see the module's docstring)."""
    def wrap(main):
        @functools.wraps(main)
        def run(argv=None) -> int:
            try:
                return int(main(argv) or 0)
            except KeyboardInterrupt:
                print(f"{prog}: interrupted", file=sys.stderr)
                return STATUS_INTERRUPTED
            except OSError as exc:
                where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
                reason = exc.strerror or _one_line(exc)
                print(f"{prog}: error: {where}{reason}", file=sys.stderr)
                return STATUS_FILE
            except Exception as exc:
                if os.environ.get("VCTOOLS_TRACEBACK"):
                    raise
                name = type(exc).__name__
                if name in ("TOMLDecodeError", "ParseError", "JSONDecodeError", "UnicodeDecodeError"):
                    print(f"{prog}: error: malformed input file: {_one_line(exc)}", file=sys.stderr)
                    return STATUS_FILE
                print(f"{prog}: internal error: {name}: {_one_line(exc)} "
                      f"(VCTOOLS_TRACEBACK=1 shows where)", file=sys.stderr)
                return STATUS_INTERNAL
        return run
    return wrap


def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {text!r}")
    return value
