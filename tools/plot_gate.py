#!/usr/bin/env python3
"""Tip displacement of elastic-gate runs against the Antoci et al. (2007) experiment (both
digitisations) and, for context, published numerical results (Antoci SPH, Yang SPH-FEM, Khayyer ISPH-SPH).
   tools/plot_gate.py PNG OUTDIR [OUTDIR ...]     (reference data: tools/refdata_csv.py)"""
import csv, json, os, sys
import matplotlib
import numpy as np
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refdata_csv import ref_path  # noqa: E402

png, dirs = sys.argv[1], sys.argv[2:]

def load(name, col):
    path = ref_path(name, "its curve is not drawn")
    if not path:
        return None
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith("#")))
    return [float(r["t_s"]) for r in rows], [1000 * float(r[col]) for r in rows]

def rms_against(exp, rows, col):
    """RMS of |sim - exp| (m) at the experiment's times up to the run's end, sim interpolated
    linearly (the scene's own comparison, src/scenes/elastic_gate.c); None without the data."""
    if not exp:
        return None
    t = [float(r["t"]) for r in rows]
    y = [float(r[col]) for r in rows]
    e2 = [(float(np.interp(te, t, y)) - ye / 1000) ** 2 for te, ye in zip(*exp) if te <= t[-1]]
    return (sum(e2) / len(e2)) ** 0.5 if e2 else None

fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
for ax, comp in zip(axes, ("dx", "dy")):
    for d in dirs:
        rows = list(csv.DictReader(open(d + "/probes.csv")))
        s = json.load(open(d + "/summary.json")); e = s["errors"]
        rms = e.get(f"tip_{comp}_err_rms")
        if rms is None:  # a run that did not find the reference data: the scene's comparison, here
            rms = rms_against(load(f"antoci2007_exp_tip{comp}__chrono.csv", f"{comp}_m"), rows, f"tip_{comp}")
        dim = s.get("dim") or (3 if os.path.exists(d + "/options_used") and "-dim 3" in open(d + "/options_used").read() else 2)  # runs before summary.json had "dim"
        lab = ("3D, " if dim == 3 else "") + f"{s['fluid']} + {s.get('solid_formulation', 'updated')} solid, dx {1000 * s['dx']:.3g} mm" + (f": RMS {1000 * rms:.1f} mm" if rms is not None else "")
        ax.plot([float(r["t"]) for r in rows], [1000 * float(r[f"tip_{comp}"]) for r in rows], label=lab)
    for name, style, lab in ((f"antoci2007_exp_tip{comp}__chrono.csv", "ko", "experiment"),
                             (f"antoci2007_exp_tip{comp}__fsi_etvf.csv", "k^", "experiment (2nd digitisation)"),
                             (f"antoci2007_SPHnum_tip{comp}__chrono.csv", "g:", "Antoci et al. SPH"),
                             (f"yang2012_SPHFEM_tip{comp}__chrono.csv", "m:", "Yang et al. SPH-FEM"),
                             (f"khayyer2018_ISPHSPH_tip{comp}__fsi_etvf.csv", "c:", "Khayyer et al. ISPH-SPH")):
        r = load(name, f"{comp}_m")
        if r:
            ax.plot(*r, style, ms=4, label=lab)
    ax.set_xlabel("t (s)"); ax.set_ylabel(f"tip_{comp} (mm)"); ax.set_xlim(0, 0.4); ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right" if comp == "dx" else "upper right")
fig.tight_layout(); fig.savefig(png, dpi=110)
print("wrote", png)
