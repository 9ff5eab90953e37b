#!/usr/bin/env python3
"""Write closed triangulated surfaces as STL files (binary, or ASCII with --ascii) for -stl_K of
-case boxes (docs/geometry.md, "STL surfaces").

  tools/stl_write.py box x0,y0,z0,x1,y1,z1 OUT.stl [--ascii]      an axis-aligned box, 12 triangles
  tools/stl_write.py sphere x,y,z,r OUT.stl [--subdiv N] [--ascii] an icosphere, 20 * 4^N triangles
  tools/stl_write.py vessel x0,y0,z0,x1,y1,z1,t,r[,cx,cy] OUT.stl   an open-top tank, walls t thick around the
                                                                 inside x0..x1, y0..y1, z0..z1, a hemispherical bowl
                                                                 of radius r (0: none) in its floor at cx,cy (the
                                                                 middle); --nphi, --nring: the bowl's mesh
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


def vessel(lo, hi, t, r, c, nphi=48, nring=12):
    """An open-top tank as one closed surface: the walls t thick around the inside lo..hi (its top
    at hi[2] is open), its floor at lo[2] with a hemispherical bowl of radius r (0: none) centred at
    c = (cx, cy) on the floor, and the bottom t below the bowl's lowest point.  Each triangle is
    turned to face out of the walls (into the water's space on the inner faces)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    zb = z0 - r - t
    X0, Y0, X1, Y1 = x0 - t, y0 - t, x1 + t, y1 + t
    faces = []  # (triangles, the outward direction: a vector, or a point the faces face towards)

    def quad(a, b, cc, d):
        return [(a, b, cc), (a, cc, d)]
    faces.append((quad((X0, Y0, zb), (X1, Y0, zb), (X1, Y1, zb), (X0, Y1, zb)), (0, 0, -1)))
    faces.append((quad((X0, Y0, zb), (X0, Y1, zb), (X0, Y1, z1), (X0, Y0, z1)), (-1, 0, 0)))
    faces.append((quad((X1, Y0, zb), (X1, Y1, zb), (X1, Y1, z1), (X1, Y0, z1)), (1, 0, 0)))
    faces.append((quad((X0, Y0, zb), (X1, Y0, zb), (X1, Y0, z1), (X0, Y0, z1)), (0, -1, 0)))
    faces.append((quad((X0, Y1, zb), (X1, Y1, zb), (X1, Y1, z1), (X0, Y1, z1)), (0, 1, 0)))
    oc = [(X0, Y0), (X1, Y0), (X1, Y1), (X0, Y1)]
    ic = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for k in range(4):  # the rim at the top, between the outer and the inner square
        a, b = oc[k], oc[(k + 1) % 4]
        p, q = ic[k], ic[(k + 1) % 4]
        faces.append((quad((*a, z1), (*b, z1), (*q, z1), (*p, z1)), (0, 0, 1)))
    # the floor's edge: rays from the bowl's centre through the rim's vertices, and the corners
    cx, cy = c
    edge = []  # (angle, (x, y)) on the inner square, counter-clockwise
    phis = [2 * math.pi * k / nphi for k in range(nphi)] if r > 0 else []
    for ph in phis:
        dx, dy = math.cos(ph), math.sin(ph)
        hits = []
        if dx > 1e-12: hits.append(((x1 - cx) / dx, "x1"))
        if dx < -1e-12: hits.append(((x0 - cx) / dx, "x0"))
        if dy > 1e-12: hits.append(((y1 - cy) / dy, "y1"))
        if dy < -1e-12: hits.append(((y0 - cy) / dy, "y0"))
        s, side = min(hits)
        px, py = cx + s * dx, cy + s * dy
        px = {"x0": x0, "x1": x1}.get(side, px)
        py = {"y0": y0, "y1": y1}.get(side, py)
        edge.append((ph, (px, py)))
    for (qx, qy) in ic:
        ang = math.atan2(qy - cy, qx - cx) % (2 * math.pi)
        if all(abs(p[0] - qx) > 1e-12 or abs(p[1] - qy) > 1e-12 for _, p in edge):
            edge.append((ang, (qx, qy)))
    edge.sort()
    for k in range(4):  # the inner walls, from the floor's edge up to the open top
        (ax, ay), (bx, by) = ic[k], ic[(k + 1) % 4]
        on = [p for _, p in edge if abs((p[0] - ax) * (by - ay) - (p[1] - ay) * (bx - ax)) < 1e-12]
        on.sort(key=lambda p: (p[0] - ax) * (bx - ax) + (p[1] - ay) * (by - ay))
        top = (ax, ay, z1)
        tris = [(top, (*on[i], z0), (*on[i + 1], z0)) for i in range(len(on) - 1)] + [(top, (*on[-1], z0), (bx, by, z1))]
        nx, ny = by - ay, -(bx - ax)  # the square runs counter-clockwise: its outward normal, turned inwards
        faces.append((tris, (-nx, -ny, 0)))
    if r == 0:
        faces.append((quad((x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)), (0, 0, 1)))
    else:
        rim = [(cx + r * math.cos(ph), cy + r * math.sin(ph)) for ph in phis]
        tris = []
        for k, ph in enumerate(phis):  # the floor between the rim and the edge, wedge by wedge
            k1 = (k + 1) % nphi
            ph1 = phis[k1] if k1 else 2 * math.pi
            wedge = [p for a, p in edge if ph <= a <= ph1] + [p for a, p in edge if k1 == 0 and a == 0]  # the last wedge ends at ray 0
            pk = (*rim[k], z0)
            for i in range(len(wedge) - 1):
                tris.append((pk, (*wedge[i], z0), (*wedge[i + 1], z0)))
            tris.append((pk, (*wedge[-1], z0), (*rim[k1], z0)))
        faces.append((tris, (0, 0, 1)))
        ring = lambda j: [(cx + r * math.cos(th) * math.cos(ph), cy + r * math.cos(th) * math.sin(ph), z0 - r * math.sin(th))
                          for th in [math.pi / 2 * j / nring] for ph in phis]
        rings = [[(*rim[k], z0) for k in range(nphi)]] + [ring(j) for j in range(1, nring)]
        pole = (cx, cy, z0 - r)
        tris = []
        for j in range(nring - 1):
            for k in range(nphi):
                k1 = (k + 1) % nphi
                tris += quad(rings[j][k], rings[j][k1], rings[j + 1][k1], rings[j + 1][k])
        tris += [(rings[-1][k], rings[-1][(k + 1) % nphi], pole) for k in range(nphi)]
        faces.append((tris, ("towards", (cx, cy, z0))))
    out = []
    for tris, d in faces:
        for tri in tris:
            a, b, cc = (np.array(p, dtype=float) for p in tri)
            n = np.cross(b - a, cc - a)
            want = np.array(d[1]) - (a + b + cc) / 3 if d[0] == "towards" else np.array(d, dtype=float)
            out.append(tri if n @ want > 0 else (tri[0], tri[2], tri[1]))
    return out


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
ap.add_argument("shape", choices=["box", "sphere", "vessel"])
ap.add_argument("numbers")
ap.add_argument("out")
ap.add_argument("--subdiv", type=int, default=3)
ap.add_argument("--ascii", action="store_true")
ap.add_argument("--nphi", type=int, default=48, help="vessel: the bowl's vertices around")
ap.add_argument("--nring", type=int, default=12, help="vessel: the bowl's rings from rim to pole")
ap.add_argument("--open", type=int, default=0, help="drop this many triangles (an open surface, for tests)")
a = ap.parse_args()
x = [float(s) for s in a.numbers.split(",")]
if a.shape == "box": tris = box(x[:3], x[3:])
elif a.shape == "sphere": tris = icosphere(x[:3], x[3], a.subdiv)
else: tris = vessel(x[:3], x[3:6], x[6], x[7], x[8:10] if len(x) > 8 else ((x[0] + x[3]) / 2, (x[1] + x[4]) / 2), a.nphi, a.nring)
write(tris[: len(tris) - a.open], a.out, a.ascii)
print(f"{a.out}: {len(tris) - a.open} triangles")
