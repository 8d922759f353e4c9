"""vc-plot: contour pictures of vemcontact results.

  python -m vctools.plot RESULT [--field F ...] [--step K] [--deformed auto|SCALE]
                         [--units LENGTH[,STRESS]] [--model-units LENGTH,STRESS]
                         [--line X1,Y1,X2,Y2 ...]
                         [--clip P] [--exclude X,Y[,R] ...] [-o DIR] [--format png|pdf]

RESULT is a .vtu file or a .pvd collection (default: its last step).  Fields:
MISES, S1, S3, U (magnitude), U:x, U:y, S:xx, S:yy, S:zz, S:xy, E:xx, E:yy, E:zz,
E:xy (tensor shear, gamma/2), RF:x, RF:y; prefix cell: for
element values (cell:S:yy).  One picture per field, named JOB_FIELD.png, titled
with the field and the step (its number and, from JOB.h5, its name); the axes
carry the length unit, the colour bar the field's unit.  --units converts: the
model's values, in --model-units (the deck's units, default m,Pa), are shown in
--units (--units mm,MPa draws the SI dam in millimetres and megapascals; reaction
forces follow as stress times length squared, strains are not converted).  --line
overlays, --exclude circles (given in the deck's undeformed coordinates) follow
the deformed shape like the field.  The colour
range can leave out a singular point (--exclude: values within R of (X, Y); R
defaults to 2 % of the model's size) and clip at a percentile (--clip 99: from
the 1st to the 99th percentile); the bar then says so and shows arrows for the
values beyond it.
When the displacements are zero (a geostatic step) the default is S1, S3, MISES,
S:yy; a field that is the same everywhere is drawn in one colour with its value in
the title, without a colour bar.
A deck with output requests writes only the fields they select: the default
pictures are then those of the step's fields, with a note naming the ones left out,
and a field (or --deformed, which needs U) the step lacks is an error naming the
request to add.
"""
from __future__ import annotations

import argparse
import os
import sys

import numpy as np

from ..cli import entry, positive_int
from .results import ResultError, check_complete, contact_file, read_contact_points, read_vtu, step_files, step_label
from .contour import field_unit, plot, unit_factors


@entry("vc-plot")
def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="vc-plot", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("result", help=".vtu file or .pvd collection")
    p.add_argument("--field", action="append", help="field to draw (repeatable; default U:x U:y S1 S3 MISES)")
    p.add_argument("--step", type=positive_int, default=None, help="step of a .pvd, 1-based (default: last)")
    p.add_argument("--deformed", default=None, help="draw on the deformed shape: auto or a scale factor")
    p.add_argument("--units", default="", metavar="LENGTH[,STRESS]",
                   help="units to show, converted from --model-units: lengths and displacements in the first, "
                        "stresses in the second (e.g. mm,MPa)")
    p.add_argument("--model-units", default="m,Pa", metavar="LENGTH,STRESS",
                   help="the units of the deck (default m,Pa; e.g. mm,MPa for a deck in mm, N, MPa)")
    p.add_argument("--line", action="append", default=[], metavar="X1,Y1,X2,Y2[,...]",
                   help="polyline drawn over the picture, e.g. a joint (repeatable; undeformed coordinates, "
                        "drawn on the deformed shape with the field)")
    p.add_argument("--clip", type=float, default=None, metavar="P",
                   help="colour range from the (100-P)th to the Pth percentile, e.g. 99")
    p.add_argument("--exclude", action="append", default=[], metavar="X,Y[,R]",
                   help="values within R of (X, Y) do not set the colour range (repeatable), e.g. a joint tip")
    p.add_argument("-o", "--output", default=None, help="folder for the pictures (default: the result's)")
    p.add_argument("--format", choices=["png", "pdf"], default="png")
    p.add_argument("--incomplete", action="store_true",
                   help="plot the steps of a run that did not finish (refused by default)")
    a = p.parse_args(argv)
    try:
        files = step_files(a.result)
        if not a.incomplete:
            check_complete(a.result)
        if a.step is not None and a.step > len(files):
            raise ResultError(f"{a.result}: has {len(files)} steps, no step {a.step}")
        vtu = files[a.step - 1] if a.step else files[-1]
        res = read_vtu(vtu)
        deformed = None
        if a.deformed is not None:
            if "U" not in res.point_data:
                raise ResultError(f"{vtu}: --deformed needs U, which the deck's output requests do not select "
                                  f"(add U under *NODE FILE)")
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
        size = float(max(res.points.max(axis=0) - res.points.min(axis=0)))
        exclude = []
        for text in a.exclude:
            try:
                v = [float(t) for t in text.split(",")]
            except ValueError:
                raise ResultError(f"--exclude {text}: expected numbers X,Y[,R]") from None
            if len(v) not in (2, 3) or (len(v) == 3 and v[2] <= 0):
                raise ResultError(f"--exclude {text}: expected X,Y or X,Y,R with R > 0")
            exclude.append((v[0], v[1], v[2] if len(v) == 3 else 0.02 * size))
        step = step_label(vtu, a.step or len(files))
        fields = a.field
        if not fields:
            fields = ["U:x", "U:y", "S1", "S3", "MISES"]
            if "U" in res.point_data and not np.asarray(res.point_data["U"]).any():
                # a geostatic step reports zero displacements by construction: its
                # picture is the stress state
                fields = ["S1", "S3", "MISES", "S:yy"]
                print(f"vc-plot: note: {vtu}: displacements are zero (a geostatic step): drawing stresses only",
                      file=sys.stderr)
            # a deck with output requests writes only the fields they select
            have = [f for f in fields if f.split(":")[0] in res.point_data]
            if len(have) < len(fields):
                left = list(dict.fromkeys(f.split(":")[0] for f in fields if f not in have))
                print(f"vc-plot: note: {vtu}: no {', '.join(left)} (not selected by the deck's output requests)",
                      file=sys.stderr)
            fields = have or [f for f in ("RF:x", "RF:y", "E:xx", "E:yy") if f.split(":")[0] in res.point_data]
            if not fields:
                raise ResultError(f"{vtu}: no result field to draw: the deck's output requests select none "
                                  f"(*NODE FILE U, *EL FILE S)")
        lf, sf, lunit, sunit = unit_factors(a.units, a.model_units) if a.units else (1.0, 1.0, "", "")
        for f in fields:
            out = os.path.join(outdir, f"{job}_{f.replace(':', '_')}.{a.format}")
            plot(res, f, out, deformed=deformed, units=field_unit(f, lunit, sunit), lines=lines, contact=contact,
                 length_unit=lunit, step=step, clip=a.clip, exclude=exclude, length_factor=lf, stress_factor=sf)
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
