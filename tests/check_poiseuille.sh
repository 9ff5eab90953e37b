#!/usr/bin/env bash
# Poiseuille flow from rest (Morris et al. 1997: Hc = 1 mm, nu = 1e-6 m^2/s, F = 1e-4 m/s^2,
# u_max = F Hc^2 / (8 nu) = 1.25e-5 m/s), 20 particle rows across, run to t = 2 Hc^2/nu = 2 s.
# Bounds: the centre speed is within 3 % of the analytic steady value at the end (where the
# transient has decayed to 3e-9), and within 3 % of the analytic transient (Morris et al. Eq. 21)
# at every probe from t = 0.05 Hc^2/nu on (u_center already 1/4 of u_max there); the whole
# velocity profile is within 3 % in the L2 norm at the end.
#   tests/check_poiseuille.sh "MPIEXEC -n P" OUTDIR [extra sphfsi options, e.g. -fluid wcsph]
set -e
MPI=$1; OUT=$2; shift 2
$MPI bin/sphfsi -options_file cases/poiseuille.opts -output_interval 0 -output_dir "$OUT" -progress_every 0 "$@"
python3 - "$OUT" <<'PY'
import csv, json, math, sys
out = sys.argv[1]
s = json.load(open(out + "/summary.json")); e = s["errors"]
Hc, nu, F, dx = 1e-3, 1e-6, 1e-4, s["dx"]
umax = F * Hc**2 / (8 * nu)
def u(y, t):  # Morris et al. 1997 Eq. 21, steady part with the sign of the flow
    v = F / (2 * nu) * y * (Hc - y)
    n = 1
    while True:
        a = math.exp(-n * n * math.pi**2 * nu * t / Hc**2) / n**3
        v -= 4 * F * Hc**2 / (nu * math.pi**3) * a * math.sin(n * math.pi * y / Hc)
        if a < 1e-16: return v
        n += 2
ny = round(Hc / dx)  # u_center averages the middle row(s): +-dx/2 for even ny, the middle one for odd
ys = [0.5 * Hc - 0.5 * dx, 0.5 * Hc + 0.5 * dx] if ny % 2 == 0 else [0.5 * Hc]
rows = list(csv.DictReader(open(out + "/probes.csv")))
worst = 0
for r in rows:
    t = float(r["t"])
    if t < 0.05 * Hc**2 / nu: continue
    ref = sum(u(y, t) for y in ys) / len(ys)
    err = abs(float(r["u_center"]) - ref) / ref
    worst = max(worst, err)
    assert err < 0.03, f"u_center {r['u_center']} at t = {t} off the analytic transient {ref:.6g} by {100*err:.2f} %"
t = float(rows[-1]["t"]); uc = float(rows[-1]["u_center"])
ref = sum(F / (2 * nu) * y * (Hc - y) for y in ys) / len(ys)
err = abs(uc - ref) / ref
print(f"poiseuille: t {t:.3g} s, u_center {uc:.6g} m/s vs steady {ref:.6g} (u_max {umax:.4g}): {100*err:.2f} % (bound 3 %); "
      f"transient worst {100*worst:.2f} % over {len(rows)} probes (bound 3 %); L2 profile error {100*e['l2_vel_err_final']:.2f} % (bound 3 %); "
      f"{s['particles']} particles, {s['steps']} steps, {s['wall_s']:.2f} s")
assert t >= 0.99 * Hc**2 / nu, "the run stopped before the flow is steady"
assert err < 0.03, "centre speed off the steady analytic value by more than 3 %"
assert abs(e["u_center_rel_err_final"]) < 0.03, "scene-reported centre-speed error above 3 %"
assert 0 <= e["l2_vel_err_final"] < 0.03, "velocity profile off the analytic one by more than 3 % (L2)"
assert s["mass_rel_drift"] == 0, "mass changed"
PY
