"""zlib settings on the arrays of a raw VTU (vemcontact --raw-vtu): compression time
(fastest of 3, processor time) and size for levels 0, 1, 2, 3, 6 and the Huffman-only
and RLE strategies, in vemcontact's block layout (262144-byte blocks, one zlib stream
each; src/output/vtu.f90).  Python's zlib is the same C library the code links.

    python bench/vtu_zlib_levels.py RAW.vtu
"""
import base64
import re
import sys
import time
import zlib

BLOCK = 262144


def main(path):
    text = open(path).read()
    arrays = [base64.b64decode(m.group(1))[8:] for m in
              re.finditer(r'<DataArray [^>]*format="binary"[^>]*>\s*([A-Za-z0-9+/=]+)\s*</DataArray>', text)]
    total = sum(len(a) for a in arrays)
    print(f"{len(arrays)} arrays, {total / 1e6:.1f} MB raw")
    print("setting,seconds,MB,ratio")
    for name, level, strategy in [("level 1", 1, zlib.Z_DEFAULT_STRATEGY), ("level 2", 2, zlib.Z_DEFAULT_STRATEGY),
                                  ("level 3", 3, zlib.Z_DEFAULT_STRATEGY), ("level 6", 6, zlib.Z_DEFAULT_STRATEGY),
                                  ("huffman only", 1, zlib.Z_HUFFMAN_ONLY), ("rle", 1, zlib.Z_RLE),
                                  ("level 0", 0, zlib.Z_DEFAULT_STRATEGY)]:
        best = float("inf")
        for _ in range(3):
            t0 = time.process_time()
            size = 0
            for a in arrays:
                for k in range(0, len(a), BLOCK):
                    c = zlib.compressobj(level, zlib.DEFLATED, 15, 8, strategy)
                    size += len(c.compress(a[k:k + BLOCK]) + c.flush())
            best = min(best, time.process_time() - t0)
        print(f"{name},{best:.3f},{size / 1e6:.1f},{size / total:.3f}")


if __name__ == "__main__":
    main(sys.argv[1])
