#!/usr/bin/env python3
"""Report of the speed-versus-error study (tools/study.sh).

Usage: tools/study_report.py [OUTDIR]   (default out/study)

Reads OUTDIR/<scene>/plan.tsv (one line per run: scheme, resolution label, nominal dx, run name,
options) and each run's summary.json, run.json, FAILED and log; writes OUTDIR/study.md (one table
row per run: particles, steps, wall time, error, observed convergence order between successive
resolutions of a scheme; per scene which scheme reaches a given error in less wall time, by
interpolation on the log-log error-against-wall-time lines) and OUTDIR/<scene>.png (error against
wall time, log-log, one line per scheme, points labelled with the resolution).  A run that did not
complete is listed as failed with its exit code and message, and left out of the plot and the
comparison.  Wall time = summary.json wall_s (the time loop, set-up excluded).  No environment
variables."""
import glob, json, math, os, re, sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.ticker import FuncFormatter
import numpy as np

OUT = sys.argv[1] if len(sys.argv) > 1 else "out/study"
# scene: title, error key (absolute value taken), its description, display unit and scale, a
# second error shown for information (key, short name[, its unit and scale]), and optionally the self-convergence of
# probes (probes.csv column or tuple of columns, short name, display unit and scale), one table column each: the
# rms difference of the probe's curve from the next coarser run of the same scheme (rms over the columns of a
# tuple), with the order of those differences
SCENES = {
    "dam_break": ("Dam break", "front_rel_err_rms", "surge front against Martin & Moyce 1952, rms relative error", "%", 100,
                  ("height_rel_err_rms", "column height rms"), ("front_x", "front's change from the coarser run", "mm", 1e3),
                  ("height_left", "column height's change", "mm", 1e3)),
    "dam_break_lobovsky": ("Dam break, Lobovsky et al. 2014", "levels_err_rms",
                           "water levels H1–H4 against Lobovsky et al. 2014 (H = 0.3 m) to t√(g/H) = 4, rms over the "
                           "four gauges of the rms |h − h_exp| / H", "% of H", 100,
                           ("P1_peak_rel_err", "P1's first peak against the experiment's, relative", "%", 100),
                           (("H1", "H2", "H3", "H4"), "levels' change from the coarser run", "% of H", 100 / 0.3)),  # H = 0.3 m
    "dam_break_impact": ("Dam break impact, Lobovsky et al. 2014", "P1_peak_rel_err",
                         "sensor 1's first peak (y = 3 mm) against the experiment's (event 5), relative", "%", 100,
                         ("P1_impulse_rel_err", "its impulse over 0.2 t√(g/H) from the onset", "%", 100)),
    "dam_break_buchner": ("Dam break, Buchner 2002", "P1_err_rms",
                          "rms of P1 (y = 0.16 m) against Buchner 2002 over 2.4 ≤ t√(g/H) ≤ 7", "ρgH", 1,
                          ("P1_peak_rel_err", "P1's first peak, relative", "%", 100)),
    "taylor_green": ("Taylor–Green, Re 100", "l2_vel_err_final", "L2 velocity error at t_end, relative", "%", 100,
                     ("e_kin_rel_err_final", "E_kin")),
    "poiseuille": ("Poiseuille", "l2_vel_err_final", "L2 velocity error at t_end, relative (Morris et al. 1997)", "%", 100,
                   ("u_center_rel_err_final", "centre speed")),
    "oscillating_plate": ("Oscillating plate", "period_rel_err", "|period − thin-plate period| / thin-plate period", "%", 100,
                          ("amplitude_rel_err", "amplitude")),
    "cantilever": ("Static cantilever", "sag_eb_rel_err", "|sag − Euler–Bernoulli sag (plane strain)| / E–B", "%", 100,
                   ("sag_rel_err", "with Timoshenko shear")),
    "turek_hron_csm1": ("Turek–Hron CSM1 (static flag)", "uy_A_rel_err", "|uy_A − benchmark| / benchmark (−66.10 mm)", "%", 100,
                        ("ux_A_rel_err", "ux_A")),
    "turek_hron_csm3": ("Turek–Hron CSM3 (swinging flag)", "uy_A_frequency_rel_err", "|frequency of uy_A − benchmark| / benchmark (1.0995 Hz)", "%", 100,
                        ("uy_A_amplitude_rel_err", "uy_A amplitude")),
    "turek_hron_cfd1": ("Turek–Hron CFD1 (rigid flag, Re 20)", "drag_rel_err", "|drag − benchmark| / benchmark (14.29 N/m)", "%", 100,
                        ("lift_rel_err", "lift")),
    "turek_hron_cfd3": ("Turek–Hron CFD3 (rigid flag, Re 200)", "lift_amplitude_rel_err", "|lift amplitude − benchmark| / benchmark (437.81 N/m)", "%", 100,
                        ("lift_frequency_rel_err", "lift frequency")),
    "turek_hron_fsi2": ("Turek–Hron FSI2", "uy_A_amplitude_rel_err", "|uy_A amplitude − benchmark| / benchmark (80.6 mm)", "%", 100,
                        ("uy_A_frequency_rel_err", "uy_A frequency")),
    "turek_hron_fsi3": ("Turek–Hron FSI3", "uy_A_amplitude_rel_err", "|uy_A amplitude − benchmark| / benchmark (34.38 mm)", "%", 100,
                        ("uy_A_frequency_rel_err", "uy_A frequency")),
    "elastic_gate": ("Elastic gate", "tip_dx_err_rms", "rms error of the gate tip's tip_dx against the experiment", "mm", 1e3,
                     ("tip_dy_err_rms", "tip_dy rms")),
}
SCHEME = {"wcsph": "WCSPH", "isph": "ISPH", "solid": "solid (WCSPH)"}
COLOR = {"wcsph": "tab:blue", "isph": "tab:red", "solid": "tab:green"}


