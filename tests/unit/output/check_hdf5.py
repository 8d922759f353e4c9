"""Read the HDF5 results file written by test_output_hdf5 with h5py and check
the layout of docs/output-format.md as Python sees it: shapes (the reverse of
the Fortran dims), dtypes, attributes, 0-based connectivity, and values of the
small test mesh (pentagon 1-5, quad 2-6-7-3, triangle 6-8-7, free node 9).

Usage: check_hdf5.py FILE.h5
"""
import sys

import h5py
import numpy as np

X = [(0.0, 0.0), (1.0, 0.0), (1.5, 0.8), (0.5, 1.4), (-0.5, 0.8),
     (2.0, 0.0), (2.0, 1.0), (3.0, 0.5), (0.1, -0.3)]


def expect(cond, what):
    if not cond:
        raise SystemExit(f"FAIL {what}")
    print(f"ok {what}")


def main(path):
    with h5py.File(path, "r") as f:
        expect(f.attrs["format"] == b"vemcontact-results", "format attribute")
        expect(int(f.attrs["format_version"]) == 1, "format_version attribute")
        m = f["mesh"]
        nnode, nelem = 9, 3
        expect(m["coordinates"].shape == (nnode, 2), "coordinates shape (nnode, 2)")
        expect(m["coordinates"].dtype == np.float64, "coordinates float64")
        expect(np.array_equal(m["coordinates"][...], np.array(X)), "coordinates values")
        expect(m["node_ids"].dtype == np.int32, "node_ids int32")
        expect(np.array_equal(m["node_ids"][...], 10 * np.arange(1, 10) + 1), "node_ids values")
        off = m["element_offsets"][...]
        con = m["element_connectivity"][...]
        expect(off.dtype == np.int64 and off.shape == (nelem + 1,), "element_offsets int64 (nelem+1)")
        expect(con.dtype == np.int32 and off[-1] == con.size, "connectivity int32, offsets[-1] = size")
        cells = [con[off[e]:off[e + 1]].tolist() for e in range(nelem)]
        expect(cells == [[0, 1, 2, 3, 4], [1, 5, 6, 2], [5, 7, 6]], "0-based cells")
        for name, values in [("element_ids", [100, 205, 307]), ("element_material", [1, 2, 1]),
                             ("element_type", [1, 2, 3]), ("element_formulation", [1, 2, 2])]:
            d = m[name]
            expect(d.dtype == np.int32 and d.shape == (nelem,) and d[...].tolist() == values, name)
        for name, values in [("element_set", [3, 1, 0]), ("element_part", [1, 1, 2])]:
            d = m[name]
            expect(d.dtype == np.int32 and d.shape == (nelem,) and d[...].tolist() == values, name)
        expect([s.decode() for s in m["element_set_names"][...]] == ["PLATE", "A_LONGER_SET_NAME", "Q"],
               "element_set_names strings")
        expect([s.decode() for s in m["material_names"][...]] == ["ROCK", "CONCRETE"], "material_names strings")
        steps = f["steps"]
        expect(sorted(steps.keys()) == ["0001", "0002"], "step groups 0001, 0002")
        s1 = steps["0001"]
        expect(s1.attrs["name"] == b"LOAD", "step 1 name")
        expect(s1.attrs["time"] == 1.0 and s1.attrs["time"].dtype == np.float64, "step 1 time")
        expect(steps["0002"].attrs["name"] == b"UNLOAD step", "step 2 name")
        expect(steps["0002"].attrs["time"] == 0.1, "step 2 time")
        expect(s1["U"].shape == (nnode, 2), "U shape (nnode, 2)")
        expect(s1["S_element"].shape == (nelem, 4), "S_element shape (nelem, 4)")
        expect(s1["S_node"].shape == (nnode, 4), "S_node shape (nnode, 4)")
        # the test writes u1(:, i) = (sin(i)*1e-3, -cos(i)/3): check node 1 loosely
        # (libm's sin may differ from numpy's in the last bit; exactness is
        # checked by the Fortran read-back)
        expect(np.allclose(s1["U"][0], [np.sin(1.0) * 1e-3, -np.cos(1.0) / 3], rtol=1e-15, atol=0),
               "U row = node (x, y)")
        expect(np.allclose(s1["S_node"][8], [9 / 7, -81 / 11, 1 / 11, np.exp(9.0)], rtol=1e-15, atol=0),
               "S_node row = node (xx, yy, zz, xy)")
        # strains and reactions (write_results): E_* = S_* scaled, RF = 3 U
        expect(s1["E_element"].shape == (nelem, 4) and s1["E_node"].shape == (nnode, 4), "E shapes")
        expect(np.array_equal(s1["E_element"][...], 0.5 * s1["S_element"][...]), "E_element values")
        expect(np.array_equal(s1["E_node"][...], 0.25 * s1["S_node"][...]), "E_node values")
        expect(s1["RF"].shape == (nnode, 2) and np.array_equal(s1["RF"][...], 3 * s1["U"][...]), "RF values")
        expect(s1["RF_total"].shape == (2,) and np.allclose(s1["RF_total"][...], s1["RF"][...].sum(axis=0),
                                                            rtol=1e-14), "RF_total = sum of RF")
        expect([s.decode() for s in s1["RF_sets/names"][...]] == ["BASE", "SIDE"], "RF_sets names")
        expect(s1["RF_sets/RF"][...].tolist() == [[1.0, 2.0], [-3.0, 0.5]], "RF_sets RF (nsets, 2)")
        expect("E_element" not in steps["0002"], "step 2 without write_results has no E")
    print("all checks passed")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    main(sys.argv[1])
