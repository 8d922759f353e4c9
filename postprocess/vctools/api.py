"""The Python API: run vemcontact and read its results as numpy arrays.

    import vctools
    res = vctools.run("inputs/dam_joint.inp", out="out/dam")    # or a Deck, or deck text
    res = vctools.open("out/dam/dam_joint.h5")                  # an existing run
    step = res.step("RESERVOIR")                                # by name or number (1-based)
    step["U"], step["S_node"], step.contact[1]["CPRESS"], step.iterations["residual"]

Everything is read from JOB.h5 (docs/output-format.md), generically: every dataset
of a step group is a field, every dataset of /steps/NNNN/contact/pair_K a column of
that pair's table, so a field or contact variable that a later version adds appears
without a change here.  docs/python-api.md has the whole interface.
"""
from __future__ import annotations

import builtins
import csv
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field

import numpy as np

from vctools.plot.results import ResultError, h5_path

__all__ = ["run", "open", "find_executable", "Result", "Step", "Mesh", "Table", "RunError", "ResultError",
           "boundary_order", "ELEMENT_TYPES"]

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# /mesh/element_type (docs/output-format.md) -> (name, meshio cell type, VTK cell type)
ELEMENT_TYPES = {1: ("polygon", "polygon", 7), 2: ("quad4", "quad", 9), 3: ("tri3", "triangle", 5),
                 4: ("polygon2", "polygon", 7), 5: ("quad8", "quad8", 23), 6: ("tri6", "triangle6", 22)}


class RunError(Exception):
    """A vemcontact run that ended with a non-zero exit status: `status` is the exit
    status (1 bad input, 2 file error, 3 model not solvable, 4 solver failure, 5
    internal error), `message` the solver's own error lines."""

    def __init__(self, status: int, message: str, deck: str):
        self.status, self.message, self.deck = status, message, deck
        super().__init__(f"{deck}: vemcontact exit status {status}: {message}")


def find_executable(exe: str | None = None) -> str:
    """The vemcontact to run: `exe` when given, else $VEMCONTACT_EXE, else the build of
    this checkout (build/, then build-debug/), else `vemcontact` on the PATH."""
    tried = []
    cands = [exe] if exe else []
    if not exe:
        if os.environ.get("VEMCONTACT_EXE"):
            cands.append(os.environ["VEMCONTACT_EXE"])
        cands += [os.path.join(ROOT, "build", "vemcontact"), os.path.join(ROOT, "build-debug", "vemcontact")]
        on_path = shutil.which("vemcontact")
        if on_path:
            cands.append(on_path)
    for c in cands:
        tried.append(c)
        if os.path.isfile(c) and os.access(c, os.X_OK):
            return os.path.abspath(c)
    raise ResultError("no vemcontact executable (tried " + ", ".join(tried or ["nothing"]) +
                      "): build it (bash scripts/build.sh Release), set VEMCONTACT_EXE or pass exe=")


def _option_args(options: dict) -> list[str]:
    """Keyword options as command-line options: blas_threads=2 -> --blas-threads 2,
    raw_vtu=True -> --raw-vtu (False or None: left out)."""
    args = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            args.append(flag)
        else:
            args += [flag, str(value)]
    return args


def run(deck, out: str | None = None, solver: str | None = None, exe: str | None = None, job: str | None = None,
        timeout: float | None = None, **options) -> Result:
    """Run vemcontact on `deck` and open its results.

    `deck`: the path of a deck, a `vctools.deck.Deck`, or the text of a deck (a string
    holding a line break).  `out`: the results folder (default: beside a deck file; a
    new temporary folder for a Deck or text).  `job`: the job name for a Deck or text
    (default: the Deck's name, else "job").  `solver`: --solver (cholmod, gamg, hypre,
    mumps, auto).  Other keywords become command-line options (`ordering="metis"`,
    `blas_threads=1`, `raw_vtu=True`, `no_vtu=True`, `petsc_options="..."`).
    Raises RunError (with the exit status and the solver's message) when the run fails."""
    exe = find_executable(exe)
    if hasattr(deck, "text") and callable(deck.text):
        text, name = deck.text(), job or getattr(deck, "name", None) or "job"
    elif isinstance(deck, str) and "\n" in deck:
        text, name = deck, job or "job"
    else:
        text, name = None, None
        path = os.fspath(deck)
        if not os.path.isfile(path):
            raise ResultError(f"{path}: no such deck")
    if text is not None:
        out = out or tempfile.mkdtemp(prefix=f"vctools-{name}-")
        os.makedirs(out, exist_ok=True)
        path = os.path.join(out, name + ".inp")
        with builtins.open(path, "w", newline="\n") as f:
            f.write(text)
    cmd = [exe, "-q"]
    if out:
        os.makedirs(out, exist_ok=True)
        cmd += ["-o", out]
    if solver:
        cmd += ["--solver", solver]
    cmd += _option_args(options) + [path]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        lines = [s for s in (r.stderr or r.stdout).splitlines() if s.strip()]
        raise RunError(r.returncode, " / ".join(lines[-5:]) or "no message", path)
    folder = out or os.path.dirname(os.path.abspath(path))
    return open(os.path.join(folder, os.path.splitext(os.path.basename(path))[0] + ".h5"))


