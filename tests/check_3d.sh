#!/usr/bin/env bash
# Three dimensions (issue 26; fluids so far): the hydrostatic tank as a 3D box (-dim 3, 0.1 m of
# water in a 0.1 x 0.1 m tank, dx = H/10, 1000 fluid particles, walls on five sides).
# WCSPH: after 0.6 s (as the 2D test: ~8 acoustic crossings) the floor pressure is within 3 % of
# rho g H and nothing moves faster than 5 % of sqrt(g H); the snapshot holds 3-component positions
# and the XDMF XYZ geometry.  With delta-SPH and shifting, 1 and 2 ranks agree exactly (the
# neighbour sums are in an order that does not depend on the ranks) and a restart from a checkpoint
# repeats the run bit for bit.
# ISPH: a column at rest is one-dimensional, so the 3D tank's floor pressure must equal the 2D
# tank's at the same dx (within 0.5 % of rho g H: a verification of the 3D pressure equation,
# whose own resolution error at H/10 is the 2D one); nothing moves faster than 5 % of sqrt(g H);
# 1 and 2 ranks agree to the solver's round-off (1e-8, as the 2D rank test) and a restart on the
# same ranks is exact.  The run guard: a step 100 times too large ends as a fault naming a 3D point.
# Taylor-Green in a triply periodic cube (-dim 3: the 2D vortices, uniform in z, an exact solution;
# the case file's Wendland C2 at 2 dx, shifting and jittered start, L/25, to t = 0.1 s): periodic
# images in all three directions and the 3D viscous and pressure operators.  The flow does not depend
# on z, so the 3D run's errors against the exact solution must be those of the 2D run at the same dx
# (within 1 point of the kinetic-energy and of the L2 velocity error: a verification of the 3D
# code; ISPH's own error at L/25 and 5 steps is the shifting's damping, 4 % in 2D), and WCSPH's within
# the 2D test's bound of 5 %.
MPI=$1; OUT=$2
MPI1=$(echo "$MPI" | sed 's/-n [0-9]*/-n 1/')
BIN="${BINDIR:-bin}"/sphfsi
mkdir -p "$OUT"
set -e
H3="-options_file cases/hydrostatic.opts -dim 3 -dx 0.01 -progress_every 0"
timeout 300 $MPI $BIN $H3 -t_end 0.6 -output_interval 0.3 -output_dir "$OUT/box" > "$OUT/box.log" 2>&1
python3 - "$OUT/box" <<'PY'
import json, sys, math, h5py, glob
d = sys.argv[1]
s = json.load(open(d + "/summary.json")); e = s["errors"]
H = 0.1; vbound = 0.05 * math.sqrt(9.81 * H)
print(f"3d hydrostatic box (wcsph): p_bottom error {100*e['p_bottom_rel_err']:.2f} % of rho g H (bound 3 %), v_max {e['v_max_final']:.4f} m/s (bound {vbound:.3f}), {s['particles']} particles, {s['steps']} steps")
assert 0 <= e["p_bottom_rel_err"] < 0.03, "floor pressure off by more than 3 %"
assert e["v_max_final"] < vbound, "water at rest moves"
assert s["mass_rel_drift"] == 0, "mass changed"
with h5py.File(sorted(glob.glob(d + "/particles_*.h5"))[-1]) as f:
    assert f["x"].shape[1] == 3 and f["v"].shape[1] == 3, f"positions {f['x'].shape}, velocities {f['v'].shape}: not 3D"
    z = f["x"][:, 2][f["kind"][:].ravel() == 0]
    assert z.min() > 0 and z.max() < 0.12, f"fluid between z = {z.min()} and {z.max()}: left the tank"
