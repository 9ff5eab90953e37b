#!/usr/bin/env python3
"""Picture of a sluice-gate run: particle snapshots coloured by pressure (and a close-up of the gate
at the last one), and the discharge q(t) against the free-flow sluice relation
q = Cd a sqrt(2 g h_up), Cd = Cc / sqrt(1 + Cc a / h_up), with the measured h_up(t).
Usage: tools/plot_sluice_gate.py OUTDIR [PNG]   (OUTDIR default out/sluice_gate)"""
import csv, glob, json, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refdata_csv import ref_path  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "out/sluice_gate"
png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "sluice_gate.png")
g = 9.81

# Cc of a sharp-edged vertical gate from the reference table (key-value CSV)
Cc = 0.611
path = ref_path("sluice_gate_reference_coefficients.csv", f"Cc = {Cc} assumed")
if path:
    for line in open(path):
        if line.startswith("Cc_sharp_edged_vertical_gate,"):
            Cc = float(line.split(",")[1])
summ = json.load(open(os.path.join(out, "summary.json"))) if os.path.exists(os.path.join(out, "summary.json")) else {}
err = summ.get("errors", {})
a = err.get("gate_opening", 0.03)
win = err.get("q_window")

rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
t = np.array([float(r["t"]) for r in rows])
q = np.array([float(r["q"]) for r in rows])
hu = np.array([float(r["h_up"]) for r in rows])
hd = np.array([float(r["h_down"]) for r in rows])
qref = Cc / np.sqrt(1 + Cc * a / hu) * a * np.sqrt(2 * g * hu)

snaps = sorted(glob.glob(os.path.join(out, "particles_*.h5")))
fig = plt.figure(figsize=(13, 9))
gs = fig.add_gridspec(4, 3, height_ratios=[1, 1, 1.2, 1], hspace=0.45, wspace=0.15, right=0.9)
if snaps:
    import h5py
    times = []
    for s in snaps:
        with h5py.File(s, "r") as f:
            times.append(float(f.attrs["time"]))
    want = [0.0, 0.05, 0.1, 0.2, times[-1]]
    pick = sorted({min(range(len(times)), key=lambda i: abs(times[i] - w)) for w in want})[-5:]
    sc = None
    for k, i in enumerate(pick):
        with h5py.File(snaps[i], "r") as f:
            x = f["x"][:]; p = f["p"][:].ravel(); kind = f["kind"][:].ravel()
        fl = kind == 0
        ax = fig.add_subplot(gs[k // 3, k % 3])
        ax.scatter(x[~fl, 0], x[~fl, 1], s=0.3, c="0.6")
        sc = ax.scatter(x[fl, 0], x[fl, 1], s=0.6, c=p[fl], cmap="viridis", vmin=0, vmax=1000 * g * 0.14)
        ax.set_aspect("equal"); ax.set_xlim(-0.01, min(0.6, x[:, 0].max())); ax.set_ylim(-0.01, 0.16)
        ax.set_title(f"t = {times[i]:.3f} s", fontsize=9); ax.tick_params(labelsize=7)
    fig.colorbar(sc, cax=fig.add_axes([0.92, 0.62, 0.01, 0.26]), label="p (Pa)")
    # close-up of the gate at the last snapshot, speed
    with h5py.File(snaps[pick[-1]], "r") as f:
        x = f["x"][:]; v = f["v"][:]; kind = f["kind"][:].ravel()
    fl = kind == 0
    ax = fig.add_subplot(gs[1, 2])
    ax.scatter(x[~fl, 0], x[~fl, 1], s=2, c="0.6")
    sv = ax.scatter(x[fl, 0], x[fl, 1], s=3, c=np.hypot(v[fl, 0], v[fl, 1]), cmap="plasma", vmin=0)
    xg = x[~fl & (x[:, 1] > a)][:, 0]
    xg = xg[(xg > 0) & (xg < xg.max() - 0.05)].min() if xg.size else 0.1  # upstream face of the gate
    ax.set_aspect("equal"); ax.set_xlim(xg - 0.03, xg + 0.09); ax.set_ylim(-0.005, 0.05)
    ax.axhline(Cc * a, color="k", lw=0.8, ls="--")
    ax.set_title(f"gate, t = {times[pick[-1]]:.3f} s: |v|; dashed: Cc a", fontsize=9); ax.tick_params(labelsize=7)
    fig.colorbar(sv, cax=fig.add_axes([0.92, 0.44, 0.01, 0.14]), label="|v| (m/s)")

ax = fig.add_subplot(gs[2, :])
ax.plot(t, q * 1e3, label="sphfsi WCSPH: q under the gate")
ax.plot(t, qref * 1e3, "--", label=f"sluice relation, Cc = {Cc}, with the measured h_up")
if win:
    ax.axvspan(win[0], win[1], color="0.9", label="quasi-steady window")
ax.set_ylabel("q (10$^{-3}$ m$^2$/s)"); ax.set_ylim(0, None); ax.legend(fontsize=8); ax.grid(alpha=0.3)
txt = ""
if "q_rel_bias" in err:
    txt = f"window: q - q_rel = {100 * err['q_rel_bias']:+.1f} %,  Cc from h_down {err['Cc_from_h_down']:.3f}, from q {err['Cc_from_q']:.3f}"
    ax.set_title(txt, fontsize=9)
ax = fig.add_subplot(gs[3, :], sharex=ax)
ax.plot(t, hu, label="h_up (mid-reservoir depth)")
ax.plot(t, hd, label="h_down (jet depth 2a past the gate edge)")
ax.axhline(Cc * a, color="k", lw=0.8, ls="--", label="Cc a")
ax.set_xlabel("t (s)"); ax.set_ylabel("depth (m)"); ax.legend(fontsize=8); ax.grid(alpha=0.3)
fig.savefig(png, dpi=110, bbox_inches="tight")
print(f"wrote {png}")
