"""Deck text for vemcontact's *INCLUDE: *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE."""
from __future__ import annotations

import io

import numpy as np

from .errors import MeshError
from .mesh import check_cells

# element types: (formulation, plane) -> {nodes per cell: type}; VEM takes any polygon
TYPES = {
    ("vem", "strain"): "VPE", ("vem", "stress"): "VPS",
    ("fem", "strain"): {3: "CPE3", 4: "CPE4"}, ("fem", "stress"): {3: "CPS3", 4: "CPS4"},
}
# the second-order type of each first-order one (corners first, then one node per side)
SECOND_ORDER = {"VPE": "VPE2", "VPS": "VPS2", "CPE3": "CPE6", "CPE4": "CPE8", "CPS3": "CPS6", "CPS4": "CPS8"}


def element_type(formulation, plane, nnode, where):
    t = TYPES.get((formulation, plane))
    if t is None:
        raise MeshError(f"{where}: formulation must be 'vem' or 'fem' and plane 'strain' or 'stress', "
                        f"got {formulation!r}, {plane!r}")
    if isinstance(t, str):
        return t
    if nnode not in t:
        raise MeshError(f"{where}: FEM elements are triangles and quads; a cell has {nnode} nodes "
                        f"(use formulation = 'vem')")
    return t[nnode]


def _fmt(v):
    return repr(float(v))


def _id_lines(ids, per_line=16):
    ids = list(ids)
    return [", ".join(str(i) for i in ids[k:k + per_line]) for k in range(0, len(ids), per_line)]


def write_deck(m, path_or_file, header_lines=(), node_set_all="NALL"):
    """Write the mesh; ids start at 1 in node/cell order.  Returns the text.  A mesh
    with a cell vemcontact would refuse is refused here (check_cells: MeshError),
    never written."""
    check_cells(m)
    out = io.StringIO()
    for line in header_lines:
        out.write(f"** {line}\n" if line else "**\n")
    out.write(f"*NODE, NSET={node_set_all}\n")
    ids = np.arange(1, len(m.nodes) + 1)
    for i, (x, y) in zip(ids, m.nodes):
        out.write(f"{i}, {_fmt(x)}, {_fmt(y)}\n")
    counts = np.diff(m.ptr)
    # one *ELEMENT block per (body, type); ids are consecutive in cell order within a block
    for k, (name, etype) in enumerate(m.bodies):
        cells = np.flatnonzero(m.cell_body == k)
        if len(cells) == 0:
            continue
        types = {}
        for c in cells:
            t = etype(int(counts[c])) if callable(etype) else etype
            if m.side_nodes is not None:
                t = SECOND_ORDER[t]
            types.setdefault(t, []).append(c)
        for t, cs in types.items():
            out.write(f"*ELEMENT, TYPE={t}, ELSET={name}\n")
            for c in cs:
                nodes = [str(v + 1) for v in m.cell(c)]
                if m.side_nodes is not None:
                    nodes += [str(v + 1) for v in m.side_nodes[m.ptr[c]:m.ptr[c + 1]]]
                head = f"{c + 1}, "
                # continuation: a line ending in a comma continues on the next
                chunks = [nodes[j:j + 15] for j in range(0, len(nodes), 15)]
                text = head + ",\n".join(", ".join(ch) for ch in chunks)
                out.write(text + "\n")
    for name, nodes in m.nsets.items():
        out.write(f"*NSET, NSET={name}\n")
        for line in _id_lines(np.asarray(nodes) + 1):
            out.write(line + "\n")
    for name, cells in m.elsets.items():
        out.write(f"*ELSET, ELSET={name}\n")
        for line in _id_lines(np.asarray(cells) + 1):
            out.write(line + "\n")
    for name, nodes in m.nsurfaces.items():
        # a TYPE=NODE data line holds one node or one node set (as CalculiX reads
        # it): name the node set of the same nodes when there is one
        out.write(f"*SURFACE, NAME={name}, TYPE=NODE\n")
        same = name in m.nsets and np.array_equal(np.sort(np.asarray(m.nsets[name])), np.sort(np.asarray(nodes)))
        if same:
            out.write(f"{name}\n")
        else:
            for v in np.asarray(nodes) + 1:
                out.write(f"{int(v)}\n")
    for name, (cells, sides) in m.esurfaces.items():
        out.write(f"*SURFACE, NAME={name}, TYPE=ELEMENT\n")
        for c, s in zip(cells, sides):
            out.write(f"{c + 1}, S{int(s)}\n")
    text = out.getvalue()
    if path_or_file is not None:
        if hasattr(path_or_file, "write"):
            path_or_file.write(text)
        else:
            with open(path_or_file, "w", newline="\n") as f:
                f.write(text)
    return text
