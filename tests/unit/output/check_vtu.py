"""Read the .vtu files written by test_output_vtu (zlib-compressed and raw) with
meshio and compare every array exactly (binary base64 output must round-trip
doubles bit for bit) with the values the Fortran test wrote to the .expected
text file (18 significant digits, which parse back to the same doubles); the
compressed file must also decode with Python's own zlib and base64 following
VTK's block layout, independently of meshio.

The third file has the extras (E = S/1000 with engineering shear, RF = 5 U,
ELSET, PART, the set and material names as FieldData, TimeValue).

Usage: check_vtu.py COMPRESSED.vtu RAW.vtu EXTRA.vtu FILE.expected
Exits non-zero with a message on the first mismatch.
"""
import base64
import sys
import xml.etree.ElementTree as ET
import zlib

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


def tensor9(s):
    """(n, 4) rows xx, yy, zz, xy as the (n, 9) full tensors, row by row."""
    s = np.asarray(s)
    z = np.zeros(len(s))
    return np.column_stack([s[:, 0], s[:, 3], z, s[:, 3], s[:, 1], z, z, z, s[:, 2]])


def same(name, actual, expected):
    actual = np.asarray(actual)
    expected = np.asarray(expected).reshape(actual.shape)
    if not np.array_equal(actual, expected):
        raise SystemExit(f"FAIL {name}:\n got {actual!r}\n expected {expected!r}")
    print(f"ok {name}")


