"""Reading what a vemcontact run leaves behind, for curves across runs.

One place for the parsing of our own files (docs/output-format.md):

* ``JOB_contact_pairK_NNNN.csv``: slave node, x, y, COPEN, CPRESS, CSLIP, STATUS
  (columns found by name; CSLIP is optional: older results lack it);
* ``JOB.log``: one line per active-set iteration (active nodes, changed, residual,
  largest penetration, largest pressure, times) under a ``step NAME`` line;
* ``JOB.h5``: mesh, element formulation and the displacements of each step.

A run is given as its output folder (``vemcontact -o DIR``) or one of its files.
Every problem is raised as ``vctools.plot.results.ResultError`` with a one-line
message naming the file, as the contour tool does.
"""
from __future__ import annotations

import csv
import glob
import os
import re
from dataclasses import dataclass, field

import h5py
import numpy as np

from vctools.plot.results import ResultError

__all__ = ["ResultError", "ContactCurve", "Iteration", "RunInfo", "contact_csv", "read_contact",
           "read_log", "log_file", "read_h5", "h5_file", "job_name"]

CONTACT_COLUMNS = ("node", "x", "y", "COPEN", "CPRESS", "STATUS")
_CSV_RE = re.compile(r"^(?P<job>.+)_contact_pair(?P<pair>\d+)_(?P<step>\d+)\.csv$")


def _single_job(folder: str, pattern: str, what: str) -> list[str]:
    if not os.path.isdir(folder):
        raise ResultError(f"{folder}: no such file or folder")
    files = sorted(glob.glob(os.path.join(glob.escape(folder), pattern)))
    if not files:
        raise ResultError(f"{folder}: no {what} in this folder (not a vemcontact output folder?)")
    return files


def job_name(path: str) -> str:
    """JOB of a run folder (the one job in it) or of one of its files."""
    if os.path.isdir(path):
        logs = _single_job(path, "*.log", "JOB.log")
        names = [os.path.basename(f)[:-4] for f in logs]
        if len(names) > 1:
            raise ResultError(f"{path}: holds several jobs ({', '.join(names)}): give the file")
        return names[0]
    base = os.path.basename(path)
    m = _CSV_RE.match(base)
    if m:
        return m.group("job")
    return os.path.splitext(base)[0]


# ------------------------------------------------------------------ contact CSV
@dataclass
class ContactCurve:
    """The contact state of one pair at one step, slave nodes in file order."""
    path: str
    job: str
    pair: int
    step: int
    node: np.ndarray
    x: np.ndarray
    y: np.ndarray
    copen: np.ndarray
    cpress: np.ndarray
    closed: np.ndarray            # bool
    cslip: np.ndarray | None = None   # None when the file has no CSLIP column

    def along(self, how: str = "auto") -> tuple[np.ndarray, str]:
        """Coordinate along the pair and its axis label.  'x' or 'y': that
        coordinate; 's': distance along the pair's main direction from its
        first end; 'auto': x for a pair lying mostly along x, y for one mostly
        along y, else s."""
        if how == "auto":
            # judged on the closed part when there is one (the Hertz slave arc is a
            # quarter circle, its contact zone nearly flat)
            sel = self.closed if self.closed.sum() >= 2 else np.ones(len(self.x), dtype=bool)
            dx = float(np.ptp(self.x[sel])) if sel.any() else 0.0
            dy = float(np.ptp(self.y[sel])) if sel.any() else 0.0
            how = "x" if dy <= 0.25 * dx else ("y" if dx <= 0.25 * dy else "s")
        if how == "x":
            return self.x, "x"
        if how == "y":
            return self.y, "y"
        if how != "s":
            raise ResultError(f"--along {how}: expected x, y, s or auto")
        p = np.column_stack([self.x, self.y])
        if len(p) < 2:
            return np.zeros(len(p)), "distance along the pair s"
        c = p - p.mean(axis=0)
        d = np.linalg.svd(c, full_matrices=False)[2][0]
        if d[0] < 0 or (d[0] == 0 and d[1] < 0):   # s grows with x (with y on a vertical pair)
            d = -d
        t = c @ d
        return t - t.min(), "distance along the pair s"


