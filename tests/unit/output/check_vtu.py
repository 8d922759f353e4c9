"""Read the .vtu written by test_output_vtu with meshio and compare every array
exactly (binary base64 output must round-trip doubles bit for bit) with the
values the Fortran test wrote to the .expected text file (18 significant
digits, which parse back to the same doubles).

Usage: check_vtu.py FILE.vtu FILE.expected
Exits non-zero with a message on the first mismatch.
"""
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np


def read_expected(path):
    arrays, cells = {}, []
    with open(path) as f:
        lines = [line.split() for line in f if line.strip()]
    i = 0
    while i < len(lines):
        head = lines[i]
        if head[0] == "array":
            name, nrows, ncols = head[1], int(head[2]), int(head[3])
            rows = lines[i + 1 : i + 1 + nrows]
            # values are written with Fortran's E format
            data = np.array([[float(v) for v in r] for r in rows])
            arrays[name] = data.reshape(nrows, ncols)
            i += 1 + nrows
        elif head[0] == "cells":
            n = int(head[1])
            for r in lines[i + 1 : i + 1 + n]:
                nv = int(r[0])
                cells.append([int(v) for v in r[1 : 1 + nv]])
            i += 1 + n
        else:
            raise ValueError(f"unexpected line {head}")
    return arrays, cells


def same(name, actual, expected):
    actual = np.asarray(actual)
    expected = np.asarray(expected).reshape(actual.shape)
    if not np.array_equal(actual, expected):
        raise SystemExit(f"FAIL {name}:\n got {actual!r}\n expected {expected!r}")
    print(f"ok {name}")


def main(vtu, expected_path):
    exp, exp_cells = read_expected(expected_path)

    # file header and array attributes as ParaView sees them
    root = ET.parse(vtu).getroot()
    assert root.attrib["type"] == "UnstructuredGrid", root.attrib
    assert root.attrib["version"] == "1.0", root.attrib
    assert root.attrib["header_type"] == "UInt64", root.attrib
    assert root.attrib["byte_order"] == "LittleEndian", root.attrib
    for da in root.iter("DataArray"):
        assert da.attrib["format"] == "binary", da.attrib
        if da.attrib["Name"] == "S":
            names = [da.attrib[f"ComponentName{k}"] for k in range(4)]
            assert names == ["XX", "YY", "ZZ", "XY"], names
    print("ok XML header and attributes")

    mesh = meshio.read(vtu)
    same("points", mesh.points, exp["points"])
    same("point U", mesh.point_data["U"], exp["U"])
    same("point S", mesh.point_data["S"], exp["S_point"])
    for name in ("S1", "S3", "MISES"):
        same(f"point {name}", mesh.point_data[name], exp[name][:, 0])
    same("point NODE_ID", mesh.point_data["NODE_ID"], exp["NODE_ID"][:, 0].astype(np.int32))
    if mesh.point_data["NODE_ID"].dtype != np.int32:
        raise SystemExit("FAIL NODE_ID is not Int32")

    # meshio splits the polygon cells into blocks of equal vertex count, in file order
    got_cells = []
    for block in mesh.cells:
        if block.type != "polygon":
            raise SystemExit(f"FAIL cell block of type {block.type}, expected polygon")
        got_cells.extend(block.data.tolist())
    if got_cells != exp_cells:
        raise SystemExit(f"FAIL cells: got {got_cells} expected {exp_cells}")
    if sorted(len(b.data[0]) for b in mesh.cells) != [3, 4, 5]:
        raise SystemExit("FAIL expected blocks of 5-, 4- and 3-vertex polygons")
    print("ok cells (pentagon, quad, triangle as polygons)")

    def cell_array(name):
        return np.concatenate(mesh.cell_data[name])

    same("cell S", cell_array("S"), exp["S_cell"])
    same("cell MATERIAL", cell_array("MATERIAL"), exp["MATERIAL"][:, 0].astype(np.int32))
    same("cell ELEMENT_ID", cell_array("ELEMENT_ID"), exp["ELEMENT_ID"][:, 0].astype(np.int32))
    for name in ("MATERIAL", "ELEMENT_ID"):
        if cell_array(name).dtype != np.int32:
            raise SystemExit(f"FAIL {name} is not Int32")
    print("all checks passed")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
