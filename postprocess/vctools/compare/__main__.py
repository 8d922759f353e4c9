"""vc-compare: compare a vemcontact HDF5 result with a reference, field by field and step by step.

  python -m vctools.compare RESULT.h5 REFERENCE.h5 [--rtol R] [--atol-u A] [--atol-s A]
                            [--fields U,S_element,S_node,COPEN,CPRESS,STATUS] [--steps 1,2] [--top N]

A value passes when |value - reference| <= atol + rtol*|reference|.  By default
rtol is 1e-8 and atol is 1e-8 times the reference's (all steps) displacement
scale max(|U|, |COPEN|) for U and COPEN, and 1e-8 times its stress scale
max(|S_element|, |CPRESS|) for S_element and S_node.  CPRESS, the penalty K times
the overclosure, gets max(stress atol, K x COPEN atol), K = CPRESS/-COPEN of the
reference's closed nodes.  --atol-u and --atol-s replace these by absolute values
(--atol-s then applies to CPRESS as well).
STATUS, the steps present, the contact pairs and their slave nodes, and the
mesh (node ids and coordinates, connectivity, element ids, materials, types)
must match; any mesh difference is reported as 'mesh changed'.

Prints the N worst differences (step, field, component, node/element/slave node
user id, its coordinates, value, reference, absolute and relative difference)
and a summary line 'compare: OK (...)' or 'compare: MISMATCH in ...'.
Exit status: 0 match, 1 mismatch, 2 unreadable input or a requested field or
step that does not exist (one line 'vc-compare: error: FILE: what').
"""
from __future__ import annotations

import argparse
import sys

from ..cli import entry
from .core import ATOL_FACTOR, FIELDS, RTOL, Tolerances, compare, parse_fields, parse_steps
from .h5file import CompareError, read_results

PROG = "vc-compare"


def _nonneg_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not v >= 0:
        raise argparse.ArgumentTypeError(f"'{text}' must be a number >= 0")
    return v


def _count(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if v < 0:
        raise argparse.ArgumentTypeError(f"'{text}' must be >= 0")
    return v


def _g(v: float) -> str:
    return f"{v:.6g}"


def _e(v: float) -> str:
    return f"{v:.3e}" if v == v and abs(v) != float("inf") else str(v)


def format_report(report, tol: Tolerances, top: int) -> list:
    lines = [f"{PROG}: {report.result} against {report.reference}"]
    steps = ", ".join(str(s) for s in report.steps) or "none"
    lines.append(f"steps {steps}; fields {', '.join(report.fields)}; rtol {tol.rtol:g}")
    t = report.applied
    if t is not None:
        u = f"{t.atol_u:.3g}" + ("" if tol.atol_u is not None else f" = {tol.factor:g} x max|U, COPEN| {t.scale_u:.4g}")
        s = f"{t.atol_s:.3g}" + ("" if tol.atol_s is not None else f" = {tol.factor:g} x max|S_element, CPRESS| {t.scale_s:.4g}")
        lines.append(f"atol U, COPEN: {u}")
        lines.append(f"atol S_element, S_node: {s}")
        for name, a in t.atol_p.items():
            why = "" if tol.atol_s is not None else (
                f" = max(stress atol, penalty {t.penalty[name]:.4g} x COPEN atol)" if t.penalty[name] else
                " (no closed node in the reference: the stress atol)")
            lines.append(f"atol CPRESS {name}: {a:.3g}{why}")
    for p in report.notes:
        lines.append(f"note: {p}")
    for p in report.problems:
        lines.append(f"MISMATCH: {p}")
    if top > 0 and report.worst:
        lines.append(f"worst {len(report.worst)} differences (ratio = |value - reference| / "
                     f"(atol + rtol*|reference|); above 1 fails):")
        head = (f"{'step':>4}  {'field':<9} {'comp':<4} {'entity':<20} {'x':>12} {'y':>12} "
                f"{'value':>14} {'reference':>14} {'abs diff':>10} {'rel diff':>10} {'ratio':>10}")
        lines.append(head)
        for e in report.worst:
            lines.append(f"{e.step:>4}  {e.field:<9} {e.comp or '-':<4} {e.entity:<20} {_g(e.x):>12} {_g(e.y):>12} "
                         f"{e.value:>14.7e} {e.reference:>14.7e} {_e(e.diff):>10} {_e(e.rel):>10} {_e(e.ratio):>10}")
    elif top > 0 and not report.problems:
        lines.append("no value differs from the reference")
    if report.ok:
        lines.append(f"compare: OK ({report.compared} values within tolerance)")
    else:
        mesh = [p for p in report.problems if p.startswith("mesh changed")]
        items = [f"mesh ({mesh[0]}" + (f"; {len(mesh) - 1} more" if len(mesh) > 1 else "") + ")"] if mesh else []
        items += [p for p in report.problems if not p.startswith("mesh changed") and not p.startswith("fields not")]
        items += [f"{label} ({nfail} of {n} values)" for label, nfail, n in report.mismatched]
        shown = "; ".join(items[:6]) + (f"; and {len(items) - 6} more" if len(items) > 6 else "")
        lines.append(f"compare: MISMATCH in {shown}")
    return lines


@entry("vc-compare")
def main(argv=None) -> int:
    doc = __doc__.split("\n\n")
    p = argparse.ArgumentParser(prog=PROG, description=doc[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n\n".join(doc[2:]))
    p.add_argument("result", help="the run's HDF5 file (JOB.h5)")
    p.add_argument("reference", help="the reference HDF5 file")
    p.add_argument("--rtol", type=_nonneg_float, default=RTOL, help=f"relative tolerance (default {RTOL:g})")
    p.add_argument("--atol-u", type=_nonneg_float, default=None, metavar="A",
                   help=f"absolute tolerance for U and COPEN in the deck's length unit "
                        f"(default: {ATOL_FACTOR:g} x max(|U|, |COPEN|) of the reference)")
    p.add_argument("--atol-s", type=_nonneg_float, default=None, metavar="A",
                   help=f"absolute tolerance for S_element, S_node and CPRESS in the deck's stress unit "
                        f"(default: {ATOL_FACTOR:g} x max(|S_element|, |CPRESS|) of the reference; "
                        f"CPRESS: at least the penalty times the U tolerance)")
    p.add_argument("--fields", default=None, metavar="LIST",
                   help=f"comma-separated fields to compare (default all: {','.join(FIELDS)})")
    p.add_argument("--steps", default=None, metavar="LIST",
                   help="comma-separated step numbers to compare (default: every step; a step "
                        "missing from either file is then a mismatch)")
    p.add_argument("--top", type=_count, default=10, metavar="N", help="rows in the table of worst differences (default 10)")
    a = p.parse_args(argv)
    tol = Tolerances(rtol=a.rtol, atol_u=a.atol_u, atol_s=a.atol_s)
    try:
        fields = parse_fields(a.fields) if a.fields is not None else None
        steps = parse_steps(a.steps)
        res = read_results(a.result)
        ref = read_results(a.reference)
        report = compare(res, ref, tol, fields=fields, steps=steps, top=a.top)
    except CompareError as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{PROG}: error: {a.result}: too large to compare in memory", file=sys.stderr)
        return 2
    print("\n".join(format_report(report, tol, a.top)))
    return 0 if report.ok else 1


if __name__ == "__main__":
    sys.exit(main())
