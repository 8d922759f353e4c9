"""vc-plot: contour pictures of vemcontact results.

  python -m vctools.plot RESULT [--field F ...] [--step K] [--deformed auto|SCALE]
                         [--units TEXT] [-o DIR] [--format png|pdf]

RESULT is a .vtu file or a .pvd collection (default: its last step).  Fields:
MISES, S1, S3, U (magnitude), U:x, U:y, S:xx, S:yy, S:zz, S:xy; prefix cell: for
element values (cell:S:yy).  One picture per field, named JOB_FIELD.png.
"""
from __future__ import annotations

import argparse
import os
import sys

from .results import ResultError, check_complete, contact_file, read_contact_points, read_vtu, step_files
from .contour import plot


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="vc-plot", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("result", help=".vtu file or .pvd collection")
    p.add_argument("--field", action="append", help="field to draw (repeatable; default U:x U:y S1 S3 MISES)")
    p.add_argument("--step", type=int, default=0, help="step of a .pvd, 1-based (default: last)")
    p.add_argument("--deformed", default=None, help="draw on the deformed shape: auto or a scale factor")
    p.add_argument("--units", default="", metavar="LENGTH[,STRESS]",
                   help="units on the colour bar: displacement fields take the first, stresses the second (e.g. m,Pa)")
    p.add_argument("--line", action="append", default=[], metavar="X1,Y1,X2,Y2[,...]",
                   help="polyline drawn over the picture, e.g. a joint (repeatable; undeformed coordinates)")
    p.add_argument("-o", "--output", default=None, help="folder for the pictures (default: the result's)")
    p.add_argument("--format", choices=["png", "pdf"], default="png")
    p.add_argument("--incomplete", action="store_true",
                   help="plot the steps of a run that did not finish (refused by default)")
    a = p.parse_args(argv)
    try:
        files = step_files(a.result)
        if not a.incomplete:
            check_complete(a.result)
        if a.step < 0 or a.step > len(files):
            raise ResultError(f"{a.result}: has {len(files)} steps, no step {a.step}")
        vtu = files[a.step - 1] if a.step else files[-1]
        res = read_vtu(vtu)
        deformed = None
        if a.deformed is not None:
            deformed = "auto" if a.deformed == "auto" else float(a.deformed)
        cfile = contact_file(a.result, vtu)
        contact = read_contact_points(cfile) if cfile and os.path.exists(cfile) else None
        outdir = a.output or os.path.dirname(os.path.abspath(vtu))
        os.makedirs(outdir, exist_ok=True)
        job = os.path.splitext(os.path.basename(vtu))[0]
        lines = []
        for text in a.line:
            try:
                v = [float(t) for t in text.split(",")]
            except ValueError:
                raise ResultError(f"--line {text}: expected numbers x1,y1,x2,y2,...") from None
            if len(v) < 4 or len(v) % 2:
                raise ResultError(f"--line {text}: expected an even number (at least 4) of coordinates")
            lines.append([v[i:i + 2] for i in range(0, len(v), 2)])
        for f in a.field or ["U:x", "U:y", "S1", "S3", "MISES"]:
            out = os.path.join(outdir, f"{job}_{f.replace(':', '_')}.{a.format}")
            units = a.units.split(",")
            unit = units[0] if f.removeprefix("cell:").startswith("U") or len(units) == 1 else units[1]
            plot(res, f, out, deformed=deformed, units=unit, lines=lines, contact=contact)
            print(out)
    except ResultError as exc:
        print(f"vc-plot: error: {exc}", file=sys.stderr)
        return 1
    except ValueError as exc:
        print(f"vc-plot: error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
