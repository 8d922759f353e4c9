"""Writing a vemcontact deck from Python: nodes and elements from arrays, sets,
materials, sections, boundary conditions and steps by name (docs/python-api.md).

    d = Deck("plate")
    d.nodes(xy)                                   # (n, 2) array; ids 1..n unless given
    d.elements(cells, type="VPE", elset="PLATE")  # (m, k) array or list of sequences, 0-based
    d.material("ROCK", E=1e9, nu=0.25)
    d.section("PLATE", "ROCK", thickness=1.0)
    d.boundary("LEFT", 1, 2)
    with d.step("LOAD") as s:
        s.cload(3, 2, -1e3)
    vctools.run(d)

Node and element arguments are 0-based indices into the arrays given (as numpy code
counts); the deck gets 1-based ids.  Anything the builder has no method for goes in
as keyword text (`d.keyword("*CONTACT PAIR, ...", ["SLAVE, MASTER"])`), in the model
part or in a step.  The keywords and their meaning are docs/deck-reference.md's.
"""
from __future__ import annotations

import numpy as np

__all__ = ["Deck", "StepBuilder"]


def _num(v) -> str:
    return repr(float(v))


def _ref(v, offset: int) -> str:
    """A node or element: a set name as it is, an index (0-based) as its 1-based id."""
    return str(v) if isinstance(v, str) else str(int(v) + offset)


def _id_lines(ids, per_line: int = 16) -> list[str]:
    ids = [str(int(i)) for i in ids]
    return [", ".join(ids[k:k + per_line]) for k in range(0, len(ids), per_line)]


class StepBuilder:
    """The keywords of one *STEP (made by Deck.step)."""

    def __init__(self, deck: Deck, name: str | None, procedure: str):
        self.deck, self.name, self.lines = deck, name, [procedure]

    def keyword(self, line: str, data=()) -> StepBuilder:
        self.lines.append(line)
        self.lines.extend(data)
        return self

    def cload(self, node, dof: int, value: float) -> StepBuilder:
        """A concentrated force on a node (0-based index) or node set."""
        return self.keyword("*CLOAD", [f"{_ref(node, self.deck.node_offset)}, {int(dof)}, {_num(value)}"])

    def boundary(self, node, first: int, last: int | None = None, value: float | None = None) -> StepBuilder:
        """Fixed or prescribed dofs first..last of a node or node set (in this step)."""
        return self.keyword("*BOUNDARY", [self.deck._bc_line(node, first, last, value)])

    def dload(self, element, face: str, value: float) -> StepBuilder:
        """A distributed load: `face` P1..Pn (pressure on side n) or GRAV, e.g.
        dload("ALL", "GRAV", "9.81, 0., -1.")."""
        return self.keyword("*DLOAD", [f"{_ref(element, self.deck.element_offset)}, {face}, {value}"])

    def output(self, node=("U", "RF"), element=("S", "E"), contact=("CDIS", "CSTR")) -> StepBuilder:
        """File output requests (*NODE FILE, *EL FILE, *CONTACT FILE); an empty tuple leaves one out."""
        for kw, names in (("*NODE FILE", node), ("*EL FILE", element), ("*CONTACT FILE", contact)):
            if names:
                self.keyword(kw, [", ".join(names)])
        return self

    def __enter__(self) -> StepBuilder:
        return self

    def __exit__(self, *exc) -> None:
        return None


