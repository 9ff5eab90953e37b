#!/usr/bin/env bash
# Static cantilever with the total-Lagrangian solid (issue: a solid that converges in bending): the
# elastic gate's plate (L = 79 mm, H = 5 mm, rubber K 2e7, G 4.27e6 Pa) clamped at x < 0 and bent by
# a uniform load of 99 N/m (gravity 18 m/s^2 on rho H), brought to rest by -solid_damping (dynamic
# relaxation, about critical for its first mode) until t = 0.12 s: the end is then within 0.03 % of its
# rest (5 across: 3.2600 mm at 0.12 s, 3.2608 mm at 0.15 s; the approach shrinks 2.2x every 0.01 s), a
# tenth of the error measured at 5 across and a quarter of that at 10.  Reference: Euler-Bernoulli with the plane-strain
# modulus, 3.249 mm; a 2D finite-element solution of the same rigidly clamped plate
# (tools/fem_plate.py) is 0.08 % below it, so beam theory is the reference to that accuracy.
# Bounds, the issue's targets: the sag within 3 % of it at 5 particles across and 1 % at 10
# (measured +0.34 % and +0.11 %), and the error at 10 across at most 0.6 x that at 5 (first-order
# convergence at least).  The same plate with the first-order gradient (-solid_order 1, the
# kernel-gradient correction alone, the clamp as material) must miss by more than 20 % at 5 across
# (measured 42 %): what the second-order fit at the free surfaces removes.
#   tests/check_cantilever.sh "MPIEXEC -n P" OUTDIR
set -e
MPI=$1; OUT=$2; shift 2
run() { local name=$1; shift
  $MPI bin/sphfsi -options_file cases/oscillating_plate.opts -solid_formulation total -plate_length 0.079 -plate_thickness 0.005 \
    -solid_rho 1100 -solid_K 2e7 -solid_G 4.27e6 -plate_vf 0 -gravity 0,-18 -solid_damping 185 -t_end 0.12 \
    -output_interval 0 -progress_every 0 -output_dir "$OUT/$name" "$@" > "$OUT.$name.log" 2>&1 || { tail -20 "$OUT.$name.log"; exit 1; }; }
mkdir -p "$OUT"
run ny5 -plate_ny 5
run ny10 -plate_ny 10
run ny5_order1 -plate_ny 5 -solid_order 1
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
e = {k: json.load(open(f"{out}/{k}/summary.json"))["errors"] for k in ["ny5", "ny10", "ny5_order1"]}
eb = e["ny5"]["sag_euler_bernoulli"]
err = {k: v["sag"] / eb - 1 for k, v in e.items()}
print(f"cantilever (total lagrangian solid): sag {1000*e['ny5']['sag']:.4f} / {1000*e['ny10']['sag']:.4f} mm at 5 / 10 across against "
      f"{1000*eb:.3f} mm (Euler-Bernoulli, plane strain): {100*err['ny5']:+.2f} % (bound 3 %) / {100*err['ny10']:+.2f} % (bound 1 %) "
      f"(ratio {err['ny10']/err['ny5']:.2f}, bound 0.6); first-order gradient {100*err['ny5_order1']:+.1f} % (must exceed 20 %); "
      f"kinetic/strain energy at the end {max(v['kinetic_over_strain_energy'] for v in e.values()):.1e}")
for k, v in e.items():
    assert v["kinetic_over_strain_energy"] < 1e-4, f"{k}: not at rest at the end"
assert abs(err["ny5"]) < 0.03, "sag at 5 across more than 3 % from beam theory"
assert abs(err["ny10"]) < 0.01, "sag at 10 across more than 1 % from beam theory"
assert abs(err["ny10"]) < 0.6 * abs(err["ny5"]), "the error does not fall at least at first order from 5 to 10 across"
assert err["ny5_order1"] > 0.20, "the first-order gradient is no longer too compliant: the test no longer shows what the second-order fit fixes"
PY
