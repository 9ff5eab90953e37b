#!/usr/bin/env bash
# A case without C (issue 27): the dam break (both fluids) and the hydrostatic tank (2D, and 3D in both fluids) written as data
# (cases/boxes/*.opts, -case boxes) give the same particles and the same state as the built-in scenes
# after 0.02 s on the same ranks, bit for bit, and so does the elastic gate (two particle sizes, a
# solid, its clamp, a wall box, outflow; both fluids) after 0.01 s; cases/dam_break_obstacle.opts
# (a case that is no built-in scene) runs; a box whose sides are not multiples of dx is filled exactly.
MPI=$1; OUT=$2
mkdir -p "$OUT"
bad=0
BIN="${BINDIR:-bin}"/sphfsi
same() { # name, tolerance, end time, built-in case file, boxes case file, options...
  local name=$1 tol=$2 t=$3 builtin=$4 boxes=$5; shift 5
  timeout 300 $MPI $BIN -options_file "$builtin" "$@" -t_end $t -output_interval $t -progress_every 0 -output_dir "$OUT/${name}_builtin" > "$OUT/${name}_builtin.log" 2>&1 || { echo "boxes: $name built-in run failed"; bad=1; return; }
  timeout 300 $MPI $BIN -options_file "$boxes" "$@" -t_end $t -output_interval $t -progress_every 0 -output_dir "$OUT/${name}_boxes" > "$OUT/${name}_boxes.log" 2>&1 || { echo "boxes: $name boxes run failed"; bad=1; return; }
  local r; r=$(python3 tests/compare_snapshots.py "$OUT/${name}_builtin" "$OUT/${name}_boxes" $tol) || { echo "boxes: $name differs from the built-in scene: $r"; bad=1; return; }
  echo "boxes: $name as the built-in scene: $r"
}
same dam_break_wcsph 0 0.02 cases/dam_break.opts cases/boxes/dam_break.opts -fluid wcsph
same dam_break_isph 0 0.02 cases/dam_break.opts cases/boxes/dam_break.opts -fluid isph
same hydrostatic_wcsph 0 0.02 cases/hydrostatic.opts cases/boxes/hydrostatic.opts -fluid wcsph
same hydrostatic_3d_wcsph 0 0.02 cases/hydrostatic.opts cases/boxes/hydrostatic_3d.opts -dim 3 -dx 0.01 -fluid wcsph
same hydrostatic_3d_isph 0 0.02 cases/hydrostatic.opts cases/boxes/hydrostatic_3d.opts -dim 3 -dx 0.01 -fluid isph
same elastic_gate_isph 0 0.01 cases/elastic_gate.opts cases/boxes/elastic_gate.opts -fluid isph
same elastic_gate_wcsph 0 0.01 cases/elastic_gate.opts cases/boxes/elastic_gate.opts -fluid wcsph
# a solid as boxes in 3D: the clamped beam of cases/boxes/cantilever_3d.opts at rest under its weight,
# its end's sag within 3 % of beam theory (Euler-Bernoulli + Timoshenko shear, 3.036 mm), and no
# sideways motion; to 0.4 s of the case's 0.6 (the damped beam's sag is then within 0.15 % of its
# settled value: measured -0.60 % at 0.4 s, -0.45 % at 0.6 s, 4 across)
timeout 300 $MPI $BIN -options_file cases/boxes/cantilever_3d.opts -t_end 0.4 -output_interval 0 -progress_every 0 -output_dir "$OUT/cantilever_3d" > "$OUT/cantilever_3d.log" 2>&1 || { echo "boxes: cases/boxes/cantilever_3d.opts failed"; bad=1; }
python3 - "$OUT/cantilever_3d" <<'PY' || bad=1
import sys
rows = [[float(v) for v in l.split(",")] for l in open(sys.argv[1] + "/probes.csv").read().split("\n")[1:] if l]
E = 9 * 3.25e6 * 7.15e5 / (3 * 3.25e6 + 7.15e5); L, H, q = 0.2, 0.02, 1000 * 1.0
ref = 1.5 * q * L**4 / (E * H * H) + q * L * L / (2 * (5 / 6) * 7.15e5)
sag = -rows[-1][5]
print(f"boxes: 3D solid beam at rest: sag {1e3*sag:.4f} mm against beam theory {1e3*ref:.4f} mm ({100*(sag/ref-1):+.2f} %, bound 3 %), sideways {abs(rows[-1][4]):.1e} m")
assert abs(sag / ref - 1) < 0.03 and abs(rows[-1][4]) < 1e-9, "the 3D beam given as boxes misses beam theory"
PY
# a box whose sides are not multiples of dx is filled exactly (SceneFitSpacing): SPHERIC Test 2's
# column 1.228 x 1 x 0.55 m and its obstacle at dx = 0.04 m hold their volume (the mass over rho0),
# and their outer particles sit half a spacing inside each face (before: 1.24 x 1 x 0.56 m of water)
timeout 300 $MPI $BIN -options_file cases/boxes/spheric_test2.opts -max_steps 1 -output_interval 1 -progress_every 0 -output_dir "$OUT/fill" > "$OUT/fill.log" 2>&1 || { echo "boxes: cases/boxes/spheric_test2.opts failed"; bad=1; }
python3 - "$OUT/fill" <<'PY' || bad=1
import glob, sys
import h5py, numpy as np
with h5py.File(sorted(glob.glob(sys.argv[1] + "/particles_*.h5"))[0]) as f:
    x, kind, m = f["x"][:], f["kind"][:].ravel(), f["m"][:].ravel()
bad = []
for name, sel, box in (("water", kind == 0, (1.992, 0, 0, 3.22, 1, 0.55)),
                       ("obstacle", (kind >= 1) & (kind <= 2) & (x[:, 0] > 0.6) & (x[:, 0] < 0.9) & (x[:, 1] > 0.25) & (x[:, 1] < 0.75) & (x[:, 2] > 0), (0.6635, 0.2985, 0, 0.8245, 0.7015, 0.161))):
    lo, hi = np.array(box[:3]), np.array(box[3:])
    vol = m[sel].sum() / 1000
    xs = x[sel]
    u = [np.unique(np.round(xs[:, d], 9)) for d in range(3)]
    s = [(u[d][-1] - u[d][0]) / (len(u[d]) - 1) for d in range(3)]  # the lattice's spacing along each axis
    gap = max(max(abs(xs[:, d].min() - s[d] / 2 - lo[d]), abs(hi[d] - s[d] / 2 - xs[:, d].max())) for d in range(3))
    print(f"boxes: {name} filled: volume {vol:.6f} m^3 against {np.prod(hi - lo):.6f}, faces off by {gap:.1e} m")
    if abs(vol / np.prod(hi - lo) - 1) > 1e-9 or gap > 1e-9:
        bad.append(name)
assert not bad, f"boxes: not filled exactly: {bad}"
PY
timeout 300 $MPI $BIN -options_file cases/dam_break_obstacle.opts -t_end 0.02 -output_interval 0.01 -progress_every 0 -output_dir "$OUT/obstacle" > "$OUT/obstacle.log" 2>&1 || { echo "boxes: cases/dam_break_obstacle.opts failed: status $?"; bad=1; }
grep -q '"status": "completed"' "$OUT/obstacle/summary.json" 2>/dev/null && echo "boxes: cases/dam_break_obstacle.opts runs" || { echo "boxes: cases/dam_break_obstacle.opts did not complete"; bad=1; }
exit $bad
