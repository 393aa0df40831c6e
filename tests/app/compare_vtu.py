#!/usr/bin/env python3
"""Compare two solution VTU files of deal.II's DataOut cell by cell
(doc/parallel.md).

usage: compare_vtu.py A.vtu B.vtu TOLERANCE

A may hold one piece (one process wrote it) and B several (the ranks wrote
their cells into one file together, in another order). Each cell's patch
(its points in DataOut's order) is found by its points' coordinates; the
two files must hold the same cells and the same fields, and every point
value must agree to TOLERANCE relative to the largest magnitude of its
field in A. The data are Float32: a TOLERANCE below about 1e-6 asks for
more than the file holds. Prints the largest difference; exits non-zero
on a mismatch.
"""
import base64
import re
import struct
import sys
import zlib


def decode(text, dtype):
    """A zlib-compressed binary DataArray (DataOutBase::VtkFlags)."""
    text = "".join(text.split())
    n_blocks = struct.unpack("<I", base64.b64decode(text[:8])[:4])[0]
    header_bytes = 4 * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = struct.unpack("<%dI" % (3 + n_blocks),
                           base64.b64decode(text[:header_chars]))
    data = base64.b64decode(text[header_chars:])
    raw, offset = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(data[offset:offset + size])
        offset += size
    code = {"Float32": "f", "Float64": "d", "Int32": "i", "UInt8": "B"}[dtype]
    return struct.unpack("<%d%s" % (len(raw) // struct.calcsize(code), code),
                         raw)


ARRAY = re.compile(r'<DataArray type="(\w+)"([^>]*)>(.*?)</DataArray>', re.S)


def cells(path):
    """{cell key: {field: [values of the patch's points]}}, field sizes."""
    text = open(path).read()
    patches, n_cells = {}, 0
    for piece in re.findall(r"<Piece (.*?)</Piece>", text, re.S):
        arrays = {}
        for dtype, attributes, body in ARRAY.findall(piece):
            name = re.search(r'Name="(\w+)"', attributes)
            name = name.group(1) if name else "points"
            components = re.search(r'NumberOfComponents="(\d+)"', attributes)
            arrays[name] = (decode(body, dtype),
                            int(components.group(1)) if components else 1)
        points = arrays.pop("points")[0]
        n_cells += int(re.search(r'NumberOfCells="(\d+)"', piece).group(1))
        offsets = arrays.pop("offsets")[0]
        arrays.pop("connectivity")
        arrays.pop("types")
        n_points = len(points) // 3
        # DataOut's patch of build_patches(2): 3 x 3 points per mesh cell
        # and four VTK cells
        per_patch = 9
        if n_points % per_patch or len(offsets) != 4 * (n_points // 9):
            raise SystemExit("%s: not a patch of 3 x 3 points per cell" % path)
        for p in range(n_points // per_patch):
            rows = range(p * per_patch, (p + 1) * per_patch)
            key = tuple(round(points[3 * i + d], 4) for i in rows
                        for d in (0, 1))
            patches[key] = {
                name: [values[c * i + k] for i in rows for k in range(c)]
                for name, (values, c) in arrays.items()}
    return patches, n_cells


def main():
    a, a_cells = cells(sys.argv[1])
    b, b_cells = cells(sys.argv[2])
    tolerance = float(sys.argv[3])
    if a_cells != b_cells or a.keys() != b.keys():
        print("different cells: %d against %d" % (a_cells, b_cells))
        return 1
    fields = next(iter(a.values())).keys()
    scale = {f: max(max(abs(v) for v in p[f]) for p in a.values()) or 1.0
             for f in fields}
    worst, worst_field = 0.0, "none"
    for key, patch in a.items():
        if patch.keys() != b[key].keys():
            print("different fields:", sorted(patch), sorted(b[key]))
            return 1
        for f in fields:
            d = max(abs(x - y) for x, y in zip(patch[f], b[key][f])) / scale[f]
            if d > worst:
                worst, worst_field = d, f
    print("%d cells, %d fields agree; largest relative difference %.1e (%s)"
          % (len(a), len(fields), worst, worst_field))
    return 0 if worst <= tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