def contact_csv(path: str, pair: int = 1, step: int = 0) -> str:
    """The contact CSV of a run folder (pair `pair`, step `step`, 0 = last) or `path`
    itself when it is a file."""
    if not os.path.exists(path):
        raise ResultError(f"{path}: no such file or folder")
    job = "*"
    if os.path.isfile(path):
        if path.endswith(".csv"):
            return path
        # another file of the run (JOB.h5, JOB.log): the CSV of the same job
        job, path = glob.escape(os.path.splitext(os.path.basename(path))[0]), os.path.dirname(os.path.abspath(path))
    files = _single_job(path, f"{job}_contact_pair{pair}_*.csv", f"contact results of pair {pair}")
    jobs = sorted({_CSV_RE.match(os.path.basename(f)).group("job") for f in files if _CSV_RE.match(os.path.basename(f))})
    if len(jobs) > 1:
        raise ResultError(f"{path}: holds several jobs ({', '.join(jobs)}): give the CSV file")
    steps = {int(_CSV_RE.match(os.path.basename(f)).group("step")): f for f in files}
    if step == 0:
        return steps[max(steps)]
    if step not in steps:
        raise ResultError(f"{path}: no contact results of pair {pair} at step {step} (steps {', '.join(map(str, sorted(steps)))})")
    return steps[step]


def read_contact(path: str, pair: int = 1, step: int = 0) -> ContactCurve:
    """Read JOB_contact_pairK_NNNN.csv (or find it in a run folder)."""
    f = contact_csv(path, pair, step)
    try:
        with open(f, newline="") as fh:
            rows = list(csv.reader(fh))
    except (OSError, UnicodeDecodeError) as exc:
        raise ResultError(f"{f}: cannot be read ({exc.__class__.__name__})") from None
    if not rows:
        raise ResultError(f"{f}: empty file, expected the header {','.join(CONTACT_COLUMNS)}")
    head = [h.strip() for h in rows[0]]
    missing = [c for c in CONTACT_COLUMNS if c not in head]
    if missing:
        raise ResultError(f"{f}: lacks the columns {', '.join(missing)}: not a vemcontact contact CSV")
    names = CONTACT_COLUMNS + (("CSLIP",) if "CSLIP" in head else ())
    idx = {c: head.index(c) for c in names}
    cols = {c: [] for c in names}
    for n, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        try:
            for c in names:
                v = row[idx[c]].strip()
                cols[c].append(v if c == "STATUS" else float(v))
        except (IndexError, ValueError):
            raise ResultError(f"{f}:{n}: bad row {','.join(row)[:60]!r}") from None
    m = _CSV_RE.match(os.path.basename(f))
    job, pr, st = (m.group("job"), int(m.group("pair")), int(m.group("step"))) if m else \
        (os.path.splitext(os.path.basename(f))[0], pair, step)
    return ContactCurve(path=f, job=job, pair=pr, step=st,
                        node=np.asarray(cols["node"], dtype=np.int64), x=np.asarray(cols["x"]),
                        y=np.asarray(cols["y"]), copen=np.asarray(cols["COPEN"]),
                        cpress=np.asarray(cols["CPRESS"]),
                        closed=np.asarray([s.upper() == "CLOSED" for s in cols["STATUS"]], dtype=bool),
                        cslip=np.asarray(cols["CSLIP"]) if "CSLIP" in cols else None)


# ------------------------------------------------------------------ log
@dataclass
class Iteration:
    iteration: int
    active: int
    changed: int
    residual: float
    penetration: float
    pressure: float


@dataclass
class LogSteps:
    path: str
    job: str
    steps: list = field(default_factory=list)      # [(step name, [Iteration, ...], converged)]

    def step(self, k: int = 0):
        """Step k (1-based among the steps with contact iterations; 0 = last)."""
        if not self.steps:
            raise ResultError(f"{self.path}: no contact iterations in this log")
        if k < 0 or k > len(self.steps):
            raise ResultError(f"{self.path}: has {len(self.steps)} steps with contact iterations, no step {k}")
        return self.steps[k - 1] if k else self.steps[-1]

    def penalty(self, k: int = 0) -> float | None:
        """The penalty slope K = pressure / penetration of the last iteration:
        exact for our node-based pressure CPRESS = K * overclosure."""
        its = self.step(k)[1]
        last = its[-1]
        return last.pressure / last.penetration if last.penetration > 0 else None


def log_file(path: str) -> str:
    if os.path.isdir(path):
        return os.path.join(path, job_name(path) + ".log")
    if not os.path.exists(path):
        raise ResultError(f"{path}: no such file or folder")
    return path