def res_label(lab):
    """Path-safe label of study.sh -> display: a20 -> a/20, ny10 -> 10 across, 1.25mm -> 1.25 mm."""
    m = re.fullmatch(r"ny(\d+)", lab)
    if m: return f"{m.group(1)} across"
    m = re.fullmatch(r"([A-Za-z]+)(\d+)", lab)
    if m: return f"{m.group(1)}/{m.group(2)}"
    return lab.replace("mm", " mm")


def load(scene, scheme, lab, dx, name):
    d = f"{OUT}/{scene}/{name}"
    r = dict(scheme=scheme, lab=lab, dx=float(dx), name=name, ok=False, why="not run")
    run = json.load(open(f"{d}/run.json")) if os.path.exists(f"{d}/run.json") else {}
    r["run"] = run
    s = json.load(open(f"{d}/summary.json")) if os.path.exists(f"{d}/summary.json") else None
    rc = run.get("rc")
    if rc is None and os.path.exists(f"{d}/FAILED"): rc = int(open(f"{d}/FAILED").read().strip() or -1)
    log = f"{OUT}/{scene}/{name}.log"
    lines = open(log, errors="replace").read().splitlines() if os.path.exists(log) else []
    r["particles0"] = next((int(m.group(1)) for m in (re.match(r"Particles: (\d+)", x) for x in lines) if m), None)
    if s is not None and s.get("status") == "completed" and rc in (0, None):
        r.update(ok=True, s=s, why="")
        return r
    # failed: the exit code and why (summary.json's message, else the last error line of the log)
    msg = (s or {}).get("message") or petsc_error(lines) or next((x for x in reversed(lines) if x.startswith("sphfsi")), "") \
        or (lines[-1] if lines else "")
    if rc == 124: msg = f"timed out after {run.get('elapsed_s', 0):.0f} s (STUDY_TIMEOUT)"
    r["why"] = f"exit {rc if rc is not None else '?'}, " + (f"status {s.get('status')}" if s else "no summary.json") + \
        (f": {msg.strip()}" if msg.strip() else "")
    r["s"] = s
    return r


