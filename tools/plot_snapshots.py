#!/usr/bin/env python3
"""Snapshots of any run side by side: particles coloured by pressure (walls grey).

  tools/plot_snapshots.py OUTDIR PNG [t1 t2 ...]     (default: 4 times spread over the run)

Reads OUTDIR/particles_*.h5 (the snapshot nearest each time); shows up to a little above the water.  Needs numpy, h5py, matplotlib."""
import glob
import json
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if len(sys.argv) < 3:
    sys.exit(__doc__)
out, png = sys.argv[1], sys.argv[2]
files = sorted(glob.glob(out + "/particles_*.h5"))
if not files:
    sys.exit(f"no snapshots in {out} (run with -output_interval T)")
stamp = {f: float(np.ravel(h5py.File(f, "r").attrs["time"])[0]) for f in files}
times = [float(t) for t in sys.argv[3:]] or list(np.linspace(0, max(stamp.values()), 4))
snaps = []
for t in times:
    f = min(files, key=lambda f: abs(stamp[f] - t))
    with h5py.File(f, "r") as F:
        snaps.append((stamp[f], F["x"][:].reshape(-1, 2), F["kind"][:].ravel(), F["p"][:].ravel()))
fluid_p = np.concatenate([p[k == 0] for _, _, k, p in snaps])
vmax = np.percentile(fluid_p, 99) if fluid_p.size else 1
allx = np.concatenate([x for _, x, _, _ in snaps])
fluid_y = np.concatenate([x[k == 0, 1] for _, x, k, _ in snaps])
ytop = 1.15 * np.percentile(fluid_y, 99.5) if fluid_y.size else allx[:, 1].max()  # walls may reach far above the water
fig, axs = plt.subplots(1, len(snaps), figsize=(4 * len(snaps), 2.6), squeeze=False)
try:  # a marker about 0.8 of a particle spacing wide on a 4-inch (288 pt) panel, at least the 0.3 of large runs
    dx = json.load(open(out + "/summary.json"))["dx"]
    ms = max(0.3, (0.8 * 288 * dx / np.ptp(allx[:, 0])) ** 2)
except (OSError, KeyError, ValueError):
    ms = 0.3
for ax, (t, x, k, p) in zip(axs[0], snaps):
    fl = k == 0
    ax.scatter(x[~fl, 0], x[~fl, 1], s=ms, c="0.45", linewidths=0)
    sc = ax.scatter(x[fl, 0], x[fl, 1], s=ms, c=p[fl], cmap="viridis", vmin=0, vmax=vmax, linewidths=0)
    ax.set_aspect("equal")
    ax.set_xlim(allx[:, 0].min(), allx[:, 0].max())
    ax.set_ylim(allx[:, 1].min(), ytop)
    ax.set_title(f"t = {t:.2f} s")
    ax.set_xlabel("x (m)")
axs[0][0].set_ylabel("y (m)")
fig.colorbar(sc, ax=axs[0].tolist(), label="p (Pa)", shrink=0.8)
fig.savefig(png, dpi=90, bbox_inches="tight")
print(f"{png}: {len(snaps)} snapshots of {out}")
