#!/usr/bin/env python3
"""Still water: the largest water speed from time T0 on (probes.csv v_max) and the largest
displacement of a water particle between the first and the last snapshot, in dx, against the
targets of issue 48 (0.01 sqrt(g H), 1 dx).
  tools/still_check.py OUTDIR [--h H] [--t0 T0] [--vbound FRACTION] [--drift DX]
Exit status 1 when a bound is missed (the bounds are only checked when given)."""
import argparse, csv, glob, json, math, sys
import h5py, numpy as np
ap = argparse.ArgumentParser()
ap.add_argument("out"); ap.add_argument("--h", type=float, default=0.1); ap.add_argument("--t0", type=float, default=0)
ap.add_argument("--vbound", type=float); ap.add_argument("--drift", type=float)
a = ap.parse_args()
s = json.load(open(a.out + "/summary.json")); dx = s["dx"]
rows = list(csv.DictReader(open(a.out + "/probes.csv")))
vmax = max(float(r["v_max"]) for r in rows if float(r["t"]) >= a.t0)
snaps = sorted(glob.glob(a.out + "/particles_*.h5"))
def fluid(f):
    d = h5py.File(f, "r"); k = d["kind"][:].ravel() == 0; i = d["id"][:].ravel()[k]; o = np.argsort(i)
    return i[o], d["x"][:][k][o], float(d.attrs.get("time", 0))
(i0, x0, t0), (i1, x1, t1) = fluid(snaps[0]), fluid(snaps[-1])
assert np.array_equal(i0, i1), "the water particles changed"
drift = np.linalg.norm(x1 - x0, axis=1).max() / dx
ref = math.sqrt(9.81 * a.h)
print(f"still water ({s['fluid']}, dx {dx:g}): v_max {vmax:.3g} m/s = {vmax / ref:.2g} sqrt(gH) from t = {a.t0:g} s; largest displacement {drift:.2f} dx from t = {t0:g} to {t1:g} s")
ok = (a.vbound is None or vmax <= a.vbound * ref) and (a.drift is None or drift <= a.drift)
sys.exit(0 if ok else 1)