def petsc_error(lines):
    """The class and message of the first PETSc error in a log ("Argument out of range: -dx ...")."""
    for i, x in enumerate(lines):
        if "PETSC ERROR: ----" in x and "Error Message" in x:
            return ": ".join(y.split("ERROR: ", 1)[1].strip() for y in lines[i + 1:i + 3] if "ERROR: " in y)
    return ""


def err_of(r, key):
    v = r["s"].get("errors", {}).get(key) if r.get("s") else None
    return abs(v) if isinstance(v, (int, float)) and math.isfinite(v) else None


def wall_at(pts, e):
    """Least wall time at which the log-log polyline through pts (wall, err), ordered by resolution,
    has error e; None when e is outside its range."""
    best = None
    for (w1, e1), (w2, e2) in zip(pts, pts[1:]):
        if min(e1, e2) <= e <= max(e1, e2):
            f = 0 if e1 == e2 else (math.log(e) - math.log(e1)) / (math.log(e2) - math.log(e1))
            w = math.exp(math.log(w1) + f * (math.log(w2) - math.log(w1)))
            best = w if best is None else min(best, w)
    for w, ee in pts:
        if ee == e: best = w if best is None else min(best, w)
    return best


def fmt_e(e, unit, scale):
    return "–" if e is None else (f"{e * scale:.3g} {unit}" if unit != "%" else f"{e * scale:.3g} %")


def compare(scene, runs, key, unit, scale):
    """Sentences: at equal error which scheme is faster and by what factor."""
    schemes = [s for s in dict.fromkeys(r["scheme"] for r in runs)]
    pts = {s: [(r["s"]["wall_s"], err_of(r, key)) for r in runs if r["scheme"] == s and r["ok"] and err_of(r, key)]
           for s in schemes}
    out = []
    for s in schemes:
        fails = [r for r in runs if r["scheme"] == s and not r["ok"]]
        if fails: out.append(f"{SCHEME[s]} failed at {', '.join(res_label(r['lab']) for r in fails)}.")
    if len(schemes) != 2:
        p = pts[schemes[0]]
        if p: out.append(f"Only one scheme; error {fmt_e(p[0][1], unit, scale)} in {p[0][0]:.3g} s at the coarsest, "
                         f"{fmt_e(p[-1][1], unit, scale)} in {p[-1][0]:.3g} s at the finest resolution.")
        return out
    ok = [r for r in runs if r["ok"] and err_of(r, key)]
    front = [r for r in ok if not any(o is not r and o["s"]["wall_s"] <= r["s"]["wall_s"] and err_of(o, key) <= err_of(r, key)
                                      for o in ok)]
    front.sort(key=lambda r: r["s"]["wall_s"])
    out.append("Pareto front (no other run has both less error and less wall time): " + ", ".join(
        f"{SCHEME[r['scheme']]} {res_label(r['lab'])} ({fmt_e(err_of(r, key), unit, scale)}, {r['s']['wall_s']:.3g} s)" for r in front) + ".")
    for s in schemes:
        e = [e for _, e in sorted(((r["dx"], err_of(r, key)) for r in ok if r["scheme"] == s), reverse=True)]
        if len(e) > 1 and e[-1] >= e[0]:
            out.append(f"{SCHEME[s]}'s error does not fall with resolution ({fmt_e(e[0], unit, scale)} at the coarsest, "
                       f"{fmt_e(e[-1], unit, scale)} at the finest completed run): its finer runs buy no accuracy against this reference.")
    a, b = schemes
    same = [(ra, rb) for ra in ok for rb in ok if ra["scheme"] == a and rb["scheme"] == b and ra["lab"] == rb["lab"]]
    if same:
        out.append(f"At the same dx, wall time {SCHEME[b]} / {SCHEME[a]}: " + ", ".join(
            f"{rb['s']['wall_s'] / ra['s']['wall_s']:.2g} at {res_label(ra['lab'])}" for ra, rb in same) + ".")
    if len(pts[a]) < 1 or len(pts[b]) < 1:
        out.append("No comparison: a scheme has no completed run."); return out
    lo = max(min(e for _, e in pts[a]), min(e for _, e in pts[b]))
    hi = min(max(e for _, e in pts[a]), max(e for _, e in pts[b]))
    if lo > hi or len(pts[a]) < 2 and len(pts[b]) < 2 and lo != hi:
        # no common error: does one scheme dominate?
        best = {s: min(pts[s], key=lambda p: p[1]) for s in (a, b)}
        cheap = {s: min(pts[s], key=lambda p: p[0]) for s in (a, b)}
        acc, inacc = (a, b) if max(e for _, e in pts[a]) < min(e for _, e in pts[b]) else (b, a)
        out.append(f"No overlap in error: {SCHEME[acc]} is more accurate at every resolution "
                   f"({fmt_e(min(e for _, e in pts[acc]), unit, scale)}–{fmt_e(max(e for _, e in pts[acc]), unit, scale)} against "
                   f"{fmt_e(min(e for _, e in pts[inacc]), unit, scale)}–{fmt_e(max(e for _, e in pts[inacc]), unit, scale)}); "
                   f"its cheapest run ({fmt_e(cheap[acc][1], unit, scale)}, {cheap[acc][0]:.3g} s) against {SCHEME[inacc]}'s "
                   f"most accurate ({fmt_e(best[inacc][1], unit, scale)}, {best[inacc][0]:.3g} s): "
                   + (f"{best[inacc][0] / cheap[acc][0]:.2g}× less wall time." if cheap[acc][0] <= best[inacc][0]
                      else f"{cheap[acc][0] / best[inacc][0]:.2g}× more wall time."))
        return out
    levels = [lo] if lo == hi else [lo, math.sqrt(lo * hi), hi]
    for e in levels:
        wa, wb = wall_at(pts[a], e), wall_at(pts[b], e)
        if wa is None or wb is None: continue
        fast, slow, wf, ws = (a, b, wa, wb) if wa <= wb else (b, a, wb, wa)
        out.append(f"At {fmt_e(e, unit, scale)}: {SCHEME[a]} {wa:.3g} s, {SCHEME[b]} {wb:.3g} s: "
                   f"**{SCHEME[fast]} {ws / wf:.2g}× faster**.")
    return out