def _text(v) -> str:
    if isinstance(v, bytes):
        v = v.decode()
    elif isinstance(v, np.ndarray):
        v = v.reshape(-1)[0]
        v = v.decode() if isinstance(v, bytes) else str(v)
    return str(v).rstrip("\x00").strip()


def _names(ds) -> list[str]:
    return [_text(n) for n in ds[...]]


class Table:
    """Columns of equal length read from an HDF5 group (one dataset per column);
    `t["CPRESS"]`, `t.columns`, `len(t)`, `t.rows()` (dicts), `t.to_pandas()`; `t.attrs` the
    group's attributes (a contact pair's friction_coefficient and cohesion, ...)."""

    def __init__(self, columns: dict, name: str = "", attrs: dict | None = None):
        self.data = dict(columns)
        self.name = name
        self.attrs = dict(attrs or {})

    @property
    def columns(self) -> list[str]:
        return list(self.data)

    def __getitem__(self, key: str) -> np.ndarray:
        if key not in self.data:
            raise KeyError(f"{self.name}: no column {key} (it has {', '.join(self.data)})")
        return self.data[key]

    def __contains__(self, key) -> bool:
        return key in self.data

    def __len__(self) -> int:
        return len(next(iter(self.data.values()))) if self.data else 0

    def rows(self) -> list[dict]:
        return [{k: v[i] for k, v in self.data.items()} for i in range(len(self))]

    def to_pandas(self):
        """A pandas DataFrame (2-column arrays such as coordinates become NAME_1, NAME_2)."""
        import pandas as pd

        flat = {}
        for k, v in self.data.items():
            if v.ndim == 1:
                flat[k] = v
            else:
                for j in range(v.shape[1]):
                    flat[f"{k}_{j + 1}"] = v[:, j]
        return pd.DataFrame(flat)

    def __repr__(self) -> str:
        return f"Table({self.name!r}, {len(self)} rows: {', '.join(self.data)})"


def boundary_order(nodes: np.ndarray, etype: int) -> np.ndarray:
    """The nodes of an element in order around its boundary: second-order elements
    (types 4, 5, 6: corners first, then one node per side) interleaved corner, side
    node, corner, ...; first-order elements as they are."""
    if etype not in (4, 5, 6):
        return nodes
    n = len(nodes) // 2
    out = np.empty_like(nodes)
    out[0::2], out[1::2] = nodes[:n], nodes[n:]
    return out


@dataclass
class Mesh:
    """The mesh of a run (/mesh of JOB.h5): 0-based node indices throughout."""
    coordinates: np.ndarray          # (nnode, 2)
    node_ids: np.ndarray             # user ids
    offsets: np.ndarray              # (nelem + 1,) into connectivity
    connectivity: np.ndarray         # deck order (corners, then side nodes)
    element_ids: np.ndarray
    element_type: np.ndarray         # ELEMENT_TYPES keys
    formulation: np.ndarray          # 1 VEM, 2 FEM
    material: np.ndarray             # 1-based into material_names, 0 none
    element_set: np.ndarray          # 1-based into element_set_names, 0 none
    part: np.ndarray                 # connected body, 1-based
    material_names: list = field(default_factory=list)
    element_set_names: list = field(default_factory=list)

    @property
    def nnode(self) -> int:
        return len(self.coordinates)

    @property
    def nelem(self) -> int:
        return len(self.element_ids)

    def cell(self, e: int) -> np.ndarray:
        """Node indices of element e (0-based), in the deck's order."""
        return self.connectivity[self.offsets[e]:self.offsets[e + 1]]

    def polygons(self) -> list[np.ndarray]:
        """Every element as a polygon through all its nodes in boundary order."""
        return [boundary_order(self.cell(e), int(t)) for e, t in enumerate(self.element_type)]

    def elements_in(self, elset: str) -> np.ndarray:
        """0-based indices of the elements whose section set is `elset`."""
        names = [n.upper() for n in self.element_set_names]
        if elset.upper() not in names:
            raise KeyError(f"no element set {elset} (sets: {', '.join(self.element_set_names)})")
        return np.flatnonzero(self.element_set == names.index(elset.upper()) + 1)


