#!/usr/bin/env python3
"""Still water over a curved floor, drawn from its snapshots (docs/geometry.md, issue 48).

  tools/plot_still.py PNG RUN [RUN ...] [--slice Y] [--h H]

Left: the first RUN's last snapshot (3D: the row of particles nearest the plane y = Y, default
the domain's middle), walls red, dummies black, each water particle coloured by its
displacement from the first snapshot in dx.  Right: the largest water speed (probes.csv v_max) of
every RUN against time, in sqrt(g H) (H: the depth the targets use, default 0.1 m), with the
target 0.01.  Needs numpy, h5py, matplotlib."""
import argparse, csv, glob, json, math

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("png")
ap.add_argument("runs", nargs="+")
ap.add_argument("--slice", type=float)
ap.add_argument("--h", type=float, default=0.1)
a = ap.parse_args()


def load(f):
    with h5py.File(f, "r") as d:
        return d["x"][:], d["kind"][:].ravel(), d["id"][:].ravel(), float(np.ravel(d.attrs["time"])[0])


run = a.runs[0]
s = json.load(open(run + "/summary.json"))
dx = s["dx"]
snaps = sorted(glob.glob(run + "/particles_*.h5"))
x0, k0, i0, _ = load(snaps[0])
x1, k1, i1, t1 = load(snaps[-1])
start = dict(zip(i0[k0 == 0], x0[k0 == 0]))
D = x1.shape[1]
keep = np.ones(len(k1), bool)
if D == 3:
    y = a.slice if a.slice is not None else 0.5 * (x1[:, 1].min() + x1[:, 1].max())
    y = x1[np.argmin(np.abs(x1[:, 1] - y)), 1]  # the nearest row of particles
    keep = np.abs(x1[:, 1] - y) < 0.5 * dx
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1.2, 1]})
xs, zs = x1[keep][:, 0], x1[keep][:, D - 1]
kk = k1[keep]
for kind, col in ((1, "tab:red"), (2, "k")):
    ax.scatter(xs[kk == kind], zs[kk == kind], s=6, c=col, marker="s", lw=0)
w = kk == 0
disp = np.array([np.linalg.norm(p - start[i]) / dx for p, i in zip(x1[keep][w], i1[keep][w])])
sc = ax.scatter(xs[w], zs[w], s=8, c=disp, cmap="viridis", vmin=0, vmax=max(disp.max(), 1e-3), lw=0)
fig.colorbar(sc, ax=ax, label=f"displacement over {t1:.3g} s (dx)")
ax.set_aspect("equal")
ax.set_title(f"{s['fluid'].upper()}, dx = {dx:g} m" + (f", slice y = {y:.3g} m" if D == 3 else ""))
for r in a.runs:
    rows = list(csv.DictReader(open(r + "/probes.csv")))
    fl = json.load(open(r + "/summary.json"))["fluid"].upper()
    bx.semilogy([float(q["t"]) for q in rows], [max(float(q["v_max"]), 1e-9) / math.sqrt(9.81 * a.h) for q in rows], label=fl)
bx.axhline(0.01, color="r", ls="--", label="target 0.01 (from 5 s)")
bx.set_ylim(bottom=1e-6)
bx.set_xlabel("t (s)")
bx.set_ylabel("largest water speed / √(gH)")
bx.legend()
fig.tight_layout()
fig.savefig(a.png, dpi=110)
print(f"{a.png}: {len(snaps)} snapshots of {run}, largest displacement {disp.max():.2f} dx in the slice")