def main():
    md = []
    T = open(f"{OUT}/study_time.txt").read().strip() if os.path.exists(f"{OUT}/study_time.txt") else ""
    md.append("# Speed against error\n")
    md.append("Generated by `tools/study_report.py` from the runs of `tools/study.sh` (`make study`). "
              "Wall = the time loop (summary.json `wall_s`); elapsed = the whole mpiexec run; CPU = user + system "
              "seconds of the whole run summed over the ranks (less sensitive to the load than wall; Open MPI's busy "
              "waiting counts in it); load = the 1-minute load "
              "average before → after the run (2 cores; a 2-rank run itself brings it to ~2 within a minute, so "
              "~2 means no other work, and above that the wall times are inflated). Order = "
              "log(e1/e2)/log(dx1/dx2) against the previous completed resolution of the same scheme; negative = the error grows "
              "with resolution. Particles at the start (the elastic gate loses water through its opening). "
              + (f"{T}." if T else "") + "\n")
    for scene, (title, key, what, unit, scale, (k2, n2, *u2), *selfc) in SCENES.items():
        unit2, scale2 = u2 if u2 else (unit, scale)   # the second error's own unit, when it has one
        plan = f"{OUT}/{scene}/plan.tsv"
        if not os.path.exists(plan): continue
        lines = open(plan).read().splitlines()
        head = lines[0].lstrip("# ") if lines and lines[0].startswith("#") else ""
        runs = [load(scene, *l.split("\t")[:4]) for l in lines if l and not l.startswith("#")]
        order = list(dict.fromkeys(r["scheme"] for r in runs))
        runs.sort(key=lambda r: order.index(r["scheme"]))   # stable: by scheme, then coarse to fine
        opts = {l.split("\t")[0]: l.split("\t")[4] for l in lines if l and not l.startswith("#")}
        md.append(f"## {title}\n\nError: {what} ({unit}). {head}.\n")
        strip_res = lambda o: re.sub(r" -(dx|plate_ny|dx_coarse) \S+", "", o)
        md.append("Schemes: " + "; ".join(f"{SCHEME[s]}: `{strip_res(o)}`" for s, o in opts.items()) + "\n")
        sc_head = "".join(f" {c[1]} ({c[2]}) (order) |" for c in selfc)
        md.append(f"| scheme | resolution | dx (m) | particles | steps | wall s | elapsed s | CPU s | load | error ({unit}) | order | {n2} ({unit2}) |{sc_head}")
        md.append("|---|---|---|---|---|---|---|---|---|---|---|---|" + "---|" * len(selfc))
        prev, prev_curve, changes = {}, [{} for _ in selfc], {}
        for r in runs:
            run = r["run"]
            load_s = f"{run['load_before']:.2f} → {run['load_after']:.2f}" if run else "–"
            el = f"{run['elapsed_s']:.1f}" if run else "–"
            cpu = f"{run['cpu_s']:.1f}" if run and run.get("cpu_s") is not None else "–"
            if not r["ok"]:
                # (no CPU time: mpiexec does not collect the rusage of ranks it kills)
                md.append(f"| {SCHEME[r['scheme']]} | {res_label(r['lab'])} | {r['dx']:.4g} | {r['particles0'] or '–'} | "
                          f"{(r['s'] or {}).get('steps', '–')} | **failed** | {el} | – | {load_s} | {r['why']} | | |")
                continue
            s, e = r["s"], err_of(r, key)
            order = "–"
            p = prev.get(r["scheme"])
            if p and e and p[1] and p[0] != r["dx"]:
                order = f"{math.log(p[1] / e) / math.log(p[0] / r['dx']):.2f}"
            if e: prev[r["scheme"]] = (r["dx"], e)
            e2 = err_of(r, k2)
            sc_cell = ""
            for i, (c, pc) in enumerate(zip(selfc, prev_curve)):
                cell, d = self_convergence(scene, r, c, pc)
                sc_cell += f" {cell} |"
                if d is not None: changes.setdefault((i, r["scheme"]), []).append(d)   # for the line under the table
            md.append(f"| {SCHEME[r['scheme']]} | {res_label(r['lab'])} | {s['dx']:.4g} | {r['particles0'] or s['particles']} | "
                      f"{s['steps']} | {s['wall_s']:.3g} | {el} | {cpu} | {load_s} | {'–' if e is None else f'{e * scale:.3g}'} | "
                      f"{order} | {'–' if e2 is None else f'{e2 * scale2:.3g}'} |{sc_cell}")
        md.append("")
        md += [f"- {x}" for x in compare(scene, runs, key, unit, scale)]
        for (i, scheme), d in changes.items():
            _, name, u, sc = selfc[i]
            if len(d) < 2: continue
            falls = all(y < x for x, y in zip(d, d[1:]))
            md.append(f"- {SCHEME[scheme]}, {name}: {' → '.join(f'{x * sc:.3g}' for x in d)} {u}, "
                      + ("falls at every refinement: the runs converge (self-convergence)." if falls
                         else "does not fall at every refinement."))
        md.append("")
        plot(scene, title, runs, key, what, unit, scale)
        md.append(f"![{title}]({scene}.png)\n")
    runs_json = [json.load(open(f"{d}/run.json")) for d in sorted(glob.glob(f"{OUT}/*/*/")) if os.path.exists(f"{d}/run.json")]
    if runs_json:
        lb = [r["load_before"] for r in runs_json]; cpu = sum(r["cpu_s"] or 0 for r in runs_json)
        md.insert(2, f"{len(runs_json)} runs: {sum(r['elapsed_s'] for r in runs_json):.0f} s elapsed in all, "
                     f"{cpu:.0f} CPU s (÷ {runs_json[0]['np']} ranks = {cpu / runs_json[0]['np']:.0f} s); "
                     f"load average before a run {min(lb):.2f}–{max(lb):.2f} (mean {sum(lb) / len(lb):.2f}).\n")
    open(f"{OUT}/study.md", "w").write("\n".join(md))
    print("\n".join(md))


