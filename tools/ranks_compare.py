#!/usr/bin/env python3
"""Two runs of one case on different rank counts (or one restarted), compared particle by particle by id
(tools/ranks.sh).

  ranks_compare.py REF RUN [--tol T] [--checkpoint] [--last]

Every snapshot particles_*.h5 of RUN against REF's of the same name (--last: the last one only): the
same ids and kinds, the same step, and every other dataset within T relative to that dataset's largest
magnitude in REF (T = 0: bit for bit; integer datasets, e.g. ISPH's free_surface flags, must be equal
at T = 0 and are counted otherwise); probes.csv row by row, every column within max(T, 1e-12) of its
largest magnitude (probes that sum over particles reduce across ranks in another order, as in
tests/test_restart.c); with --checkpoint also checkpoint.h5: its particle datasets by id as above, its
tables (probe rows, kept series, snapshot times) as the probes, and the attributes that describe the
state (step, time, dt, particles, next id and output times) equal within T.  --field_tol NAME=T2 gives
one dataset a bound of its own (reported apart), e.g. a solid's acceleration in the checkpoint.  The partition and the
per-rank counts are left out: they are the decomposition, not the state.
Prints the two largest differences (particle state, probes and tables) on one line, then a line
'max relative difference D (bound T) ...' that names the worst dataset; exits 1 when D > T, the probes
differ by more than max(T, 1e-12), or anything is missing or unequal."""
import glob
import os
import sys

import h5py
import numpy as np

import argparse

ap = argparse.ArgumentParser()
ap.add_argument("ref"); ap.add_argument("run")
ap.add_argument("--tol", type=float, default=0.0)
ap.add_argument("--checkpoint", action="store_true"); ap.add_argument("--last", action="store_true")
ap.add_argument("--field_tol", action="append", default=[], metavar="NAME=T", help="another bound for one dataset")
opt = ap.parse_args()
ref, run, tol = opt.ref, opt.run, opt.tol
ftol = {k: float(v) for k, v in (f.split("=") for f in opt.field_tol)}
fworst = {k: [0.0, ""] for k in ftol}  # the datasets with their own bound
ptol = max(tol, 1e-12)
worst = [0.0, ""]       # particle fields: largest relative difference, where
pworst = [0.0, ""]      # probes and tables
flips = [0, ""]         # integer datasets that differ (ISPH's flags at T > 0)
problems = []


