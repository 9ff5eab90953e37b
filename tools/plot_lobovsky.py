#!/usr/bin/env python3
"""Water levels H1..H4 and far-wall pressures P1..P4 of dam_break_lobovsky runs against Lobovsky et
al. (2014), H = 0.3 m.  Usage: tools/plot_lobovsky.py PNG LABEL=OUTDIR [LABEL=OUTDIR ...]"""
import csv, math, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refdata_csv import load_ref  # noqa: E402

H, g, rho0 = 0.3, 9.81, 1000.0
if len(sys.argv) < 3:
    sys.exit(__doc__)
png, runs = sys.argv[1], [a.split("=", 1) for a in sys.argv[2:]]
lev = load_ref("lobovsky2014_H0.3_water_levels.csv")
pre = load_ref("lobovsky2014_H0.3_pressure_peak_event5.csv")
gauges = ["H1_2_x0.300m", "H2_3_x0.865m", "H3_3_x1.114m", "H4_4_x1.3625m"]
sensors = ["s1_y0.003m", "s2_y0.015m", "s3_y0.030m", "s4_y0.080m"]
ts = math.sqrt(H / g)

fig, axes = plt.subplots(4, 2, figsize=(12, 11), sharex=True)
for k in range(4):
    axl, axp = axes[k]
    axl.plot(lev["t_star"], lev[gauges[k]], "k.", ms=2, label="experiment")
    axp.plot(pre["t_star"], pre[sensors[k]], color="0.6", lw=0.5, label="experiment (event 5)")
    for label, out in runs:
        rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
        t = np.array([float(r["t"]) for r in rows]) / ts
        axl.plot(t, np.array([float(r[f"H{k + 1}"]) for r in rows]) / H, lw=1, label=label)
        axp.plot(t, np.array([float(r[f"P{k + 1}"]) for r in rows]) / (rho0 * g * H), lw=0.8, label=label)
    axl.set_ylabel(f"H{k + 1}: h / H"); axp.set_ylabel(f"P{k + 1}: p / ρgH")
    axp.set_ylim(-0.5, 4)
    for ax in (axl, axp):
        ax.grid(alpha=0.3); ax.set_xlim(0, 8)
axes[0, 0].legend(fontsize=8); axes[0, 1].legend(fontsize=8)
axes[3, 0].set_xlabel("t sqrt(g/H)"); axes[3, 1].set_xlabel("t sqrt(g/H)")
fig.suptitle("Dam break, Lobovsky et al. 2014 (H = 0.3 m): water levels and far-wall pressures")
fig.savefig(png, dpi=100, bbox_inches="tight")
print(f"wrote {png}")