def read_log(path: str) -> LogSteps:
    """The contact iterations of every step of a run (a run folder, its JOB.h5 or its
    JOB.log): the records vemcontact writes into /steps/NNNN/contact/iterations of
    JOB.h5 (docs/output-format.md), not the log's text."""
    if os.path.isdir(path):
        f = os.path.join(path, job_name(path) + ".h5")
    else:
        f = os.path.splitext(path)[0] + ".h5"
    if not os.path.exists(f):
        raise ResultError(f"{f}: no such file (the results of the run)")
    out = LogSteps(path=f, job=os.path.splitext(os.path.basename(f))[0])
    try:
        with h5py.File(f, "r") as h:
            for key in sorted(h["steps"]):
                st = h["steps"][key]
                g = st.get("contact/iterations")
                if g is None:
                    continue
                name = st.attrs.get("name", key)
                name = name.decode() if isinstance(name, bytes) else str(name)
                its = [Iteration(int(i), int(a), int(c), float(r), float(pen), float(pr))
                       for i, a, c, r, pen, pr in zip(g["iteration"], g["active"], g["changed"], g["residual"],
                                                      g["max_penetration"], g["max_pressure"])]
                # a step is written only once its contact iterations have converged
                out.steps.append((name, its, True))
    except OSError as exc:
        raise ResultError(f"{f}: cannot be read ({exc})") from None
    if not out.steps:
        raise ResultError(f"{f}: no contact iterations in this run (no contact pair)")
    return out


# ------------------------------------------------------------------ HDF5
@dataclass
class RunInfo:
    path: str
    job: str
    coordinates: np.ndarray        # (nnode, 2)
    node_ids: np.ndarray
    nelem: int
    formulation: str               # "VEM", "FEM", "VEM+FEM"; second order: "VEM k=2", "FEM Q8", "FEM T6"
    steps: list                    # step keys ("0001", ...)
    displacements: dict            # step key -> (nnode, 2)


def h5_file(path: str) -> str:
    if os.path.isdir(path):
        return os.path.join(path, job_name(path) + ".h5")
    if not os.path.exists(path):
        raise ResultError(f"{path}: no such file or folder")
    if path.endswith(".log"):
        return path[:-4] + ".h5"
    m = _CSV_RE.match(os.path.basename(path))
    if m:
        return os.path.join(os.path.dirname(path), m.group("job") + ".h5")
    return path


def read_h5(path: str) -> RunInfo:
    """Mesh size, formulation and displacements of a run (JOB.h5 or its folder)."""
    import h5py

    f = h5_file(path)
    if not os.path.exists(f):
        raise ResultError(f"{f}: no such file")
    try:
        with h5py.File(f, "r") as h:
            if h.attrs.get("format", b"") not in (b"vemcontact-results", "vemcontact-results"):
                raise ResultError(f"{f}: not a vemcontact HDF5 result (no format attribute)")
            if int(np.asarray(h.attrs.get("complete", 1)).reshape(-1)[0]) != 1:
                raise ResultError(f"{f}: incomplete results: the run that wrote it stopped with an error "
                                  "(root attribute complete = 0)")
            xy = h["mesh/coordinates"][()]
            ids = h["mesh/node_ids"][()]
            form = h["mesh/element_formulation"][()]
            etype = h["mesh/element_type"][()] if "mesh/element_type" in h else np.ones_like(form)
            keys = sorted(h["steps"]) if "steps" in h else []
            disp = {k: h["steps"][k]["U"][()] for k in keys if "U" in h["steps"][k]}
    except ResultError:
        raise
    except (OSError, KeyError) as exc:
        raise ResultError(f"{f}: cannot be read as a vemcontact HDF5 result ({' '.join(str(exc).split())})") from None
    # second-order elements (element_type 4, 5, 6: docs/output-format.md) are named apart
    names = {(1, 4): "VEM k=2", (2, 4): "FEM", (2, 5): "FEM Q8", (2, 6): "FEM T6", (1, 5): "VEM k=2",
             (1, 6): "VEM k=2"}
    kinds = sorted({names.get((int(f_), int(t_)), "VEM" if f_ == 1 else "FEM") for f_, t_ in zip(form, etype)})
    return RunInfo(path=f, job=os.path.splitext(os.path.basename(f))[0], coordinates=xy, node_ids=ids,
                   nelem=int(len(form)), formulation="+".join(kinds) if kinds else "none",
                   steps=list(disp), displacements=disp)