def self_convergence(scene, r, spec, prev):
    """The rms difference of probe column spec[0] (or of the columns of a tuple, rms over them) from the
    same scheme's previous (coarser) run on 301 times over their common span, scaled to spec[3]; the
    order of successive differences. Returns the table cell and the difference (None for a scheme's
    first run or a run without probes); prev keeps per scheme (dx, t, y, difference)."""
    cols, _, unit, scale = spec
    cols = (cols,) if isinstance(cols, str) else cols
    f = f"{OUT}/{scene}/{r['name']}/probes.csv"
    if not os.path.exists(f): return "–", None
    rows = [l.split(",") for l in open(f).read().splitlines()]
    if any(c not in rows[0] for c in cols) or len(rows) < 3: return "–", None
    data = np.array([[float(v) for v in x] for x in rows[1:]])
    t, y = data[:, 0], data[:, [rows[0].index(c) for c in cols]]
    p, cell = prev.get(r["scheme"]), "–"
    diff = None
    if p:
        tt = np.linspace(0, min(t[-1], p[1][-1]), 301)
        d = [np.interp(tt, t, y[:, j]) - np.interp(tt, p[1], p[2][:, j]) for j in range(len(cols))]
        diff = float(np.sqrt(np.mean(np.square(d))))
        cell = f"{diff * scale:.3g}"
        if p[3] and diff > 0 and p[0] != r["dx"]:
            cell += f" ({math.log(p[3] / diff) / math.log(p[0] / r['dx']):.2f})"
    prev[r["scheme"]] = (r["dx"], t, y, diff)
    return cell, diff


