"""Field-by-field, step-by-step comparison of two vemcontact results.

A value a (result) passes against b (reference) when |a - b| <= atol + rtol*|b|.
The absolute tolerances default to ATOL_FACTOR times a scale of the whole
reference (every step): the displacement scale L = max(|U|, |COPEN|) for U and
COPEN, the stress scale S = max(|S_element|, |CPRESS|) for S_element and
S_node.  A contact pressure is the penalty K times the overclosure, so CPRESS
gets K times the COPEN tolerance (K read from the reference's closed nodes as
CPRESS/-COPEN, per pair) or the stress tolerance, whichever is larger.  STATUS
and every integer of the mesh must match exactly; coordinates of the mesh
within 1e-12 of its extent (a deck's numbers parse the same way on every
machine).  See docs/regression.md for why these values.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .h5file import CONTACT_FIELDS, STEP_FIELDS, CompareError, Results

RTOL = 1e-8
ATOL_FACTOR = 1e-8
MESH_RTOL = 1e-12
FIELDS = STEP_FIELDS + CONTACT_FIELDS          # U, S_element, S_node, COPEN, CPRESS, STATUS
LENGTH_FIELDS = ("U", "COPEN")
COMPONENTS = {"U": ("x", "y"), "S_element": ("xx", "yy", "zz", "xy"), "S_node": ("xx", "yy", "zz", "xy")}


@dataclass
class Tolerances:
    rtol: float = RTOL
    atol_u: float | None = None       # absolute, length unit; None: ATOL_FACTOR x displacement scale
    atol_s: float | None = None       # absolute, stress unit; None: ATOL_FACTOR x stress scale
    factor: float = ATOL_FACTOR


@dataclass
class Entry:
    """One compared value (a row of the table)."""
    step: int
    field: str
    comp: str
    entity: str
    x: float
    y: float
    value: float
    reference: float
    diff: float
    rel: float
    tol: float
    ratio: float                       # diff / tol; > 1 fails


@dataclass
class Applied:
    """The absolute tolerances in use and where they come from."""
    atol_u: float                      # U, COPEN
    scale_u: float                     # L = max |U|, |COPEN| of the reference
    atol_s: float                      # S_element, S_node
    scale_s: float                     # S = max |S_element|, |CPRESS| of the reference
    atol_p: dict = field(default_factory=dict)      # pair -> CPRESS atol
    penalty: dict = field(default_factory=dict)     # pair -> K estimated from the reference


@dataclass
class Report:
    result: str
    reference: str
    compared: int = 0
    failed: int = 0
    problems: list = field(default_factory=list)      # structural mismatches, one line each
    notes: list = field(default_factory=list)         # fields in neither file (output requests), one line each
    mismatched: list = field(default_factory=list)    # (label, nfail, n) per compared array
    worst: list = field(default_factory=list)         # Entry, worst first
    applied: Applied | None = None
    steps: list = field(default_factory=list)
    fields: tuple = ()

    @property
    def ok(self) -> bool:
        return not self.problems and not self.mismatched


def parse_fields(text: str | None) -> tuple:
    if not text:
        return FIELDS
    names = [t.strip() for t in text.split(",") if t.strip()]
    for n in names:
        if n not in FIELDS:
            raise CompareError(f"--fields: unknown field {n} (fields: {', '.join(FIELDS)})")
    return tuple(dict.fromkeys(names))


def parse_steps(text: str | None):
    if not text:
        return None
    out = []
    for t in text.split(","):
        t = t.strip()
        if not t:
            continue
        if not t.isdigit() or int(t) < 1:
            raise CompareError(f"--steps: '{t}' is not a step number (1, 2, ...)")
        out.append(int(t))
    return list(dict.fromkeys(out)) or None


# ------------------------------------------------------------------ mesh
def _extent(x: np.ndarray) -> float:
    if x.size == 0:
        return 1.0
    e = float(np.max(np.ptp(x, axis=0)))
    return e if e > 0 else max(1.0, float(np.abs(x).max()))


def compare_mesh(res: Results, ref: Results) -> list:
    """One 'mesh changed: ...' line per kind of difference (empty when equal)."""
    a, b = res.mesh, ref.mesh
    out = []
    nn, nn0 = len(a["node_ids"]), len(b["node_ids"])
    ne, ne0 = len(a["element_ids"]), len(b["element_ids"])
    if nn != nn0 or a["coordinates"].shape != b["coordinates"].shape:
        out.append(f"mesh changed: {nn} nodes, reference {nn0}")
    if ne != ne0 or a["element_offsets"].shape != b["element_offsets"].shape:
        out.append(f"mesh changed: {ne} elements, reference {ne0}")
    if out:
        return out
    ids, ids0 = a["node_ids"], b["node_ids"]
    bad = np.flatnonzero(ids != ids0)
    if bad.size:
        i = bad[0]
        out.append(f"mesh changed: {bad.size} node ids differ (node {i + 1} has id {ids[i]}, reference {ids0[i]})")
    x, x0 = np.asarray(a["coordinates"], float), np.asarray(b["coordinates"], float)
    d = np.abs(x - x0).max(axis=1) if x.size else np.zeros(0)
    bad = np.flatnonzero(~(d <= MESH_RTOL * _extent(x0)))
    if bad.size:
        i = bad[np.argmax(np.where(np.isfinite(d[bad]), d[bad], np.inf))]
        out.append(f"mesh changed: {bad.size} nodes moved (node id {ids0[i]} at ({x[i, 0]:.9g}, {x[i, 1]:.9g}), "
                   f"reference ({x0[i, 0]:.9g}, {x0[i, 1]:.9g}))")
    eids, eids0 = a["element_ids"], b["element_ids"]
    bad = np.flatnonzero(eids != eids0)
    if bad.size:
        e = bad[0]
        out.append(f"mesh changed: {bad.size} element ids differ (element {e + 1} has id {eids[e]}, reference {eids0[e]})")
    off, off0 = a["element_offsets"], b["element_offsets"]
    con, con0 = a["element_connectivity"], b["element_connectivity"]
    if not np.array_equal(off, off0) or not np.array_equal(con, con0):
        for e in range(ne0):
            c = con[off[e]:off[e + 1]] if e + 1 < len(off) else con[0:0]
            c0 = con0[off0[e]:off0[e + 1]]
            if not np.array_equal(c, c0):
                def names(cc, ii):
                    return " ".join(str(ii[k]) if 0 <= k < len(ii) else f"?{k}" for k in cc)
                out.append(f"mesh changed: connectivity of element id {eids0[e]} is [{names(c, ids)}], "
                           f"reference [{names(c0, ids0)}] (node ids)")
                break
        else:
            out.append("mesh changed: element connectivity arrays differ")
    for name, what in (("element_material", "material"), ("element_type", "type"),
                       ("element_formulation", "formulation")):
        v, v0 = a[name], b[name]
        bad = np.flatnonzero(v != v0) if v.shape == v0.shape else np.arange(ne0)
        if bad.size:
            e = bad[0]
            out.append(f"mesh changed: {bad.size} elements have another {what} "
                       f"(element id {eids0[e]}: {v[e] if e < len(v) else '-'}, reference {v0[e]})")
    return out


# ------------------------------------------------------------------ values
class _Worst:
    """Keeps the N largest entries by ratio (then absolute difference)."""

    def __init__(self, n: int):
        self.n = n
        self.items = []

    def add(self, entries):
        self.items.extend(entries)
        self.items.sort(key=lambda e: (e.ratio, e.diff), reverse=True)
        del self.items[self.n:]


def _element_centroids(mesh) -> np.ndarray:
    x = np.asarray(mesh["coordinates"], float)
    off = np.asarray(mesh["element_offsets"], np.int64)
    con = np.asarray(mesh["element_connectivity"], np.int64)
    n = np.diff(off)
    if con.size == 0:
        return np.zeros((len(n), 2))
    owner = np.repeat(np.arange(len(n)), n)
    c = np.zeros((len(n), 2))
    np.add.at(c, owner, x[con])
    return c / np.maximum(n, 1)[:, None]


def _compare_array(a, b, atol, rtol, step, name, kind, ids, xy, worst: _Worst, report: Report, label=None):
    """Compare result a with reference b (same shape) and record the outcome."""
    label = f"step {step} {label or name}"
    a2 = np.asarray(a).reshape(len(a), -1)
    b2 = np.asarray(b).reshape(len(b), -1)
    exact = a2.dtype.kind in "iub" and b2.dtype.kind in "iub"
    af, bf = a2.astype(float), b2.astype(float)
    with np.errstate(invalid="ignore", over="ignore"):
        diff = np.abs(af - bf)
        both_nan = np.isnan(af) & np.isnan(bf)
        diff[both_nan] = 0.0
        diff[np.isnan(diff)] = np.inf
        if exact:
            tol = np.zeros_like(bf)
        else:
            tol = atol + rtol * np.abs(bf)
            tol[~np.isfinite(tol)] = 0.0
        ratio = np.where(tol > 0, diff / np.where(tol > 0, tol, 1.0), np.where(diff > 0, np.inf, 0.0))
        fail = diff > tol
    n, nfail = diff.size, int(np.count_nonzero(fail))
    report.compared += n
    report.failed += nfail
    if nfail:
        report.mismatched.append((label, nfail, n))
    if worst.n <= 0 or n == 0:
        return
    flat = ratio.ravel()
    k = min(worst.n, n)
    cand = np.argpartition(-flat, k - 1)[:k] if k < n else np.arange(n)
    comps = COMPONENTS.get(name, ("",) * a2.shape[1])
    entries = []
    for idx in cand:
        i, j = divmod(int(idx), a2.shape[1])
        if diff[i, j] == 0:
            continue
        v, r = af[i, j], bf[i, j]
        rel = diff[i, j] / abs(r) if r != 0 else math.inf
        entries.append(Entry(step, name, comps[j] if j < len(comps) else str(j), f"{kind} {ids[i]}",
                             float(xy[i, 0]), float(xy[i, 1]), float(v), float(r), float(diff[i, j]),
                             float(rel), float(tol[i, j]), float(ratio[i, j])))
    worst.add(entries)


def _max_abs(*arrays) -> float:
    m = 0.0
    for a in arrays:
        a = np.asarray(a, float)
        if a.size:
            v = np.abs(a[np.isfinite(a)])
            if v.size:
                m = max(m, float(v.max()))
    return m


def penalty_of(ref: Results) -> dict:
    """Per contact pair, the penalty slope K = CPRESS / -COPEN of its closed nodes
    (the linear pressure-overclosure law), largest over the steps; 0 if none closed."""
    k = {}
    for st in ref.steps.values():
        for name, pair in st.pairs.items():
            p, g = pair.data.get("CPRESS"), pair.data.get("COPEN")
            k.setdefault(name, 0.0)
            if p is None or g is None or p.shape != g.shape:
                continue
            p, g = np.asarray(p, float), np.asarray(g, float)
            closed = (g < 0) & (p > 0) & np.isfinite(p) & np.isfinite(g)
            if "STATUS" in pair.data and pair.data["STATUS"].shape == p.shape:
                closed &= pair.data["STATUS"] == 1
            if closed.any():
                k[name] = max(k[name], float(np.max(p[closed] / -g[closed])))
    return k


def tolerances(ref: Results, tol: Tolerances) -> Applied:
    steps = ref.steps.values()
    scale_u = _max_abs(*[s.fields.get("U", []) for s in steps],
                       *[p.data.get("COPEN", []) for s in steps for p in s.pairs.values()])
    scale_s = _max_abs(*[s.fields.get("S_element", []) for s in steps],
                       *[p.data.get("CPRESS", []) for s in steps for p in s.pairs.values()])
    atol_u = tol.atol_u if tol.atol_u is not None else tol.factor * scale_u
    atol_s = tol.atol_s if tol.atol_s is not None else tol.factor * scale_s
    k = penalty_of(ref)
    atol_p = {name: atol_s if tol.atol_s is not None else max(atol_s, kk * atol_u) for name, kk in k.items()}
    return Applied(atol_u, scale_u, atol_s, scale_s, atol_p, k)


def compare(res: Results, ref: Results, tol: Tolerances | None = None, fields=None, steps=None,
            top: int = 10) -> Report:
    """Compare res against ref.  fields: names from FIELDS (None: all); steps: step
    numbers (None: every step of both).  Raises CompareError for a requested field
    or step that one of the files does not have."""
    tol = tol or Tolerances()
    requested = tuple(fields) if fields else ()
    fields = requested or FIELDS
    report = Report(res.path, ref.path, fields=fields)
    for name in requested:
        for r in (ref, res):
            if not r.has_field(name):
                raise CompareError(f"{r.path}: no field {name} in any step (not computed for this model, "
                                   f"or not selected by the deck's output requests)")
    if steps:
        for r in (ref, res):
            missing = [s for s in steps if s not in r.steps]
            if missing:
                have = ", ".join(str(s) for s in r.steps) or "none"
                raise CompareError(f"{r.path}: no step {missing[0]} (it has steps {have})")
        numbers = list(steps)
    else:
        for s in ref.steps:
            if s not in res.steps:
                report.problems.append(f"step {s} ({ref.steps[s].name}) missing in the result")
        for s in res.steps:
            if s not in ref.steps:
                report.problems.append(f"step {s} ({res.steps[s].name}) not in the reference (extra step)")
        numbers = [s for s in ref.steps if s in res.steps]
    report.steps = numbers

    mesh_problems = compare_mesh(res, ref)
    if mesh_problems:
        report.problems.extend(mesh_problems)
        report.problems.append("fields not compared: the mesh changed")
        return report

    worst = _Worst(top)
    applied = report.applied = tolerances(ref, tol)
    atol_u, atol_s = applied.atol_u, applied.atol_s
    node_ids = ref.mesh["node_ids"]
    xy = np.asarray(ref.mesh["coordinates"], float)
    elem_ids = ref.mesh["element_ids"]
    centroids = _element_centroids(ref.mesh)
    where = {"U": ("node", node_ids, xy), "S_node": ("node", node_ids, xy),
             "S_element": ("element", elem_ids, centroids)}

    for s in numbers:
        a, b = res.steps[s], ref.steps[s]
        if a.name != b.name:
            report.problems.append(f"step {s}: name '{a.name}', reference '{b.name}'")
        if (a.time is None) != (b.time is None) or (
                a.time is not None and abs(a.time - b.time) > 1e-12 * max(1.0, abs(b.time))):
            report.problems.append(f"step {s}: time {a.time}, reference {b.time}")

        for name in STEP_FIELDS:
            if name not in fields:
                continue
            if name not in b.fields:
                if name in a.fields:
                    report.problems.append(f"step {s}: {name} in the result but not in the reference")
                else:
                    report.notes.append(f"step {s}: {name} not compared: in neither file "
                                        f"(the deck's output requests do not select it)")
                continue
            if name not in a.fields:
                report.problems.append(f"step {s}: {name} missing in the result")
                continue
            if a.fields[name].shape != b.fields[name].shape:
                report.problems.append(f"step {s}: {name} has shape {a.fields[name].shape}, "
                                       f"reference {b.fields[name].shape}")
                continue
            kind, ids, pos = where[name]
            _compare_array(a.fields[name], b.fields[name], atol_u if name in LENGTH_FIELDS else atol_s,
                           tol.rtol, s, name, kind, ids, pos, worst, report)

        if not any(f in fields for f in CONTACT_FIELDS):
            continue
        for pk in b.pairs:
            if pk not in a.pairs:
                report.problems.append(f"step {s}: contact {pk} missing in the result")
        for pk in a.pairs:
            if pk not in b.pairs:
                report.problems.append(f"step {s}: contact {pk} not in the reference")
        for pk, pb in b.pairs.items():
            pa = a.pairs.get(pk)
            if pa is None:
                continue
            nid_a, nid_b = pa.data.get("node_ids"), pb.data.get("node_ids")
            if nid_a is None or nid_b is None or not np.array_equal(nid_a, nid_b):
                na = "none" if nid_a is None else len(nid_a)
                nb = "none" if nid_b is None else len(nid_b)
                report.problems.append(f"step {s}: contact {pk} slave nodes changed ({na} nodes, reference {nb})")
                continue
            pos = np.asarray(pb.data.get("coordinates", np.full((len(nid_b), 2), np.nan)), float)
            if "coordinates" in pa.data and not np.allclose(pa.data["coordinates"], pos, rtol=0,
                                                            atol=MESH_RTOL * _extent(xy)):
                report.problems.append(f"step {s}: contact {pk} slave node coordinates changed")
            for name in CONTACT_FIELDS:
                if name not in fields:
                    continue
                label = f"contact {pk} {name}"
                if name not in pb.data:
                    if name in pa.data:
                        report.problems.append(f"step {s}: {label} in the result but not in the reference")
                    continue
                if name not in pa.data:
                    report.problems.append(f"step {s}: {label} missing in the result")
                    continue
                if pa.data[name].shape != pb.data[name].shape:
                    report.problems.append(f"step {s}: {label} has shape {pa.data[name].shape}, "
                                           f"reference {pb.data[name].shape}")
                    continue
                atol = {"COPEN": atol_u, "CPRESS": applied.atol_p.get(pk, atol_s)}.get(name, 0.0)
                _compare_array(pa.data[name], pb.data[name], atol,
                               tol.rtol, s, name, f"{pk} slave", nid_b, pos, worst, report, label=label)
    report.worst = worst.items
    return report