def rel(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return np.inf
    if a.size == 0:
        return 0.0
    both_nan = np.isnan(a) & np.isnan(b)
    d = np.where(both_nan, 0.0, np.abs(a - b))
    scale = np.nanmax(np.abs(a)) if np.isfinite(a).any() else 0.0
    m = float(np.nanmax(d)) if d.size else 0.0
    if np.isnan(a).sum() != np.isnan(b).sum():
        return np.inf
    return m / scale if scale > 0 else m


def note(w, d, where):
    if d > w[0] or (d == np.inf and not w[1]):
        w[0], w[1] = d, where


def particles(A, B, name, skip=()):
    """the datasets with one row per particle, sorted by id"""
    ia, ib = A["id"][:].ravel(), B["id"][:].ravel()
    n = len(ia)
    oa, ob = np.argsort(ia, kind="stable"), np.argsort(ib, kind="stable")
    if len(ib) != n or not np.array_equal(ia[oa], ib[ob]):
        problems.append(f"{name}: different particles ({n} and {len(ib)}, ids differ)")
        return
    for k in A:
        if k in skip or k == "id" or not isinstance(A[k], h5py.Dataset) or A[k].shape[:1] != (n,):
            continue
        if k not in B:
            problems.append(f"{name}: no dataset {k} in {run}")
            continue
        a, b = A[k][()][oa], B[k][()][ob]
        if a.dtype.kind in "iub":
            nd = int(np.sum(np.any((a != b).reshape(n, -1), axis=1)))
            if nd and (tol == 0 or k == "kind"):
                note(worst, np.inf, f"{name}:{k} ({nd} particles)")
            elif nd and nd > flips[0]:
                flips[0], flips[1] = nd, f"{name}:{k}"
        else:
            note(fworst[k] if k in ftol else worst, rel(a, b), f"{name}:{k}")
    for k in B:
        if k not in A and isinstance(B[k], h5py.Dataset):
            problems.append(f"{name}: dataset {k} only in {run}")


fa = sorted(os.path.basename(f) for f in glob.glob(ref + "/particles_*.h5"))
fb = sorted(os.path.basename(f) for f in glob.glob(run + "/particles_*.h5"))
if not fa or fa != fb:
    problems.append(f"snapshots: {len(fa)} in {ref}, {len(fb)} in {run}")
for f in (fa[-1:] if opt.last else fa) if fa == fb else []:
    with h5py.File(os.path.join(ref, f)) as A, h5py.File(os.path.join(run, f)) as B:
        if int(A.attrs["step"]) != int(B.attrs["step"]):
            problems.append(f"{f}: step {int(B.attrs['step'])}, reference {int(A.attrs['step'])}")
        note(worst, rel(A.attrs["time"], B.attrs["time"]), f"{f}:time")
        particles(A, B, f)

pa, pb = os.path.join(ref, "probes.csv"), os.path.join(run, "probes.csv")
if os.path.exists(pa):
    ta, tb = np.genfromtxt(pa, delimiter=",", skip_header=1, ndmin=2), np.genfromtxt(pb, delimiter=",", skip_header=1, ndmin=2) if os.path.exists(pb) else None
    if tb is None or ta.shape != tb.shape:
        problems.append(f"probes.csv: {ta.shape[0]} rows in {ref}, {'none' if tb is None else tb.shape[0]} in {run}")
    else:
        for c in range(ta.shape[1]):
            note(pworst, rel(ta[:, c], tb[:, c]), f"probes.csv column {c}")

nck = 0
if opt.checkpoint:
    ca, cb = os.path.join(ref, "checkpoint.h5"), os.path.join(run, "checkpoint.h5")
    if not (os.path.exists(ca) and os.path.exists(cb)):
        problems.append("checkpoint.h5 missing")
    else:
        with h5py.File(ca) as A, h5py.File(cb) as B:
            nck = 1
            n = A["id"].shape[0]
            particles(A, B, "checkpoint.h5", skip=("partition", "rank_counts", "row"))
            for k in A:
                if k in ("partition", "rank_counts", "row") or A[k].shape[:1] == (n,):
                    continue
                note(pworst, rel(A[k][()], B[k][()]) if k in B else np.inf, f"checkpoint.h5:{k}")
            for k in ("step", "particles", "next_id", "snapshots", "probe_rows"):
                if int(A.attrs[k]) != int(B.attrs[k]):
                    problems.append(f"checkpoint.h5: {k} {int(B.attrs[k])}, reference {int(A.attrs[k])}")
            for k in ("time", "dt", "next_output", "next_checkpoint", "next_probe", "mass_out"):
                note(worst, rel(A.attrs[k], B.attrs[k]), f"checkpoint.h5:@{k}")
            note(pworst, rel(A.attrs["mass0"], B.attrs["mass0"]), "checkpoint.h5:@mass0")  # a sum over particles

ok = not problems and worst[0] <= tol and pworst[0] <= ptol and all(fworst[k][0] <= ftol[k] for k in ftol)
msg = (f"max relative difference {worst[0]:.3g} (bound {tol:.0e}; worst {worst[1] or '-'}) over {len(fa)} snapshot(s)"
       f"{' and the checkpoint' if nck else ''}; probes/tables {pworst[0]:.3g} (bound {ptol:.0e})")
for k in ftol:
    msg += f"; {k} {fworst[k][0]:.3g} (bound {ftol[k]:.0e})"
if flips[0]:
    msg += f"; {flips[0]} particle(s) with another integer flag in {flips[1]}"
if problems:
    msg += "; " + "; ".join(problems[:3])
print(f"{worst[0]:.3g} {pworst[0]:.3g}" + "".join(f" {k} {fworst[k][0]:.3g}" for k in ftol))  # for tools/ranks.sh
print(msg)
sys.exit(0 if ok else 1)