class Deck:
    """A deck under construction; `text()` gives it, `write(path)` stores it."""

    def __init__(self, name: str = "job", heading: str | None = None):
        self.name = name
        self.model: list[str] = [] if heading is None else ["*HEADING", heading]
        self.steps: list[StepBuilder] = []
        self.node_offset = 1          # id = index + 1 for nodes given without ids
        self.element_offset = 1
        self._nnode = 0
        self._nelem = 0

    def keyword(self, line: str, data=()) -> Deck:
        """Any keyword line and its data lines, in the model part (before the steps)."""
        self.model.append(line)
        self.model.extend(data)
        return self

    def nodes(self, xy, nset: str | None = None) -> np.ndarray:
        """Nodes at the rows of `xy` (n, 2); returns their 0-based indices.  Calls add
        nodes after the ones before (the indices continue)."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        first = self._nnode
        head = "*NODE" + (f", NSET={nset}" if nset else "")
        self.keyword(head, [f"{first + i + 1}, {_num(x)}, {_num(y)}" for i, (x, y) in enumerate(xy)])
        self._nnode += len(xy)
        return np.arange(first, self._nnode)

    def elements(self, cells, type: str = "VPE", elset: str | None = None) -> np.ndarray:  # noqa: A002
        """Elements of one TYPE (VPE, VPS, VPE2, CPE4, CPE8, ...) through the nodes of each
        row of `cells` (0-based node indices, counter-clockwise; second order: corners,
        then side nodes); returns their 0-based indices."""
        rows = [np.asarray(c, int).reshape(-1) for c in cells]
        first = self._nelem
        data = []
        for i, c in enumerate(rows):
            ids = [str(int(v) + 1) for v in c]
            # a line ending in a comma continues on the next (long polygons)
            chunks = [", ".join(ids[j:j + 15]) for j in range(0, len(ids), 15)]
            data.append(f"{first + i + 1}, " + ",\n".join(chunks))
        self.keyword(f"*ELEMENT, TYPE={type}" + (f", ELSET={elset}" if elset else ""), data)
        self._nelem += len(rows)
        return np.arange(first, self._nelem)

    def nset(self, name: str, nodes) -> Deck:
        """A node set of 0-based node indices."""
        return self.keyword(f"*NSET, NSET={name}", _id_lines(np.asarray(nodes, int).reshape(-1) + 1))

    def elset(self, name: str, elements) -> Deck:
        """An element set of 0-based element indices."""
        return self.keyword(f"*ELSET, ELSET={name}", _id_lines(np.asarray(elements, int).reshape(-1) + 1))

    def surface(self, name: str, elements, sides) -> Deck:
        """An element-face surface: element (0-based) and side number (1-based, S1..Sn) pairs."""
        return self.keyword(f"*SURFACE, NAME={name}, TYPE=ELEMENT",
                            [f"{int(e) + 1}, S{int(s)}" for e, s in zip(elements, sides)])

    def material(self, name: str, E: float, nu: float, density: float | None = None) -> Deck:  # noqa: N803
        self.keyword(f"*MATERIAL, NAME={name}", ["*ELASTIC", f"{_num(E)}, {_num(nu)}"])
        if density is not None:
            self.keyword("*DENSITY", [_num(density)])
        return self

    def section(self, elset: str, material: str, thickness: float = 1.0, **params) -> Deck:
        """*SOLID SECTION of an element set; `params` become parameters
        (formulation="FEM", stabilization=0.5)."""
        extra = "".join(f", {k.upper()}={v}" for k, v in params.items())
        return self.keyword(f"*SOLID SECTION, ELSET={elset}, MATERIAL={material}{extra}", [_num(thickness)])

    def _bc_line(self, node, first: int, last: int | None, value: float | None) -> str:
        line = f"{_ref(node, self.node_offset)}, {int(first)}"
        if last is not None or value is not None:
            line += f", {int(last if last is not None else first)}"
        if value is not None:
            line += f", {_num(value)}"
        return line

    def boundary(self, node, first: int, last: int | None = None, value: float | None = None) -> Deck:
        """Dofs first..last of a node (0-based index) or node set fixed (or at `value`)
        from the start, in the model part."""
        return self.keyword("*BOUNDARY", [self._bc_line(node, first, last, value)])

    def step(self, name: str | None = None, procedure: str = "*STATIC") -> StepBuilder:
        """A new step (*STEP, NAME=...); add its loads to what this returns."""
        s = StepBuilder(self, name, procedure)
        self.steps.append(s)
        return s

    def text(self) -> str:
        out = list(self.model)
        for s in self.steps:
            out.append("*STEP" + (f", NAME={s.name}" if s.name else ""))
            out.extend(s.lines)
            out.append("*END STEP")
        return "\n".join(out) + "\n"

    def write(self, path: str) -> str:
        with open(path, "w", newline="\n") as f:
            f.write(self.text())
        return path
