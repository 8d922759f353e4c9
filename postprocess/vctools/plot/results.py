"""Reading vemcontact's .vtu/.pvd results into plain numpy arrays.

Errors are raised as ResultError with a one-line message naming the file and
what is missing; the command-line front end prints it and exits non-zero.
"""
from __future__ import annotations

import contextlib
import io
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np


class ResultError(Exception):
    """A result file that is missing, unreadable or lacks what was asked for."""


@dataclass
class PolyResult:
    points: np.ndarray            # (npoints, 2)
    polygons: list                # list of int arrays (0-based point indices), one per cell
    point_data: dict              # name -> (npoints,) or (npoints, k)
    cell_data: dict               # name -> (ncells,) or (ncells, k)
    path: str


def h5_path(path: str) -> str:
    """The JOB.h5 that `path` names: the file itself, or the one .h5 file of a run folder."""
    if os.path.isdir(path):
        h5s = sorted(f for f in os.listdir(path) if f.endswith(".h5"))
        if len(h5s) != 1:
            raise ResultError(f"{path}: expected one JOB.h5 in the folder, found {len(h5s)}: give the file")
        path = os.path.join(path, h5s[0])
    if not os.path.isfile(path):
        raise ResultError(f"{path}: no such file")
    return path


def job_of(path: str) -> str | None:
    """The job of a vemcontact .pvd (JOB.pvd) or .vtu (JOB_NNNN.vtu, JOB_contact_NNNN.vtu)."""
    base = os.path.basename(path)
    if base.endswith(".pvd"):
        return base[:-4]
    m = re.fullmatch(r"(.+?)(_contact)?_(\d+)\.vtu", base)
    return m.group(1) if m else None


def check_complete(path: str) -> None:
    """Refuse the results of a job whose run did not finish (docs/output-format.md):
    its JOB.lock exists (written by a vemcontact that marks completion) and its
    JOB.h5 is missing or has the root attribute complete = 0."""
    job = job_of(path)
    if job is None:
        return
    folder = os.path.dirname(path)
    if not os.path.exists(os.path.join(folder, job + ".lock")):
        return
    h5 = os.path.join(folder, job + ".h5")
    hint = "see its log and rerun, or give --incomplete to plot the steps written"
    if not os.path.exists(h5):
        raise ResultError(f"{path}: incomplete results: {h5} is missing (the run of {job} is still going, "
                          f"was killed or could not write it); {hint}")
    import h5py

    try:
        with h5py.File(h5, "r") as f:
            complete = int(np.asarray(f.attrs.get("complete", 1)).reshape(-1)[0])
            signo = int(np.asarray(f.attrs.get("interrupted", 0)).reshape(-1)[0])
    except (OSError, KeyError, ValueError) as exc:
        raise ResultError(f"{path}: {h5} cannot be read ({' '.join(str(exc).split())}); {hint}") from None
    if complete != 1:
        why = f"was interrupted by signal {signo}" if signo else "stopped with an error"
        raise ResultError(f"{path}: incomplete results: the run of {job} {why} "
                          f"({h5} has complete = 0); {hint}")


def step_files(path: str) -> list[str]:
    """The .vtu files of a .pvd collection in order, or [path] for a .vtu."""
    if not os.path.exists(path):
        raise ResultError(f"{path}: no such file")
    if not path.endswith(".pvd"):
        return [path]
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise ResultError(f"{path}: not a readable .pvd collection ({exc})") from None
    base = os.path.dirname(path)
    # part 0 is the mesh; other parts (1: the contact points) are not steps
    files = [os.path.join(base, ds.get("file", "")) for ds in root.iter("DataSet") if ds.get("part", "0") == "0"]
    if not files:
        raise ResultError(f"{path}: the collection lists no steps")
    return files


def contact_file(pvd_path: str, step_file: str) -> str | None:
    """The contact point set (part 1) written for the same time step as `step_file`."""
    if not pvd_path.endswith(".pvd"):
        return None
    root = ET.parse(pvd_path).getroot()
    base = os.path.dirname(pvd_path)
    sets = list(root.iter("DataSet"))
    times = {os.path.join(base, ds.get("file", "")): ds.get("timestep") for ds in sets}
    t = times.get(step_file)
    for ds in sets:
        if ds.get("part", "0") == "1" and ds.get("timestep") == t:
            return os.path.join(base, ds.get("file", ""))
    return None


def read_contact_points(path: str) -> tuple[np.ndarray, np.ndarray]:
    """Slave nodes (undeformed coordinates) and their status (1 closed, 0 open)."""
    import meshio

    sink = io.StringIO()
    try:
        with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            mesh = meshio.read(path, file_format="vtu")
    except (Exception, SystemExit):
        raise ResultError(f"{path}: cannot be read as a VTK XML file (contact points)") from None
    if "STATUS" not in mesh.point_data:
        raise ResultError(f"{path}: lacks STATUS: not a vemcontact contact file")
    return np.asarray(mesh.points)[:, :2], np.asarray(mesh.point_data["STATUS"]).astype(int)


