#!/usr/bin/env python3
"""Write a case's particles to an HDF5 file for `-case file` (docs/geometry.md has the schema).

The example: a 2D tank [0, L] x [0, T] with `rows` rows of wall particles (the first row KIND 1 wall,
the rest 2 dummy) under and beside it, water at rest filling [0, W] x [0, H], and a sloping beach of
wall particles rising from x = X0 at the slope 1:S (lattice points under the slope line, the rows
within `rows` spacings of it; the first row walls).  Positions on a lattice of spacing dx; masses,
densities and smoothing lengths are left to the program (rho0 dx^2, hydrostatic, h_factor dx).

  tools/particles_file.py OUT.h5 [--dx 0.01] [--rows 3] [--beach 1.0,3]
  mpiexec -n 2 bin/sphfsi -case file -particles_file OUT.h5 -t_end 1

The file holds x (N x 2), kind (N) and the attributes dx and domain; a user's own generator writes
the same (any of id, m, h, rho, v, p may be added: see docs/geometry.md).
"""
import argparse
import h5py
import numpy as np

FLUID, WALL, DUMMY = 0, 1, 2


def tank_case(dx, rows, L=2.0, T=1.0, W=0.6, H=0.4, beach=None):
    """Positions and kinds of the example; beach = (x0, S) or None."""
    xs = (np.arange(-rows, round(L / dx) + rows) + 0.5) * dx
    ys = (np.arange(-rows, round(T / dx)) + 0.5) * dx
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    X, Y = X.ravel(), Y.ravel()
    # depth into the walls, in spacings: > 0 outside the tank's interior [0, L] x [0, inf)
    depth = np.maximum.reduce([-X / dx, (X - L) / dx, -Y / dx, np.zeros_like(X)])
    if beach:
        x0, S = beach
        height = np.maximum(X - x0, 0) / S  # the beach's surface above the floor
        under = (height - Y) * S / np.hypot(1, S) / dx  # distance under the slope, in spacings
        depth = np.where((X > x0) & (under > 0) & (X <= L), np.maximum(depth, under), depth)
    kind = np.full(X.size, -1)
    kind[(depth > 0) & (depth <= 1)] = WALL
    kind[(depth > 1) & (depth <= rows)] = DUMMY
    fluid = (depth <= 0) & (X < W) & (Y < H)
    if beach:
        fluid &= ~((X > beach[0]) & (Y < np.maximum(X - beach[0], 0) / beach[1] + 0.5 * dx))
    kind[fluid] = FLUID
    keep = kind >= 0
    x = np.stack([X[keep], Y[keep]], axis=1)
    domain = [-(rows + 0.5) * dx, -(rows + 0.5) * dx, L + (rows + 0.5) * dx, 2 * T]
    return x, kind[keep], domain


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--dx", type=float, default=0.01)
    ap.add_argument("--rows", type=int, default=3, help="wall rows (3 covers 2h at h = 1.4 dx)")
    ap.add_argument("--beach", default=None, help="x0,S: a beach from x0 rising 1 in S (default: none)")
    a = ap.parse_args()
    beach = tuple(float(v) for v in a.beach.split(",")) if a.beach else None
    x, kind, domain = tank_case(a.dx, a.rows, beach=beach)
    with h5py.File(a.out, "w") as f:
        f["x"] = x
        f["kind"] = kind.astype(np.int32)
        f.attrs["dx"] = a.dx
        f.attrs["domain"] = np.array(domain, dtype=float)
    print(f"{a.out}: {len(x)} particles ({int((kind == FLUID).sum())} fluid), dx {a.dx}, domain {domain}")


if __name__ == "__main__":
    main()
