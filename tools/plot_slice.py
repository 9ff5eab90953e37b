#!/usr/bin/env python3
"""A slice of a 3D run's snapshot: the row of particles nearest a plane, walls red, dummies black,
solids and clamps grey, the water coloured by its speed.

  tools/plot_slice.py OUTDIR PNG [--axis x|y|z] [--at VALUE] [--t TIME]

Defaults: the plane z = the domain's middle, the last snapshot.  Needs numpy, h5py, matplotlib."""
import argparse, glob

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("out")
ap.add_argument("png")
ap.add_argument("--axis", choices="xyz", default="z")
ap.add_argument("--at", type=float)
ap.add_argument("--t", type=float)
a = ap.parse_args()
files = sorted(glob.glob(a.out + "/particles_*.h5"))
if not files:
    raise SystemExit(f"no snapshots in {a.out} (run with -output_interval T)")
stamp = {f: float(np.ravel(h5py.File(f, "r").attrs["time"])[0]) for f in files}
f = files[-1] if a.t is None else min(files, key=lambda g: abs(stamp[g] - a.t))
with h5py.File(f, "r") as d:
    x, k, v, dx = d["x"][:], d["kind"][:].ravel(), d["v"][:], float(np.ravel(d.attrs["dx"])[0])
if x.shape[1] != 3:
    raise SystemExit("a 3D run's snapshots are needed (tools/plot_snapshots.py draws 2D runs)")
ax_i = "xyz".index(a.axis)
at = a.at if a.at is not None else 0.5 * (x[:, ax_i].min() + x[:, ax_i].max())
at = x[np.argmin(np.abs(x[:, ax_i] - at)), ax_i]  # the nearest row of particles
sel = np.abs(x[:, ax_i] - at) < 0.5 * dx
u, w = [i for i in range(3) if i != ax_i]
fig, ax = plt.subplots(figsize=(6, 5))
for kind, col in ((1, "tab:red"), (2, "k"), (3, "0.5"), (4, "0.3")):
    m = sel & (k == kind)
    ax.scatter(x[m, u], x[m, w], s=12, c=col, marker="s", lw=0)
m = sel & (k == 0)
sc = ax.scatter(x[m, u], x[m, w], s=12, c=np.linalg.norm(v[m], axis=1), cmap="viridis", lw=0)
fig.colorbar(sc, ax=ax, label="water speed (m/s)")
ax.set_aspect("equal")
ax.set_xlabel(f"{'xyz'[u]} (m)")
ax.set_ylabel(f"{'xyz'[w]} (m)")
ax.set_title(f"{a.axis} = {at:.4g} m, t = {stamp[f]:.4g} s")
fig.tight_layout()
fig.savefig(a.png, dpi=100)
print(f"{a.png}: {int(sel.sum())} particles of {f}")
