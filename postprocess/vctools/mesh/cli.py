"""Command line: vc-mesh {scene,paper,gmsh,bench} ..."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .errors import MeshError

HERE = Path(__file__).resolve()
SCENES = HERE.parents[2] / "scenes"                  # postprocess/scenes
OUTDIR = HERE.parents[3] / "inputs" / "meshes"       # inputs/meshes of the repository


def _parser():
    p = argparse.ArgumentParser(
        prog="vc-mesh",
        description="Meshes for vemcontact: Voronoi bodies with joints split into contact faces, "
                    "structured quad/triangle meshes, Gmsh import.  Writes deck text "
                    "(*NODE, *ELEMENT, *NSET, *ELSET, *SURFACE) to *INCLUDE, with a quality report.")
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("scene", help="mesh a scene file (TOML); every [[variant]] gives one file")
    s.add_argument("scene", help="scene file, see docs/meshing.md")
    s.add_argument("-o", "--output", help="output .inp file or directory (default: next to the scene)")
    s.add_argument("--seed", type=int, help="override [mesh] seed")
    s.add_argument("--processes", type=int, help="worker processes for large Voronoi meshes (default: CPUs)")
    s.add_argument("-v", "--verbose", action="store_true", help="print the Lloyd energy of each iteration")
    s = sub.add_parser("paper", help="regenerate the meshes of the paper's four examples")
    s.add_argument("--scenes", default=str(SCENES), help=f"scene directory (default {SCENES}): its ex*.toml")
    s.add_argument("-o", "--output", default=str(OUTDIR), help=f"output directory (default {OUTDIR})")
    s = sub.add_parser("gmsh", help="convert a Gmsh .msh mesh (2.2 or 4.1, ASCII or binary)")
    s.add_argument("msh")
    s.add_argument("-o", "--output", help="output .inp (default: next to the .msh)")
    s.add_argument("--formulation", default="vem", choices=["vem", "fem"])
    s.add_argument("--plane", default="strain", choices=["strain", "stress"])
    s = sub.add_parser("bench", help="cells per second of Voronoi meshing with Lloyd iterations")
    s.add_argument("--cells", type=float, nargs="+", default=[1e3, 1e4, 1e5, 1e6])
    s.add_argument("--lloyd", type=int, default=10)
    s.add_argument("--processes", type=int)
    return p


def main(argv=None):
    args = _parser().parse_args(argv)
    try:
        if args.cmd == "scene":
            from .scene import mesh_scene_file
            mesh_scene_file(args.scene, args.output, seed=args.seed, verbose=args.verbose,
                            processes=args.processes)
        elif args.cmd == "paper":
            from .scene import mesh_scene_file
            # the paper's examples are ex1..ex4; the other scenes (the sliding-safety
            # dams) are meshed one by one with `vc-mesh scene`
            files = sorted(Path(args.scenes).glob("ex*.toml"))
            if not files:
                raise MeshError(f"no scene files in {args.scenes}")
            t0 = time.time()
            n = 0
            for f in files:
                n += len(mesh_scene_file(f, args.output + "/"))
            print(f"{n} meshes written to {args.output} in {time.time() - t0:.1f} s")
        elif args.cmd == "gmsh":
            from .deck import write_deck
            from .gmsh import read_msh
            from .scene import header
            form, plane = args.formulation, args.plane
            from .scene import _etype
            et = _etype(form, plane, args.msh)
            m = read_msh(args.msh, et)
            out = args.output or str(Path(args.msh).with_suffix(".inp"))
            hdr = header(m, Path(args.msh).name)
            write_deck(m, out, hdr)
            print(out + ":")
            for line in hdr[2:]:
                print("  " + line)
        elif args.cmd == "bench":
            from .bench import run
            run(args.cells, args.lloyd, args.processes)
    except MeshError as exc:
        print(f"vc-mesh: error: {exc}", file=sys.stderr)
        return 2
    return 0
