#!/usr/bin/env python3
"""The polygons of cases/boxes/still_trough.opts (issue 48): a tank's section with a half-cylinder
trough under the middle of its floor, and the water that fills it.

  tools/trough_polygons.py [--width W] [--depth H] [--radius R] [--top Y] [--thickness T] [--edges N] [--out PREFIX]

writes PREFIX_wall.txt (the walls: the tank's section, T thick below the trough, up to Y) and
PREFIX_water.txt (water H deep over the floor, the trough full), x y one vertex a line, for
-polygon_K_file.  Defaults: W 0.2, H 0.1, R 0.04, Y 0.15, T 0.015 (3 rows of 5 mm), N 48 edges on the arc.
"""
import argparse, math

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--width", type=float, default=0.2)
ap.add_argument("--depth", type=float, default=0.1)
ap.add_argument("--radius", type=float, default=0.04)
ap.add_argument("--top", type=float, default=0.15)
ap.add_argument("--thickness", type=float, default=0.015)
ap.add_argument("--edges", type=int, default=48)
ap.add_argument("--out", default="cases/boxes/still_trough")
a = ap.parse_args()
W, H, R, top, t, n = a.width, a.depth, a.radius, a.top, a.thickness, a.edges
arc = [(W / 2 + R * math.cos(math.pi * (1 + k / n)), R * math.sin(math.pi * (1 + k / n))) for k in range(n + 1)]
wall = [(0, top), (0, 0)] + arc + [(W, 0), (W, top), (W + t, top), (W + t, -R - t), (-t, -R - t), (-t, top)]
water = [(0, 0)] + arc + [(W, 0), (W, H), (0, H)]
hdr = "# %s (x y, m, one vertex a line; tools/trough_polygons.py --width %g --depth %g --radius %g --top %g --thickness %g --edges %d)\n" % ("%s", W, H, R, top, t, n)
for name, pts, what in (("wall", wall, "the tank's walls with a half-cylinder trough under its floor"), ("water", water, "the water over the floor and in the trough")):
    with open(f"{a.out}_{name}.txt", "w") as f:
        f.write(hdr % what + "".join(f"{x:.9g} {y:.9g}\n" for x, y in pts))
