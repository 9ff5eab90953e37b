#!/usr/bin/env bash
# Hydrostatic WCSPH: after settling (t = 0.6 s, ~8 acoustic crossings... and ~2 gravity-wave periods
# of the tank) the floor pressure is within 3 % of rho g H, nothing moves faster than
# 5 % of sqrt(g H), and every particle is still in the tank (a particle leaving fails the run).
set -e
MPI=$1; OUT=$2
$MPI bin/sphfsi -options_file cases/hydrostatic.opts -t_end 0.6 -output_interval 0 -output_dir "$OUT" -progress_every 0
python3 - "$OUT" <<'PY'
import json, sys, math
s = json.load(open(sys.argv[1] + "/summary.json"))
e = s["errors"]
H = 0.1; vbound = 0.05 * math.sqrt(9.81 * H)
print(f"hydrostatic: p_bottom error {100*e['p_bottom_rel_err']:.2f} % of rho g H (bound 3 %), v_max {e['v_max_final']:.4f} m/s (bound {vbound:.3f}), {s['particles']} particles, {s['steps']} steps, {s['particle_steps_per_s']:.3g} particle-steps/s")
assert 0 <= e["p_bottom_rel_err"] < 0.03, "floor pressure off by more than 3 %"
assert e["v_max_final"] < vbound, "water at rest moves"
assert s["mass_rel_drift"] == 0, "mass changed"
PY
