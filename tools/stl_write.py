#!/usr/bin/env python3
"""Write closed triangulated surfaces as STL files (binary, or ASCII with --ascii) for -stl_K of
-case boxes (docs/geometry.md, "STL surfaces").

  tools/stl_write.py box x0,y0,z0,x1,y1,z1 OUT.stl [--ascii]      an axis-aligned box, 12 triangles
  tools/stl_write.py sphere x,y,z,r OUT.stl [--subdiv N] [--ascii] an icosphere, 20 * 4^N triangles
  tools/stl_write.py box ... OUT.stl --open 1                       drop N triangles (bad input, tests)
  tools/stl_write.py --ascii box -- -0.1,-0.05,0,0.1,0.05,0.2 OUT.stl   numbers beginning with '-': options first, then --

The triangles face outwards (counter-clockwise seen from outside).  A binary file holds float32
numbers (the format's), so a box corner 0.6635 becomes 0.66350001; an ASCII file writes the numbers
as given (Python's shortest repr of the double), so sphfsi reads exactly the numbers of the options:
cases/boxes/spheric_test2_box.stl is ASCII for that reason (docs/geometry.md)."""
import argparse, math, struct

import numpy as np


def box(lo, hi):
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for a, b, c, d in quads:
        tris += [(v[a], v[b], v[c]), (v[a], v[c], v[d])]
    return tris


def icosphere(c, r, n):
    t = (1 + math.sqrt(5)) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(x / math.sqrt(sum(y * y for y in p)) for x in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(n):
        mid, g = {}, []
        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = [(x + y) / 2 for x, y in zip(v[a], v[b])]
                l = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / l for x in p)); mid[k] = len(v) - 1
            return mid[k]
        for a, b, d in f:
            ab, bd, da = m(a, b), m(b, d), m(d, a)
            g += [(a, ab, da), (b, bd, ab), (d, da, bd), (ab, bd, da)]
        f = g
    p = [tuple(ci + r * x for ci, x in zip(c, q)) for q in v]
    return [(p[a], p[b], p[d]) for a, b, d in f]


def write(tris, path, ascii):
    t = np.asarray(tris, dtype=np.float64 if ascii else np.float32)  # n x 3 x 3
    nrm = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-30)
    if ascii:
        with open(path, "w") as f:
            f.write("solid sphfsi\n")
            for n, tri in zip(nrm, t):
                f.write("  facet normal %r %r %r\n    outer loop\n" % tuple(round(float(x), 9) for x in n))
                for p in tri:
                    f.write("      vertex %r %r %r\n" % tuple(float(x) for x in p))
                f.write("    endloop\n  endfacet\n")
            f.write("endsolid sphfsi\n")
    else:
        with open(path, "wb") as f:
            f.write(b"binary STL written by tools/stl_write.py".ljust(80, b" "))
            f.write(struct.pack("<I", len(t)))
            for n, tri in zip(nrm, t):
                f.write(struct.pack("<12f", *n, *tri.ravel()) + b"\0\0")


ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("shape", choices=["box", "sphere"])
ap.add_argument("numbers")
ap.add_argument("out")
ap.add_argument("--subdiv", type=int, default=3)
ap.add_argument("--ascii", action="store_true")
ap.add_argument("--open", type=int, default=0, help="drop this many triangles (an open surface, for tests)")
a = ap.parse_args()
x = [float(s) for s in a.numbers.split(",")]
tris = box(x[:3], x[3:]) if a.shape == "box" else icosphere(x[:3], x[3], a.subdiv)
write(tris[: len(tris) - a.open], a.out, a.ascii)
print(f"{a.out}: {len(tris) - a.open} triangles")