@dataclass
class Step:
    """One step: `fields` (every dataset of the step group: U, S_element, S_node,
    E_element, E_node, RF, RF_total, ERROR_INDICATOR, ...), `rf_sets` (constrained
    node set -> RF total), `contact` (pair number -> Table), `iterations` (Table of
    the contact iterations, or None), `attrs` (error_estimate, energy_norm,
    factor_of_safety, ...), `strength_reduction` (Table of the trials F, converged,
    u_char, iterations of a *STRENGTH REDUCTION step, or None)."""
    number: int
    name: str
    time: float
    fields: dict
    rf_sets: dict
    contact: dict
    iterations: Table | None
    attrs: dict
    strength_reduction: Table | None = None

    def __getitem__(self, key: str) -> np.ndarray:
        if key not in self.fields:
            raise KeyError(f"step {self.number} ({self.name}) has no field {key} (it has {', '.join(self.fields)}; "
                           "the deck's output requests select what is written, docs/output-format.md)")
        return self.fields[key]

    def __contains__(self, key) -> bool:
        return key in self.fields

    @property
    def relative_error(self) -> float | None:
        """The estimated relative energy-norm error (docs/error-estimate.md), or None."""
        est, en = self.attrs.get("error_estimate"), self.attrs.get("energy_norm")
        if est is None or en is None:
            return None
        d = float(np.hypot(en, est))
        return float(est) / d if d > 0 else 0.0


def _read_group_arrays(g) -> dict:
    import h5py

    return {k: g[k][...] for k in g if isinstance(g[k], h5py.Dataset)}


def _attrs(g) -> dict:
    return {k: (_text(v) if isinstance(v, (bytes, str)) or (isinstance(v, np.ndarray) and v.dtype.kind == "S")
                else (v.item() if isinstance(v, np.ndarray) and v.size == 1 else v))
            for k, v in g.attrs.items()}


def _read_step(number: int, g) -> Step:
    import h5py

    attrs = _attrs(g)
    fields = _read_group_arrays(g)
    rf_sets = {}
    if "RF_sets" in g:
        names, rf = _names(g["RF_sets/names"]), g["RF_sets/RF"][...]
        rf_sets = {n: rf[i] for i, n in enumerate(names)}
    contact, iterations = {}, None
    if "contact" in g:
        for key, sub in g["contact"].items():
            if not isinstance(sub, h5py.Group):
                continue
            if key == "iterations":
                iterations = Table(_read_group_arrays(sub), f"step {number} contact iterations")
            elif key.startswith("pair_"):
                k = int(key[5:])
                contact[k] = Table(_read_group_arrays(sub), f"step {number} contact pair {k}", _attrs(sub))
    srm = None
    if "strength_reduction" in g:
        srm = Table(_read_group_arrays(g["strength_reduction"]), f"step {number} strength reduction",
                    _attrs(g["strength_reduction"]))
    return Step(number=number, name=attrs.pop("name", f"Step-{number}"), time=float(attrs.pop("time", number)),
                fields=fields, rf_sets=rf_sets, contact=dict(sorted(contact.items())), iterations=iterations,
                attrs=attrs, strength_reduction=srm)