def read_vtu(path: str) -> PolyResult:
    """Read one step written by vemcontact."""
    import meshio  # imported late: the package is only needed here

    if not os.path.exists(path):
        raise ResultError(f"{path}: no such file")
    sink = io.StringIO()
    try:
        # meshio prints its own message and calls sys.exit on some bad files
        with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            mesh = meshio.read(path, file_format="vtu")
    except (Exception, SystemExit) as exc:  # meshio raises many kinds; report one line
        why = " ".join(str(exc).split()) if not isinstance(exc, SystemExit) else "truncated or not VTK XML"
        raise ResultError(f"{path}: cannot be read as a VTK XML file ({why})") from None
    polygons = []
    cell_data = {}
    blocks = []
    for block in mesh.cells:
        if not block.type.startswith("polygon") and block.type not in ("triangle", "quad", "triangle6", "quad8"):
            raise ResultError(f"{path}: cells of type {block.type} are not polygons: not a vemcontact result")
        blocks.append(block)
        data = np.asarray(block.data, dtype=np.int64)
        if block.type in ("triangle6", "quad8"):
            # corners, then side nodes -> the polygon round the boundary through the side nodes
            n = data.shape[1] // 2
            ring = np.empty_like(data)
            ring[:, 0::2], ring[:, 1::2] = data[:, :n], data[:, n:]
            data = ring
        polygons.extend(data)
    for name, arrays in mesh.cell_data.items():
        cell_data[name] = np.concatenate([np.asarray(a) for a in arrays])
    # meshio splits polygons into blocks by vertex count; cells keep the file's
    # order within each block, so reorder by ELEMENT_ID position when present
    # the labels are always written; the result fields only when the deck's output
    # requests select them (docs/output-format.md)
    if "ELEMENT_ID" not in cell_data or "NODE_ID" not in mesh.point_data:
        raise ResultError(f"{path}: lacks ELEMENT_ID/NODE_ID: not written by vemcontact")
    return PolyResult(points=np.asarray(mesh.points)[:, :2], polygons=polygons,
                      point_data=dict(mesh.point_data), cell_data=cell_data, path=path)


# the .vtu's tensors have 9 components, row by row (docs/output-format.md)
TENSOR = ["xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"]
COMPONENTS = {"U": ["x", "y", "z"], "RF": ["x", "y", "z"], "S": TENSOR, "E": TENSOR}
# the output request that writes a field (a deck with requests writes only what they select)
REQUEST = {"U": "U under *NODE FILE", "RF": "RF under *NODE FILE", "S": "S under *EL FILE",
           "S1": "S under *EL FILE", "S3": "S under *EL FILE", "MISES": "S under *EL FILE",
           "E": "E under *EL FILE"}


def field_values(res: PolyResult, spec: str) -> tuple[np.ndarray, str, str]:
    """Values of a field spec: 'MISES', 'S1', 'S3', 'U' (magnitude), 'U:x', 'S:xx',
    'cell:S:yy' (element values).  Returns (values, 'point'|'cell', label)."""
    where = "point"
    s = spec
    if s.startswith("cell:"):
        where, s = "cell", s[5:]
    name, _, comp = s.partition(":")
    data = res.point_data if where == "point" else res.cell_data
    if name not in data:
        have = ", ".join(sorted(data))
        hint = f"; the deck's output requests do not select it (add {REQUEST[name]})" if name in REQUEST else ""
        raise ResultError(f"{res.path}: no {where} field {name} (it has {have}{hint})")
    v = np.asarray(data[name], dtype=float)
    if v.ndim == 1:
        if comp:
            raise ResultError(f"{res.path}: field {name} has no components")
        return v, where, name
    names = COMPONENTS.get(name, [str(i) for i in range(v.shape[1])])
    if not comp:
        if name == "U":
            return np.linalg.norm(v[:, :2], axis=1), where, "|U|"
        raise ResultError(f"{res.path}: field {name} has components {', '.join(names)}: say which, as {name}:{names[0]}")
    if comp not in names:
        raise ResultError(f"{res.path}: field {name} has no component {comp} (it has {', '.join(names)})")
    return v[:, names.index(comp)], where, f"{name}_{comp}"


def step_label(vtu_path: str, index: int | None = None) -> str:
    """'step K, NAME' of a step file JOB_NNNN.vtu: K from the file name (or `index`),
    NAME the step's name in JOB.h5 beside it (Abaqus' *STEP, NAME=, default Step-K);
    only 'step K' when the HDF5 file or the name is not there."""
    import re

    base = os.path.basename(vtu_path)
    m = re.match(r"(?P<job>.*)_(?P<k>\d{4,})\.vtu$", base)
    if not m:
        return f"step {index}" if index else ""
    k = int(m.group("k"))
    h5 = os.path.join(os.path.dirname(vtu_path), m.group("job") + ".h5")
    name = ""
    if os.path.exists(h5):
        try:
            import h5py
            with h5py.File(h5, "r") as f:
                g = f.get(f"steps/{m.group('k')}")
                if g is not None and "name" in g.attrs:
                    name = g.attrs["name"]
                    name = name.decode() if isinstance(name, bytes) else str(name)
                    name = name.strip().strip("\x00")
        except OSError:
            name = ""
    return f"step {k}, {name}" if name else f"step {k}"
