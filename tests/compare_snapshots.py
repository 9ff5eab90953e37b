#!/usr/bin/env python3
"""Compare the last snapshots of two runs particle by particle (matched by id): the same particles,
and x, v, p, rho equal within TOL relative to each field's largest magnitude (0 = bit for bit).
Usage: compare_snapshots.py DIR_A DIR_B [TOL]"""
import glob
import sys

import h5py
import numpy as np

a, b = sys.argv[1], sys.argv[2]
tol = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
fa, fb = sorted(glob.glob(a + "/particles_*.h5")), sorted(glob.glob(b + "/particles_*.h5"))
if not fa or not fb or len(fa) != len(fb):
    sys.exit(f"snapshots: {len(fa)} in {a}, {len(fb)} in {b}")
with h5py.File(fa[-1]) as A, h5py.File(fb[-1]) as B:
    ia, ib = np.argsort(A["id"][:].ravel()), np.argsort(B["id"][:].ravel())
    if not np.array_equal(A["id"][:].ravel()[ia], B["id"][:].ravel()[ib]) or not np.array_equal(A["kind"][:].ravel()[ia], B["kind"][:].ravel()[ib]):
        sys.exit("the runs have different particles (ids or kinds)")
    worst = {k: float(np.max(np.abs(A[k][:][ia] - B[k][:][ib])) / max(float(np.max(np.abs(A[k][:]))), 1e-300)) for k in ("x", "v", "p", "rho")}
print(f"{len(ia)} particles, largest differences relative to each field's largest value: " + ", ".join(f"{k} {d:.3g}" for k, d in worst.items()))
sys.exit(0 if all(d <= tol for d in worst.values()) else 1)