def decode_compressed(text):
    """Bytes of a compressed inline array by VTK's layout (UInt64 header
    [nblocks, block size, last block size or 0 when full, compressed sizes],
    base64-encoded on its own, then the zlib blocks as one base64 stream)."""
    text = text.strip()
    nblocks = int(np.frombuffer(base64.b64decode(text[:12])[:8], "<u8")[0])
    nhead = 4 * ((8 * (3 + nblocks) + 2) // 3)
    head = np.frombuffer(base64.b64decode(text[:nhead]), "<u8")
    assert head[0] == nblocks and len(head) == 3 + nblocks, head
    packed = base64.b64decode(text[nhead:])
    out, pos = b"", 0
    for k in range(nblocks):
        block = zlib.decompress(packed[pos:pos + int(head[3 + k])])
        full = k < nblocks - 1 or head[2] == 0
        assert len(block) == (head[1] if full else head[2]), (k, len(block), head[:3])
        out += block
        pos += int(head[3 + k])
    assert pos == len(packed), "trailing bytes after the last block"
    return out


def check_extras(vtu, expected_path):
    exp, _ = read_expected(expected_path)
    mesh = meshio.read(vtu)
    e = tensor9(exp["S_point"] / 1000)
    e[:, [1, 3]] /= 2          # the tensor holds gamma_xy / 2
    if not np.allclose(mesh.point_data["E"], e, rtol=1e-15, atol=0):
        raise SystemExit("FAIL point E")
    e = tensor9(exp["S_cell"] / 1000)
    e[:, [1, 3]] /= 2
    if not np.allclose(np.concatenate(mesh.cell_data["E"]), e, rtol=1e-15, atol=0):
        raise SystemExit("FAIL cell E")
    rf = np.column_stack([5 * exp["U"][:, :2], np.zeros(len(exp["U"]))])
    same("point RF", mesh.point_data["RF"], rf)
    same("cell ELSET", np.concatenate(mesh.cell_data["ELSET"]), np.array([2, 1, 2], np.int32))
    same("cell PART", np.concatenate(mesh.cell_data["PART"]), np.array([1, 1, 2], np.int32))
    fd = {k: np.asarray(v).ravel().tolist() for k, v in mesh.field_data.items()}
    expected = {"TimeValue": [2.5], "ELSET:PLATE": [1], "ELSET:A&B<C>": [2], "MATERIAL:ROCK": [1],
                "MATERIAL:CONCRETE": [2]}
    if fd != expected:
        raise SystemExit(f"FAIL field data {fd}, expected {expected}")
    print("ok field data (names escaped, unused set left out)")


def main(vtu, raw_vtu, extra_vtu, expected_path):
    check_extras(extra_vtu, expected_path)
    check_file(raw_vtu, expected_path, compressed=False)
    check_file(vtu, expected_path, compressed=True)
    # independent decoding of the compressed arrays: the same bytes as the raw file's
    raw = [base64.b64decode(da.text.strip())[8:] for da in ET.parse(raw_vtu).getroot().iter("DataArray")]
    arrays = list(ET.parse(vtu).getroot().iter("DataArray"))
    assert len(arrays) == len(raw), (len(arrays), len(raw))
    for da, expected in zip(arrays, raw):
        name = da.attrib["Name"]
        if decode_compressed(da.text) != expected:
            raise SystemExit(f"FAIL {name}: zlib blocks do not decode to the raw bytes")
    print("ok compressed arrays decode (zlib, base64) to the raw bytes")
    print("all checks passed")


def check_file(vtu, expected_path, compressed):
    exp, exp_cells = read_expected(expected_path)

    # file header and array attributes as ParaView sees them
    root = ET.parse(vtu).getroot()
    assert root.attrib["type"] == "UnstructuredGrid", root.attrib
    assert root.attrib["version"] == "1.0", root.attrib
    assert root.attrib["header_type"] == "UInt64", root.attrib
    assert root.attrib["byte_order"] == "LittleEndian", root.attrib
    assert root.attrib.get("compressor") == ("vtkZLibDataCompressor" if compressed else None), root.attrib
    for da in root.iter("DataArray"):
        assert da.attrib["format"] == "binary", da.attrib
        if da.attrib["Name"] == "S":
            names = [da.attrib[f"ComponentName{k}"] for k in range(9)]
            assert names == ["XX", "XY", "XZ", "YX", "YY", "YZ", "ZX", "ZY", "ZZ"], names
    print("ok XML header and attributes")

    mesh = meshio.read(vtu)
    same("points", mesh.points, exp["points"])
    same("point U", mesh.point_data["U"], exp["U"])
    same("point S", mesh.point_data["S"], tensor9(exp["S_point"]))
    for name in ("S1", "S3", "MISES"):
        same(f"point {name}", mesh.point_data[name], exp[name][:, 0])
    same("point NODE_ID", mesh.point_data["NODE_ID"], exp["NODE_ID"][:, 0].astype(np.int32))
    if mesh.point_data["NODE_ID"].dtype != np.int32:
        raise SystemExit("FAIL NODE_ID is not Int32")

    # one block per run of equal cell type (polygons: of equal vertex count), in file order
    got_cells = []
    for block in mesh.cells:
        got_cells.extend(block.data.tolist())
    if got_cells != exp_cells:
        raise SystemExit(f"FAIL cells: got {got_cells} expected {exp_cells}")
    types = [b.type for b in mesh.cells]
    if types != ["polygon", "quad", "triangle"]:
        raise SystemExit(f"FAIL cell blocks {types}, expected polygon (5 nodes), quad, triangle")
    print("ok cells (pentagon as polygon, quad, triangle)")

    def cell_array(name):
        return np.concatenate(mesh.cell_data[name])

    same("cell S", cell_array("S"), tensor9(exp["S_cell"]))
    same("cell MATERIAL", cell_array("MATERIAL"), exp["MATERIAL"][:, 0].astype(np.int32))
    same("cell ELEMENT_ID", cell_array("ELEMENT_ID"), exp["ELEMENT_ID"][:, 0].astype(np.int32))
    for name in ("MATERIAL", "ELEMENT_ID"):
        if cell_array(name).dtype != np.int32:
            raise SystemExit(f"FAIL {name} is not Int32")
    print(f"ok {vtu}")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        raise SystemExit(__doc__)
    main(*sys.argv[1:5])
