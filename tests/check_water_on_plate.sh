#!/usr/bin/env bash
# Water at rest on a clamped elastic plate (issue 5: fluid on solid), periodic in x so that no
# side wall takes a share: the clamp's mean support force over the second half of 0.15 s, less the
# plate's weight, must equal the water's weight.  Bounds: WCSPH 2 % (measured 0.3 %; the rest is
# the acoustic ringing of the start); ISPH 5 % (L_BOUND): its hybrid pressure gradient is not
# antisymmetric at the free surface, so the water's own pair forces do not carry all its weight to
# the plate (1.6 % with the symmetric Eq. 14 gradient, 2.9 % with the hybrid one, measured).  The
# water must stay at rest (5 % of sqrt(g H)) and keep its mass.
#   tests/check_water_on_plate.sh "MPIEXEC -n P" OUTDIR [extra sphfsi options]
set -e
MPI=$1; OUT=$2; shift 2
$MPI bin/sphfsi -case water_on_plate -t_end 0.15 -probe_interval 0.005 -output_interval 0 -output_dir "$OUT" -progress_every 0 "$@"
L_BOUND=${L_BOUND:-0.02} python3 - "$OUT" <<'PY'
import json, sys, math, os
s = json.load(open(sys.argv[1] + "/summary.json"))
e = s["errors"]; lb = float(os.environ["L_BOUND"])
rows = [l.split(",") for l in open(sys.argv[1] + "/probes.csv").read().split("\n")[1:] if l]
vmax = float(rows[-1][3]); vbound = 0.05 * math.sqrt(9.81 * 0.05)
print(f"water on plate ({s['fluid']}): support - plate weight = {e['load_ratio_mean']:.4f} x water weight {e['water_weight']:.3f} N/m "
      f"(bound {100*lb:.0f} %), v_max {vmax:.4f} m/s (bound {vbound:.3f}), {s['particles']} particles, {s['steps']} steps")
assert 0 <= e["load_rel_err"] < lb, f"the plate does not carry the water's weight within {100*lb:.0f} %"
assert vmax < vbound, "water at rest moves"
assert s["mass_rel_drift"] == 0, "mass changed"
PY