class Result:
    """A run's results (JOB.h5 and the files beside it), read once into memory:
    `mesh`, `steps` (list, in order), `step(k or name)`, `attrs` (solver, complete,
    processes, ...), `phases` (Table of JOB_phases.csv, or None), `log` (path),
    `to_meshio(step)`, `to_pyvista(step)`."""

    def __init__(self, path: str):
        import h5py

        path = h5_path(path)
        self.path = os.path.abspath(path)
        self.job = os.path.splitext(os.path.basename(path))[0]
        self.folder = os.path.dirname(self.path)
        try:
            with h5py.File(path, "r") as f:
                if _text(f.attrs.get("format", b"")) != "vemcontact-results":
                    raise ResultError(f"{path}: not a vemcontact HDF5 result (no format attribute)")
                self.attrs = {k: (_text(v) if isinstance(v, (bytes, str)) else
                                  (v.item() if isinstance(v, np.ndarray) and v.size == 1 else v))
                              for k, v in f.attrs.items()}
                self.mesh = self._read_mesh(f["mesh"])
                self.steps = [_read_step(int(k), f["steps"][k]) for k in sorted(f.get("steps", {}), key=int)]
        except ResultError:
            raise
        except (OSError, KeyError) as exc:
            raise ResultError(f"{path}: cannot be read as a vemcontact HDF5 result ({' '.join(str(exc).split())})") \
                from None
        self.complete = int(self.attrs.get("complete", 1)) == 1
        self.phases = self._read_phases()
        log = os.path.join(self.folder, self.job + ".log")
        self.log = log if os.path.exists(log) else None

    @staticmethod
    def _read_mesh(g) -> Mesh:
        ne = len(g["element_ids"])
        get = lambda k, d: g[k][...] if k in g else d   # noqa: E731
        return Mesh(coordinates=g["coordinates"][...], node_ids=g["node_ids"][...],
                    offsets=g["element_offsets"][...].astype(np.int64),
                    connectivity=g["element_connectivity"][...].astype(np.int64),
                    element_ids=g["element_ids"][...],
                    element_type=get("element_type", np.ones(ne, np.int32)),
                    formulation=get("element_formulation", np.ones(ne, np.int32)),
                    material=get("element_material", np.zeros(ne, np.int32)),
                    element_set=get("element_set", np.zeros(ne, np.int32)),
                    part=get("element_part", np.ones(ne, np.int32)),
                    material_names=_names(g["material_names"]) if "material_names" in g else [],
                    element_set_names=_names(g["element_set_names"]) if "element_set_names" in g else [])

    def _read_phases(self) -> Table | None:
        p = os.path.join(self.folder, self.job + "_phases.csv")
        if not os.path.exists(p):
            return None
        with builtins.open(p, newline="") as fh:
            rows = list(csv.DictReader(fh))
        if not rows:
            return None
        return Table({"step": np.array([int(r["step"]) for r in rows]),
                      "phase": np.array([r["phase"] for r in rows]),
                      "within": np.array([r["within"] for r in rows]),
                      "seconds": np.array([float(r["seconds"]) for r in rows])}, p)

    def step(self, key: int | str = -1) -> Step:
        """A step by its number (1-based; -1 = the last) or its name (case-insensitive)."""
        if not self.steps:
            raise ResultError(f"{self.path}: holds no step")
        if isinstance(key, str):
            for s in self.steps:
                if s.name.upper() == key.upper():
                    return s
            raise KeyError(f"{self.path}: no step named {key} (steps: {', '.join(s.name for s in self.steps)})")
        if key == -1:
            return self.steps[-1]
        for s in self.steps:
            if s.number == key:
                return s
        raise KeyError(f"{self.path}: no step {key} (steps 1 to {len(self.steps)})")

    __getitem__ = step

    @property
    def last(self) -> Step:
        return self.step(-1)

    # ---------------------------------------------------------------- sliding safety
    def plot_srm(self, out: str, step: int = 0, title: str | None = None) -> dict:
        """F against u_char of a *STRENGTH REDUCTION step (0: the last one) drawn to `out`,
        failed trials marked, the factor of safety as a line; returns the arrays drawn
        (F, u_char, converged, iterations) and factor_of_safety, tolerance, F_lower, F_upper."""
        from vctools.plot.sliding import plot_srm

        return plot_srm(self.path, out, step, title=title)

    def plot_joint(self, out: str, step: int = 0, pair: int = 1, mu: float | None = None,
                   cohesion: float | None = None, title: str | None = None) -> dict:
        """The state along contact pair `pair` of a step (0: the last) drawn to `out`:
        CPRESS, CFLUIDP, |CSHEAR| against c + mu CPRESS, STATUS colours; returns the arrays
        drawn (s from the heel, CPRESS, CFLUIDP, shear, strength, STATUS, ...).  mu and c
        come from the pair's attributes unless given."""
        from vctools.plot.sliding import plot_joint

        return plot_joint(self.path, out, step, pair, mu, cohesion, title=title)

    def __repr__(self) -> str:
        return (f"Result({self.path!r}: {self.mesh.nnode} nodes, {self.mesh.nelem} elements, steps "
                f"{', '.join(f'{s.number} {s.name}' for s in self.steps)})")

    # ---------------------------------------------------------------- conversions
    def _blocks(self):
        """The elements grouped by meshio cell type and node count, element order kept
        within each group: [(meshio type, element indices, (n, k) node array)]."""
        m = self.mesh
        groups: dict = {}
        for e in range(m.nelem):
            t = int(m.element_type[e])
            kind = ELEMENT_TYPES.get(t, ELEMENT_TYPES[1])[1]
            nodes = boundary_order(m.cell(e), t) if kind == "polygon" else m.cell(e)
            es, ns = groups.setdefault((kind, len(nodes)), ([], []))
            es.append(e)
            ns.append(nodes)
        return [(k[0], np.array(es), np.array(ns)) for k, (es, ns) in groups.items()]

    def _point_cell_data(self, step: Step | None):
        m = self.mesh
        point = {"NODE_ID": m.node_ids}
        cell = {"ELEMENT_ID": m.element_ids, "MATERIAL": m.material, "ELSET": m.element_set, "PART": m.part}
        if step is not None:
            for k, v in step.fields.items():
                if v.shape[:1] == (m.nnode,) and k not in ("RF_total",):
                    point[k] = v
                elif v.shape[:1] == (m.nelem,):
                    cell[k] = v
        return point, cell

    def to_meshio(self, step: int | str | None = -1):
        """A meshio.Mesh of the mesh with the fields of `step` (None: the mesh alone):
        points (x, y, 0); cells as triangle, quad, triangle6, quad8 and polygon blocks
        (second-order polygons through their 2n nodes in boundary order), one block per
        type and node count, element order kept within a block (cell data ELEMENT_ID
        says which element a cell is); point data U, S_node, E_node, RF; cell data
        S_element, E_element, ERROR_INDICATOR and the labels."""
        import meshio

        st = None if step is None else self.step(step)
        pts = np.column_stack([self.mesh.coordinates, np.zeros(self.mesh.nnode)])
        blocks = self._blocks()
        point, cell = self._point_cell_data(st)
        cells = [meshio.CellBlock(k, ns) for k, _, ns in blocks]
        cell_data = {name: [v[es] for _, es, _ in blocks] for name, v in cell.items()}
        return meshio.Mesh(pts, cells, point_data=point, cell_data=cell_data)

    def vtk_cells(self) -> tuple[np.ndarray, np.ndarray]:
        """The mesh as VTK's legacy cell array ([n, i1, ..., in] per cell) and cell types
        (5 triangle, 9 quad, 7 polygon, 22 quadratic triangle, 23 quadratic quad), in
        element order, as pyvista.UnstructuredGrid takes them."""
        m = self.mesh
        parts, types = [], np.empty(m.nelem, np.uint8)
        for e in range(m.nelem):
            t = int(m.element_type[e])
            kind, vtk = ELEMENT_TYPES.get(t, ELEMENT_TYPES[1])[1:]
            nodes = boundary_order(m.cell(e), t) if kind == "polygon" else m.cell(e)
            parts.append(np.concatenate([[len(nodes)], nodes]))
            types[e] = vtk
        return np.concatenate(parts).astype(np.int64), types

    def to_pyvista(self, step: int | str | None = -1):
        """A pyvista.UnstructuredGrid with the fields of `step` (pyvista must be installed)."""
        import pyvista as pv

        st = None if step is None else self.step(step)
        cells, types = self.vtk_cells()
        pts = np.column_stack([self.mesh.coordinates, np.zeros(self.mesh.nnode)])
        grid = pv.UnstructuredGrid(cells, types, pts)
        point, cell = self._point_cell_data(st)
        for k, v in point.items():
            grid.point_data[k] = np.column_stack([v, np.zeros(len(v))]) if k in ("U", "RF") else v
        for k, v in cell.items():
            grid.cell_data[k] = v
        return grid


def open(path: str) -> Result:  # noqa: A001 (vctools.open, as the API is documented)
    """The results of a run: its JOB.h5, or a results folder holding one job."""
    return Result(os.fspath(path))
