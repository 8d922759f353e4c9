"""Reading a vemcontact HDF5 results file (docs/output-format.md) into numpy arrays.

Every failure (no such file, not HDF5, truncated, not vemcontact's, a dataset
missing or unreadable) becomes a CompareError with a one-line message that
names the file and what is wrong; the command line prints it and exits 2.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

FORMAT = "vemcontact-results"
FORMAT_VERSION = 1
MESH_DATASETS = ("coordinates", "node_ids", "element_offsets", "element_connectivity",
                 "element_ids", "element_material", "element_type", "element_formulation")
STEP_FIELDS = ("U", "S_element", "S_node")
CONTACT_FIELDS = ("COPEN", "CPRESS", "STATUS")
CONTACT_DATASETS = ("node_ids", "coordinates") + CONTACT_FIELDS


class CompareError(Exception):
    """Input that cannot be compared: the message is one line, starting with the file."""


@dataclass
class Pair:
    name: str                       # pair_K
    data: dict                      # node_ids, coordinates, COPEN, CPRESS, STATUS (what is present)


@dataclass
class Step:
    key: str                        # the group name, e.g. "0001"
    number: int
    name: str
    time: float | None
    fields: dict                    # U, S_element, S_node (what is present)
    pairs: dict = field(default_factory=dict)   # pair_K -> Pair


@dataclass
class Results:
    path: str
    mesh: dict                      # MESH_DATASETS -> array
    steps: dict                     # number -> Step

    def has_field(self, name: str) -> bool:
        for s in self.steps.values():
            if name in s.fields or any(name in p.data for p in s.pairs.values()):
                return True
        return False


def _text(v) -> str:
    if isinstance(v, bytes):
        return v.decode("ascii", "replace").rstrip("\0 ")
    if isinstance(v, np.ndarray) and v.size == 1:
        return _text(v.reshape(-1)[0])
    return str(v)


def _one_line(exc: Exception) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def read_results(path: str) -> Results:
    """Read the whole file (meshes and steps of vemcontact runs are small)."""
    import h5py  # late: only needed here

    if not os.path.exists(path):
        raise CompareError(f"{path}: no such file")
    if os.path.isdir(path):
        raise CompareError(f"{path}: is a directory, not a results file")
    try:
        is_hdf5 = h5py.is_hdf5(path)
    except OSError as exc:
        raise CompareError(f"{path}: cannot be read ({_one_line(exc)})") from None
    if not is_hdf5:
        raise CompareError(f"{path}: not an HDF5 file (expected a vemcontact .h5 results file)")
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        why = _one_line(exc)
        what = "truncated HDF5 file" if "truncated" in why else "unreadable HDF5 file"
        raise CompareError(f"{path}: {what} ({why})") from None
    try:
        with f:
            return _read_open(path, f)
    except CompareError:
        raise
    except (OSError, KeyError, ValueError, TypeError, RuntimeError) as exc:
        # h5py reports a damaged or truncated file when a dataset is read
        raise CompareError(f"{path}: damaged or truncated HDF5 file ({_one_line(exc)})") from None


def _read_open(path, f) -> Results:
    import h5py

    fmt = _text(f.attrs["format"]) if "format" in f.attrs else None
    if fmt != FORMAT:
        what = "no root attribute 'format'" if fmt is None else f"root attribute format is '{fmt}'"
        raise CompareError(f"{path}: not a vemcontact results file ({what}, expected '{FORMAT}')")
    version = int(np.asarray(f.attrs.get("format_version", -1)).reshape(-1)[0])
    if version != FORMAT_VERSION:
        raise CompareError(f"{path}: format_version {version} is not supported (this tool reads {FORMAT_VERSION})")
    # the completion marker (docs/output-format.md); files of older writers have none
    if "complete" in f.attrs and int(np.asarray(f.attrs["complete"]).reshape(-1)[0]) != 1:
        signo = int(np.asarray(f.attrs.get("interrupted", 0)).reshape(-1)[0])
        why = f"was interrupted by signal {signo}" if signo else "stopped with an error"
        raise CompareError(f"{path}: incomplete results: the run that wrote it {why} "
                           "(root attribute complete = 0); see its log and rerun the job")

    mesh = {}
    for name in MESH_DATASETS:
        obj = f.get(f"mesh/{name}")
        if not isinstance(obj, h5py.Dataset):
            raise CompareError(f"{path}: no dataset /mesh/{name}: incomplete vemcontact results file")
        mesh[name] = obj[()]

    steps = {}
    grp = f.get("steps")
    if not isinstance(grp, h5py.Group):
        raise CompareError(f"{path}: no group /steps: incomplete vemcontact results file")
    for key in grp:
        g = grp[key]
        if not isinstance(g, h5py.Group) or not key.isdigit():
            raise CompareError(f"{path}: /steps/{key} is not a step group")
        name = _text(g.attrs["name"]) if "name" in g.attrs else ""
        time = float(np.asarray(g.attrs["time"]).reshape(-1)[0]) if "time" in g.attrs else None
        fields = {n: g[n][()] for n in STEP_FIELDS if isinstance(g.get(n), h5py.Dataset)}
        pairs = {}
        c = g.get("contact")
        if isinstance(c, h5py.Group):
            for pk in c:
                pg = c[pk]
                # pair_K groups; /contact/iterations holds the iteration records, which
                # depend on the path to the answer, not on the answer: not compared
                if isinstance(pg, h5py.Group) and pk.startswith("pair_"):
                    pairs[pk] = Pair(pk, {n: pg[n][()] for n in CONTACT_DATASETS
                                          if isinstance(pg.get(n), h5py.Dataset)})
        number = int(key)
        steps[number] = Step(key, number, name, time, fields, pairs)
    return Results(path, mesh, dict(sorted(steps.items())))
