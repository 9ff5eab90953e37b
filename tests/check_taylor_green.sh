#!/usr/bin/env bash
# Taylor-Green vortices at Re = 100 (L = 1 m, U = 1 m/s, nu = 0.01 m^2/s), t = 1 s, on the case's
# 50 x 50 lattice unless the caller passes -dx.
# Bound: the kinetic energy E(t)/E(0) is within 5 % of the exact decay exp(-16 pi^2 nu t / L^2)
# (= 0.206 at t = 1 s), checked at t = 0.25, 0.5, 0.75 and 1 s; and the L2 velocity error at t = 1 s
# is at most 5 % (issue 24's target at L/100; the cubic spline at 1.3 dx gave 60 % in WCSPH).
# WCSPH reaches it at L/50 already; ISPH is run at L/100, where the target is set: at L/50 its
# 70 steps (CFL 0.25 on the flow speed) leave E(1) 5.5 % low, the first-order-in-dt damping of the
# shifting's velocity re-interpolation (shifting off: 0.8 %; -cfl 0.1: 2.7 %).
#   tests/check_taylor_green.sh "MPIEXEC -n P" OUTDIR [extra sphfsi options, e.g. -fluid isph]
set -e
MPI=$1; OUT=$2; shift 2
$MPI bin/sphfsi -options_file cases/taylor_green.opts -output_interval 0 -output_dir "$OUT" -progress_every 0 "$@"
python3 - "$OUT" <<'PY'
import csv, json, math, sys
out = sys.argv[1]
s = json.load(open(out + "/summary.json")); e = s["errors"]
nu = 1.0 / e["re"]  # U = L = 1
assert abs(e["re"] - 100) < 1e-6 * 100, f"expected Re = 100, the run has {e['re']}"
rows = [(float(r["t"]), float(r["e_kin"]), float(r["l2_vel_err"])) for r in csv.DictReader(open(out + "/probes.csv"))]
assert rows[0][0] == 0, "the first probe row is not t = 0"
E0 = rows[0][1]
ok = True
for tc in (0.25, 0.5, 0.75, 1.0):
    t, E, l2 = min(rows, key=lambda r: abs(r[0] - tc))
    assert abs(t - tc) < 0.02, f"no probe near t = {tc}"
    ex = math.exp(-16 * math.pi**2 * nu * t)
    err = abs(E / E0 - ex) / ex
    print(f"taylor_green: t {t:.3f}  E/E0 {E/E0:.4f}  exact {ex:.4f}  error {100*err:.1f} % (bound 5 %)  L2 velocity error {100*l2:.1f} %")
    ok = ok and err < 0.05
t = rows[-1][0]
assert abs(t - 1.0) < 1e-9, f"the run ended at t = {t}, not 1 s"
print(f"taylor_green: E(1)/E(0) error {100*e['e_kin_rel_err_final']:.1f} % (bound 5 %), L2 velocity error {100*e['l2_vel_err_final']:.1f} %, {s['particles']} particles, {s['steps']} steps, {s['wall_s']:.2f} s")
assert ok and e["e_kin_rel_err_final"] < 0.05, "kinetic-energy decay off the exact one by more than 5 %"
assert e["l2_vel_err_final"] < 0.05, "L2 velocity error at t = 1 s above 5 %"
assert s["mass_rel_drift"] == 0, "mass changed"
PY
