#!/usr/bin/env python3
"""Far-wall pressure of dam-break runs against the experiment: Lobovsky et al. 2014 sensors 1 and 3
(the first impact, t sqrt(g/H) 2.3-3.3, and the whole run) or Buchner 2002 P1.
Usage: tools/plot_impact.py lobovsky|buchner PNG LABEL=OUTDIR [LABEL=OUTDIR ...]"""
import csv, math, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refdata_csv import load_ref  # noqa: E402

if len(sys.argv) < 4 or sys.argv[1] not in ("lobovsky", "buchner"):
    sys.exit(__doc__)
case, png, runs = sys.argv[1], sys.argv[2], [a.split("=", 1) for a in sys.argv[3:]]
g, rho0 = 9.81, 1000.0
if case == "lobovsky":
    H, ref = 0.3, load_ref("lobovsky2014_H0.3_pressure_peak_event5.csv")
    panels = [("P1", "s1_y0.003m", "sensor 1, y = 3 mm", (2.3, 3.3)), ("P1", "s1_y0.003m", "sensor 1", (2.0, 8.0)),
              ("P3", "s3_y0.030m", "sensor 3, y = 30 mm", (2.3, 3.3)), ("P4", "s4_y0.080m", "sensor 4, y = 80 mm", (2.0, 8.0))]
else:
    H, ref = 0.6, load_ref("buchner2002_dambreak_H0.6_pressure_P1__trixiparticles.csv")
    panels = [("P1", "p_star", "P1, y = 0.16 m", (2.0, 7.0))]
ts = math.sqrt(H / g)
fig, axes = plt.subplots(len(panels), 1, figsize=(10, 3.2 * len(panels)), squeeze=False)
for ax, (col, rcol, title, xlim) in zip(axes[:, 0], panels):
    ax.plot(ref["t_star"], ref[rcol], color="k", lw=1.2, label="experiment")
    for label, out in runs:
        rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
        t = np.array([float(r["t"]) for r in rows]) / ts
        ax.plot(t, np.array([float(r[col]) for r in rows]) / (rho0 * g * H), lw=0.8, label=label)
    ax.set_xlim(*xlim); ax.grid(alpha=0.3)
    if col == "P1" and case == "lobovsky": ax.set_ylim(-6, 12)  # a one-step ISPH spike may run off the scale
    ax.set_ylabel(f"{title}: p / ρgH")
axes[0, 0].legend(fontsize=8, ncol=2)
axes[-1, 0].set_xlabel("t √(g/H)")
fig.suptitle("Dam break far-wall pressure: " + ("Lobovsky et al. 2014, H = 0.3 m (event 5)" if case == "lobovsky" else "Buchner 2002, H = 0.6 m"))
fig.savefig(png, dpi=90, bbox_inches="tight")
