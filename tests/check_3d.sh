#!/usr/bin/env bash
# Three dimensions (issue 26, WCSPH so far): the hydrostatic tank as a 3D box (-dim 3, 0.1 m of
# water in a 0.1 x 0.1 m tank, dx = H/10, 1000 fluid particles, walls on five sides).  After 0.6 s
# (as the 2D test: ~8 acoustic crossings) the floor pressure is within 3 % of rho g H and nothing
# moves faster than 5 % of sqrt(g H); the snapshot holds 3-component positions and the XDMF XYZ
# geometry.  With delta-SPH and shifting, 1 and 2 ranks agree exactly (the neighbour sums are in
# an order that does not depend on the ranks) and a restart from a checkpoint repeats the run bit
# for bit.
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
echo "3d: the box at rest, 1 and 2 ranks equal, restart equal"
