#!/usr/bin/env python3
"""tip_y of oscillating-plate runs against time, with the analytic (thin-plate, small-amplitude)
motion A sin(omega t).   tools/plot_plate.py PNG OUTDIR [OUTDIR ...]"""
import csv, json, math, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

png, dirs = sys.argv[1], sys.argv[2:]
fig, ax = plt.subplots(figsize=(8, 3.5))
for d in dirs:
    rows = list(csv.DictReader(open(d + "/probes.csv")))
    s = json.load(open(d + "/summary.json")); e = s["errors"]
    ax.plot([float(r["t"]) for r in rows], [1000 * float(r["tip_y"]) for r in rows],
            label=f"SPH, {e['plate_ny']} across: T c0/L {e['period_c0_over_L']:.1f}")
T, A = e["period_s_analytic"], e["amplitude_over_L_analytic"] * 0.2 * 1000
t = [i * 0.8 / 400 for i in range(401)]
ax.plot(t, [A * math.sin(2 * math.pi * x / T) for x in t], "k--", label="thin plate: T c0/L 72.4")
ax.set_xlabel("t (s)"); ax.set_ylabel("tip_y (mm)"); ax.legend(fontsize=8, loc="lower left"); ax.grid(alpha=0.3)
fig.tight_layout(); fig.savefig(png, dpi=110)
print("wrote", png)
