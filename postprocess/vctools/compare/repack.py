"""Rewrite a vemcontact HDF5 results file compressed (gzip 9 + shuffle), for references.

  python -m vctools.compare.repack SOURCE.h5 DEST.h5

Every group, dataset (same dtype, shape and values, bit for bit) and attribute
is copied; only the storage changes (chunked, compressed), which h5py and the
HDF5 library read transparently.  The copy is checked value by value before
DEST is written (through DEST.tmp and a rename).
"""
from __future__ import annotations

import os
import sys

import numpy as np

from .h5file import CompareError, read_results


def _copy_attrs(src, dst):
    for k, v in src.attrs.items():
        dst.attrs.create(k, v, dtype=src.attrs.get_id(k).dtype)


def repack(source: str, dest: str) -> None:
    import h5py

    read_results(source)                          # a readable vemcontact file, or CompareError
    tmp = dest + ".tmp"
    with h5py.File(source, "r") as fi, h5py.File(tmp, "w", libver="earliest") as fo:
        _copy_attrs(fi, fo)

        def visit(name, obj):
            if isinstance(obj, h5py.Group):
                _copy_attrs(obj, fo.require_group(name))
            else:
                data = obj[()]
                kw = dict(compression="gzip", compression_opts=9, shuffle=True) if data.nbytes >= 4096 else {}
                d = fo.create_dataset(name, data=data, dtype=obj.dtype, **kw)
                _copy_attrs(obj, d)
        fi.visititems(visit)
    with h5py.File(source, "r") as fi, h5py.File(tmp, "r") as fo:
        def check(name, obj):
            other = fo[name]
            if isinstance(obj, h5py.Dataset):
                a, b = obj[()], other[()]
                if a.dtype != b.dtype or a.shape != b.shape or a.tobytes() != b.tobytes():
                    raise CompareError(f"{tmp}: {name} differs from {source} after repacking")
            for k, v in obj.attrs.items():
                if not np.array_equal(np.asarray(v), np.asarray(other.attrs[k])):
                    raise CompareError(f"{tmp}: attribute {k} of /{name} differs after repacking")
        fi.visititems(check)
    os.replace(tmp, dest)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2 or argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    try:
        repack(argv[0], argv[1])
    except CompareError as exc:
        print(f"vc-compare: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