assert 'GeometryType="XYZ"' in open(d + "/particles.xmf").read(), "XDMF geometry is not XYZ"
PY
R3="$H3 -wcsph_shift 1 -t_end 0.1 -output_interval 0.1"
timeout 300 $MPI1 $BIN $R3 -output_dir "$OUT/rank1" > "$OUT/rank1.log" 2>&1
timeout 300 $MPI $BIN $R3 -output_dir "$OUT/rank2" > "$OUT/rank2.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/rank1" "$OUT/rank2" 0) || { echo "3d: 1 and 2 ranks differ: $r"; exit 1; }
echo "3d ranks (1 against 2): $r"
timeout 300 $MPI $BIN $R3 -checkpoint_interval 0.05 -max_steps 300 -output_dir "$OUT/restart" > "$OUT/restart1.log" 2>&1
timeout 300 $MPI $BIN $R3 -restart "$OUT/restart/checkpoint.h5" -output_dir "$OUT/restart" > "$OUT/restart2.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/rank2" "$OUT/restart" 0) || { echo "3d: the restarted run differs: $r"; exit 1; }
echo "3d restart: $r"
# the run guard in 3D: a step 100 times too large ends as a fault (exit status 4) that names a 3D point,
# with a finite last good state of 3-component positions
set +e
timeout 120 $MPI $BIN -case hydrostatic -dim 3 -dx 0.02 -dt 0.01 -t_end 0.5 -progress_every 0 -output_dir "$OUT/fault" > "$OUT/fault.log" 2>&1
rc=$?
set -e
[ $rc -eq 4 ] && grep -q 'left the domain .* x .* x .*at ([-0-9.e]*, [-0-9.e]*, [-0-9.e]*)' "$OUT/fault.log" || { echo "3d: the unstable run did not end as a fault naming a 3D point (exit $rc)"; exit 1; }
python3 -c "import h5py, numpy as np, sys; f = h5py.File(sys.argv[1]); assert f['x'].shape[1] == 3 and np.isfinite(f['x'][:]).all()" "$OUT/fault/last_good.h5"
echo "3d fault: exit 4, $(grep -o 'e.g. id .*) at ([^)]*)' "$OUT/fault.log" | head -1), last_good.h5 finite"
# ISPH, with the BoomerAMG block for 3D (strong threshold 0.5, HMIS, ext+i, aggressive coarsening)
I3="-options_file cases/hydrostatic.opts -fluid isph -dx 0.01 -progress_every 0 -ppe_pc_hypre_boomeramg_coarsen_type HMIS -ppe_pc_hypre_boomeramg_interp_type ext+i -ppe_pc_hypre_boomeramg_P_max 4 -ppe_pc_hypre_boomeramg_agg_nl 1 -ppe_pc_hypre_boomeramg_strong_threshold 0.5"
timeout 300 $MPI $BIN $I3 -dim 3 -t_end 0.6 -output_interval 0.3 -output_dir "$OUT/isph3" > "$OUT/isph3.log" 2>&1
timeout 300 $MPI $BIN $I3 -dim 2 -t_end 0.6 -output_interval 0.3 -output_dir "$OUT/isph2" > "$OUT/isph2.log" 2>&1
python3 - "$OUT/isph3" "$OUT/isph2" <<'PY'
import json, sys, math
s3, s2 = (json.load(open(d + "/summary.json")) for d in sys.argv[1:3])
e3, e2 = s3["errors"], s2["errors"]
H = 0.1; vbound = 0.05 * math.sqrt(9.81 * H)
# p_bottom_rel_err is |mean - rho g H| / rho g H; both columns sit below rho g H (the surface row is at P = 0)
d = abs(e3["p_bottom_rel_err"] - e2["p_bottom_rel_err"])
print(f"3d hydrostatic box (isph): p_bottom error {100*e3['p_bottom_rel_err']:.2f} % of rho g H, 2D at the same dx {100*e2['p_bottom_rel_err']:.2f} % (difference bound 0.5 %), v_max {e3['v_max_final']:.4f} m/s (bound {vbound:.3f}), CG its per step {s3['ksp_its_mean']:.2f}")
assert d < 0.005, "the 3D ISPH column's floor pressure differs from the 2D column's"
assert e3["v_max_final"] < vbound, "water at rest moves"
assert s3["mass_rel_drift"] == 0, "mass changed"
PY
RI="$I3 -dim 3 -t_end 0.05 -output_interval 0.05 -ppe_ksp_rtol 1e-10" # the V-cycle differs with the ranks: agreement to the solver tolerance
timeout 300 $MPI1 $BIN $RI -output_dir "$OUT/isph_rank1" > "$OUT/isph_rank1.log" 2>&1
timeout 300 $MPI $BIN $RI -output_dir "$OUT/isph_rank2" > "$OUT/isph_rank2.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/isph_rank1" "$OUT/isph_rank2" 1e-8) || { echo "3d isph: 1 and 2 ranks differ: $r"; exit 1; }
echo "3d isph ranks (1 against 2, bound 1e-8): $r"
timeout 300 $MPI $BIN $RI -checkpoint_interval 0.025 -max_steps 6 -output_dir "$OUT/isph_restart" > "$OUT/isph_restart1.log" 2>&1
timeout 300 $MPI $BIN $RI -restart "$OUT/isph_restart/checkpoint.h5" -output_dir "$OUT/isph_restart" > "$OUT/isph_restart2.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/isph_rank2" "$OUT/isph_restart" 0) || { echo "3d isph: the restarted run differs: $r"; exit 1; }
echo "3d isph restart: $r"
for f in wcsph isph; do
  for dim in 2 3; do
    timeout 300 $MPI $BIN -options_file cases/taylor_green.opts -fluid $f -dim $dim -dx 0.04 -t_end 0.1 -output_interval 0 -progress_every 0 -ppe_pc_hypre_boomeramg_strong_threshold 0.5 -ppe_pc_hypre_boomeramg_coarsen_type HMIS -ppe_pc_hypre_boomeramg_agg_nl 1 -output_dir "$OUT/tg_${f}_$dim" > "$OUT/tg_${f}_$dim.log" 2>&1
  done
  python3 - "$OUT/tg_${f}_3" "$OUT/tg_${f}_2" <<'PY'
import json, sys
s3, s2 = (json.load(open(d + "/summary.json")) for d in sys.argv[1:3])
e3, e2 = s3["errors"], s2["errors"]
print(f"3d taylor-green ({s3['fluid']}, L/25, t = {e3['t_final']:.2f} s): E error {100*e3['e_kin_rel_err_final']:.2f} % (2D {100*e2['e_kin_rel_err_final']:.2f} %), L2 velocity error {100*e3['l2_vel_err_final']:.2f} % (2D {100*e2['l2_vel_err_final']:.2f} %), {s3['particles']} particles, {s3['steps']} steps")
assert abs(e3["e_kin_rel_err_final"] - e2["e_kin_rel_err_final"]) < 0.01 and abs(e3["l2_vel_err_final"] - e2["l2_vel_err_final"]) < 0.01, "the 3D vortices differ from the 2D ones"
assert s3["fluid"] == "isph" or (e3["e_kin_rel_err_final"] < 0.05 and e3["l2_vel_err_final"] < 0.05), "3D WCSPH Taylor-Green off the exact decay"
PY
done
echo "3d: the box at rest in both fluids, 1 and 2 ranks equal, restart equal; Taylor-Green in a periodic cube"
