#!/usr/bin/env bash
# Static cantilever with the total-Lagrangian solid (issue: a solid that converges in bending),
# cases/cantilever.opts: the elastic gate's plate (L = 79 mm, H = 5 mm, rubber K 2e7, G 4.27e6 Pa)
# clamped at x < 0 and bent by a uniform load of 99 N/m (gravity 18 m/s^2 on rho H), brought to rest
# by -solid_damping (dynamic relaxation, about critical for its first mode) until t = 0.12 s: the end
# is then within 0.03 % of its rest (5 across: 3.2600 mm at 0.12 s, 3.2608 mm at 0.15 s; the approach
# shrinks 2.2x every 0.01 s), a tenth of the error measured at 5 across.  Reference: Euler-Bernoulli
# with the plane-strain modulus, 3.249 mm; a 2D finite-element solution of the same rigidly clamped
# plate (tools/fem_plate.py) is 0.08 % below it, so beam theory is the reference to that accuracy.
# Bounds: the sag within 3 % of it at 5 particles across (the issue's target; measured +0.34 %).  The
# same plate with the first-order gradient (-solid_order 1, the kernel-gradient correction alone, the
# clamp as material) must miss by more than 20 % at 5 across (measured 42 %): what the second-order
# fit at the free surfaces removes.  The convergence (10 across: +0.11 %, bound 1 %, and at least
# first order) costs 2 min here and runs in `make study` (STUDY_SCENES=cantilever: 5, 7, 10 across).
#   tests/check_cantilever.sh "MPIEXEC -n P" OUTDIR
set -e
MPI=$1; OUT=$2; shift 2
run() { local name=$1; shift
  $MPI bin/sphfsi -options_file cases/cantilever.opts -output_interval 0 -progress_every 0 -output_dir "$OUT/$name" "$@" > "$OUT.$name.log" 2>&1 || { tail -20 "$OUT.$name.log"; exit 1; }; }
mkdir -p "$OUT"
run ny5 -plate_ny 5
run ny5_order1 -plate_ny 5 -solid_order 1
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
e = {k: json.load(open(f"{out}/{k}/summary.json"))["errors"] for k in ["ny5", "ny5_order1"]}
eb = e["ny5"]["sag_euler_bernoulli"]
err = {k: v["sag"] / eb - 1 for k, v in e.items()}
print(f"cantilever (total lagrangian solid): sag {1000*e['ny5']['sag']:.4f} mm at 5 across against {1000*eb:.3f} mm "
      f"(Euler-Bernoulli, plane strain): {100*err['ny5']:+.2f} % (bound 3 %); first-order gradient {100*err['ny5_order1']:+.1f} % "
      f"(must exceed 20 %); kinetic/strain energy at the end {max(v['kinetic_over_strain_energy'] for v in e.values()):.1e}")
assert abs(e["ny5"]["sag_eb_rel_err"] - err["ny5"]) < 1e-4, "summary.json's sag_eb_rel_err disagrees with sag / sag_euler_bernoulli - 1"
for k, v in e.items():
    assert v["kinetic_over_strain_energy"] < 1e-4, f"{k}: not at rest at the end"
assert abs(err["ny5"]) < 0.03, "sag at 5 across more than 3 % from beam theory"
assert err["ny5_order1"] > 0.20, "the first-order gradient is no longer too compliant: the test no longer shows what the second-order fit fixes"
PY
