#!/usr/bin/env python3
"""Plot Turek-Hron runs (-case turek_hron): drag, lift and point A's displacement against time with
the benchmark's band (mean +- amplitude, or the steady value), from the runs' probes.csv and the
reference data (turek_hron2006_fsi_benchmark.csv).

  tools/plot_turek_hron.py OUT.png LABEL=RUNDIR [LABEL=RUNDIR ...]
  tools/plot_turek_hron.py --vorticity OUT.png RUNDIR [SNAPSHOT]

Each RUNDIR holds a run's probes.csv and options_used (its case is read there).  One panel per
quantity the runs have (drag, lift with the fluid; uy_A, ux_A with the elastic flag).  --vorticity:
the vorticity dv/dx - du/dy around the cylinder and the flag in a snapshot (the last by default): the
fluid's velocity averaged on a grid of 1.5 dx cells, differentiated by central differences (a
picture, not a measurement); walls and the flag in grey."""
import csv, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))
REF = [os.path.join(HERE, "..", "..", "shared", "refdata"), os.path.join(HERE, "..", "refdata")]


def reference():
    for d in REF:
        f = os.path.join(d, "turek_hron2006_fsi_benchmark.csv")
        if os.path.exists(f):
            rows = [r for r in csv.reader(open(f)) if r and not r[0].startswith("#")]
            head = rows[0]
            return {(r[0].lower(), r[1]): dict(zip(head, r)) for r in rows[1:]}
    return {}


def main():
    out, runs = sys.argv[1], [a.split("=", 1) for a in sys.argv[2:]]
    ref = reference()
    data = []
    for label, d in runs:
        p = np.genfromtxt(os.path.join(d, "probes.csv"), delimiter=",", names=True)
        cs = ""  # the case, from the run's options_used (a run still going has no summary.json yet)
        for line in open(os.path.join(d, "options_used")):
            if line.startswith("-turek_hron_case"):
                cs = line.split()[1]
        data.append((label, cs, p))
    qs = [q for q in ("drag", "lift", "uy_A", "ux_A") if any(np.any(p[q][1:] != 0) for _, _, p in data)]
    fig, axs = plt.subplots(len(qs), 1, figsize=(8, 2.4 * len(qs)), sharex=True, squeeze=False)
    for ax, q in zip(axs[:, 0], qs):
        scale = 1e3 if q.endswith("_A") else 1
        for label, cs, p in data:
            ax.plot(p["t"], scale * p[q], lw=0.7, label=f"{label}")
        r = ref.get((data[0][1], q))
        if r:
            m, a = float(r["mean"]), float(r["amplitude"] or 0)
            if a > 0:
                ax.axhspan(m - a, m + a, color="0.85", zorder=0, label="benchmark mean ± amplitude")
            ax.axhline(m, color="k", lw=0.8, ls="--", label="benchmark mean")
        ax.set_ylabel(q + (" (mm)" if scale != 1 else " (N/m)"))
        ax.legend(fontsize=7, loc="best")
    axs[-1, 0].set_xlabel("t (s)")
    fig.suptitle(f"Turek–Hron {data[0][1].upper()}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def vorticity(out, run, snap=None):
    import glob
    import h5py
    files = sorted(glob.glob(os.path.join(run, "particles_*.h5")))
    h = h5py.File(snap or files[-1], "r")
    kind, x, v = h["kind"][:].ravel(), h["x"][:], h["v"][:]
    dx = float(np.median(h["h"][:])) / 1.4  # h = 1.4 dx with WCSPH's default; only sets the grid
    cell = 1.5 * dx
    lo, hi = np.array([0.0, 0.0]), np.array([1.5, 0.41])
    n = np.ceil((hi - lo) / cell).astype(int)
    fl = (kind == 0) & np.all((x >= lo) & (x < hi), axis=1)
    ij = ((x[fl] - lo) / cell).astype(int)
    cnt = np.zeros(n); u = np.zeros(n); w = np.zeros(n)
    np.add.at(cnt, (ij[:, 0], ij[:, 1]), 1)
    np.add.at(u, (ij[:, 0], ij[:, 1]), v[fl, 0])
    np.add.at(w, (ij[:, 0], ij[:, 1]), v[fl, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        u /= cnt; w /= cnt
    om = np.gradient(w, cell, axis=0) - np.gradient(u, cell, axis=1)
    om[cnt == 0] = np.nan
    fig, ax = plt.subplots(figsize=(11, 3.6))
    lim = np.nanpercentile(np.abs(om), 99)
    im = ax.imshow(om.T, origin="lower", extent=[lo[0], hi[0], lo[1], hi[1]], cmap="RdBu_r", vmin=-lim, vmax=lim)
    b = (kind != 0) & np.all((x >= lo) & (x < hi), axis=1)
    ax.scatter(x[b, 0], x[b, 1], s=0.3, c="0.5")
    ax.set_aspect("equal"); ax.set_xlabel("x (m)"); ax.set_ylabel("y (m)")
    fig.colorbar(im, ax=ax, label="vorticity (1/s)", shrink=0.8)
    ax.set_title(f"{os.path.basename(os.path.normpath(run))}, t = {float(h.attrs.get('time', np.nan)) if 'time' in h.attrs else ''}")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    if sys.argv[1] == "--vorticity":
        vorticity(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) > 4 else None)
    else:
        main()
