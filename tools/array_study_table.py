#!/usr/bin/env python3
"""The table of a periodic-array study (tools/array_study.sh cylinder, tools/array_study.sh sphere):
one row per run OUT/FLUID_PHI_N/summary.json (the drag against the reference at phi and at the
lattice's phi, Re, wall time) and the observed order of each series.
Usage: array_study_table.py OUT "NS" "PHIS" "FLUIDS" cylinder|sphere"""
import json, math, sys

out, ns, phis, fluids, kind = sys.argv[1], sys.argv[2].split(), sys.argv[3].split(), sys.argv[4].split(), sys.argv[5]
val, ref, name = ("K", "K_reference", "K") if kind == "sphere" else ("drag_coefficient", "drag_reference", "drag F/(mu U)")
print(f"| phi | fluid | L/dx | {name} | reference | error | phi_lattice | error at phi_lattice | Re | wall time (s) |")
print("|---|---|---|---|---|---|---|---|---|---|")
for phi in phis:
    for f in fluids:
        errs = []
        for n in ns:
            try:
                s = json.load(open(f"{out}/{f}_{phi}_{n}/summary.json")); e = s["errors"]
            except (OSError, KeyError, ValueError):
                print(f"| {phi} | {f} | {n} | (no result) |"); continue
            errs.append((int(n), e["drag_rel_err"]))
            print(f"| {phi} | {f} | {n} | {e[val]:.3f} | {e[ref]:.3f} | {100 * e['drag_rel_err']:+.2f} % | {e['phi_lattice']:.4f} | {100 * e['drag_rel_err_phi_lattice']:+.2f} % | {e['re']:.2g} | {s['wall_s']:.0f} |")
        orders = [math.log(abs(a[1] / b[1])) / math.log(b[0] / a[0]) for a, b in zip(errs, errs[1:]) if a[1] and b[1]]
        if orders: print(f"| {phi} | {f} | observed order | " + ", ".join(f"{o:.2f}" for o in orders) + " | | | | | | |")