def plot(scene, title, runs, key, what, unit, scale):
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    loads = [r["run"][k] for r in runs if r["run"] for k in ("load_before", "load_after")]
    for s in dict.fromkeys(r["scheme"] for r in runs):
        rs = [r for r in runs if r["scheme"] == s and r["ok"] and err_of(r, key)]
        fails = [res_label(r["lab"]) for r in runs if r["scheme"] == s and not r["ok"]]
        lab = SCHEME[s] + (f" (failed: {', '.join(fails)})" if fails else "")
        if not rs:
            ax.plot([], [], "o-", color=COLOR[s], label=lab); continue
        w = np.array([r["s"]["wall_s"] for r in rs]); e = np.array([err_of(r, key) * scale for r in rs])
        ax.plot(w, e, "o-", color=COLOR[s], label=lab)
        for r, x, y in zip(rs, w, e):
            ax.annotate(res_label(r["lab"]), (x, y), textcoords="offset points", xytext=(5, 4), fontsize=8, color=COLOR[s])
    ax.set_xscale("log"); ax.set_yscale("log")
    for axis, lim in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        digits = "123456789" if lim[1] / lim[0] < 3 else "235" if lim[1] / lim[0] < 30 else "25"   # more labels on a short axis
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_formatter(FuncFormatter(lambda v, _, d=digits: f"{v:g}" if f"{v:.0e}"[0] in d else ""))
    ax.set_xlabel("wall time of the time loop (s), %d ranks" % (runs[0]["run"] or {}).get("np", 2))
    ax.set_ylabel(f"error ({unit})")
    ax.set_title(f"{title}: {what}", fontsize=9)
    if loads: ax.text(0.01, 0.01, f"load average {min(loads):.1f}–{max(loads):.1f}", transform=ax.transAxes, fontsize=7, color="gray")
    ax.grid(True, which="both", alpha=0.3); ax.legend(fontsize=8)
    fig.tight_layout(); fig.savefig(f"{OUT}/{scene}.png", dpi=110); plt.close(fig)


if __name__ == "__main__":
    main()
