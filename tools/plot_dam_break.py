#!/usr/bin/env python3
"""Picture of a dam-break run: particle snapshots coloured by pressure, and the surge front
against Martin & Moyce (1952).  Usage: tools/plot_dam_break.py OUTDIR [PNG]"""
import csv, glob, math, os, sys
import h5py
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refdata_csv import ref_path  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "out/dam_break"
png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "dam_break.png")
a, g = 0.05715, 9.81

snaps = sorted(glob.glob(os.path.join(out, "particles_*.h5")))
if not snaps:
    sys.exit(f"no snapshots in {out}: run with -output_interval > 0")
want = [0.0, 0.05, 0.10, 0.15, 0.20, 0.30]
times = []
for s in snaps:
    with h5py.File(s, "r") as f:
        times.append(float(f.attrs["time"]))
pick = sorted({min(range(len(times)), key=lambda i: abs(times[i] - w)) for w in want})

fig = plt.figure(figsize=(13, 7))
for k, i in enumerate(pick[:6]):
    ax = fig.add_subplot(3, 3, k + 1 if k < 3 else k + 1)
    with h5py.File(snaps[i], "r") as f:
        x = f["x"][:]; p = f["p"][:]; kind = f["kind"][:].ravel()
    fl = kind == 0
    ax.scatter(x[~fl, 0], x[~fl, 1], s=0.5, c="0.6")
    sc = ax.scatter(x[fl, 0], x[fl, 1], s=0.8, c=p[fl], cmap="viridis", vmin=0, vmax=1000 * g * 2 * a)
    ax.set_aspect("equal"); ax.set_xlim(-0.01, 5.25 * a + 0.01); ax.set_ylim(-0.01, 2.2 * a)
    ax.set_title(f"t = {times[i]:.3f} s (T = {times[i] * math.sqrt(2 * g / a):.2f})", fontsize=9)
    ax.tick_params(labelsize=7)
fig.colorbar(sc, ax=fig.axes, shrink=0.6, label="p (Pa)")

ax = fig.add_subplot(3, 1, 3)
rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
t = np.array([float(r["t"]) for r in rows]); fx = np.array([float(r["front_x"]) for r in rows])
ax.plot(t * math.sqrt(2 * g / a), fx / a, label="sphfsi WCSPH")
for name, lab, mk in [("martin_moyce1952_surge_n2eq2_a2.25in__pysph.csv", "Martin & Moyce 1952 (a = 2.25 in)", "o"),
                      ("martin_moyce1952_surge_n2eq2_a1.125in__pysph.csv", "Martin & Moyce 1952 (a = 1.125 in)", "s"),
                      ("koshizuka_oka1996_surge__pysph.csv", "Koshizuka & Oka 1996", "^")]:
    path = ref_path(name, f"{lab} is not drawn")
    if path:
        d = np.array([[float(v) for v in l.split(",")[:2]] for l in open(path) if l[:1].isdigit()])
        ax.plot(d[:, 0], d[:, 1], mk, ms=4, label=lab)
ax.set_xlabel("T = t sqrt(2g/a)"); ax.set_ylabel("Z = front / a"); ax.set_xlim(0, max(3.5, t[-1] * math.sqrt(2 * g / a)))
ax.set_ylim(1, None); ax.legend(fontsize=8); ax.grid(alpha=0.3)
fig.savefig(png, dpi=110, bbox_inches="tight")
print(f"wrote {png}")
