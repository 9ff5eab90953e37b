#!/usr/bin/env bash
# Three dimensions, the solid and FSI (issue 26).
# 1. The cantilever of square section (-case oscillating_plate -dim 3) at 4 particles across, one
#    period (to 0.35 s): its first bending period within 5 % of Euler-Bernoulli (the issue's bound at
#    6 across; measured +1.5 % at 4, +1.1 % at 6), its amplitude within 5 % of V_f c0 / omega.
# 2. The plate as a slab periodic across its width (-plate_periodic: plane strain) must move as the
#    2D plate at the same dx: the tip within 0.5 % of the 2D tip's swing to t = 0.01 s (measured
#    0.007 % to 0.02 s: only the 3D kernel's sums differ), which checks periodic images of a solid (its reference
#    positions shift with its images).  1 and 2 ranks agree bit for bit, and a restart from a
#    checkpoint repeats the run bit for bit.
# 3. The elastic gate as a slab periodic in z (-case elastic_gate -dim 3, ISPH, uniform dx = t/3) must
#    reproduce the 2D gate (FSI both ways in 3D, the implicit solid rows of the pressure equation):
#    the tip's horizontal displacement within 0.1 mm of the 2D run's at every probe to t = 5 ms and
#    the water's load within 5 % at the end (measured 0.006 mm and 3.7 %; to 10 ms 0.008 mm and 3.9 %,
#    twice the time; the issue's bound for the slab is 0.5 mm RMS over the run, docs/three_d.md).  The gate between side walls takes 3 steps.
MPI=$1; OUT=$2
MPI1=$(echo "$MPI" | sed 's/-n [0-9]*/-n 1/')
BIN="${BINDIR:-bin}"/sphfsi
mkdir -p "$OUT"
set -e
P3="-options_file cases/oscillating_plate.opts -dim 3 -plate_ny 4 -progress_every 0"
timeout 300 $MPI $BIN $P3 -t_end 0.35 -output_interval 0 -output_dir "$OUT/beam" > "$OUT/beam.log" 2>&1
python3 - "$OUT/beam" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json")); e = s["errors"]
print(f"3d cantilever (4 across, {s['particles']} particles, {s['steps']} steps): period T c0/L {e['period_c0_over_L']:.2f} against Euler-Bernoulli {e['period_c0_over_L_analytic']:.2f} "
      f"({100*e['period_rel_err']:+.2f} %, bound 5 %; Timoshenko {e['period_c0_over_L_timoshenko']:.2f}), amplitude {100*e['amplitude_rel_err']:+.2f} % (bound 5 %)")
assert e["zero_crossings"] >= 2, "the beam did not swing through a period"
assert abs(e["period_rel_err"]) < 0.05, "3D cantilever period off beam theory"
assert abs(e["amplitude_rel_err"]) < 0.05, "3D cantilever amplitude off beam theory"
PY
S3="$P3 -plate_width 0.05 -plate_periodic -t_end 0.01 -output_interval 0.01"
timeout 300 $MPI $BIN $S3 -output_dir "$OUT/slab" > "$OUT/slab.log" 2>&1
timeout 300 $MPI $BIN -options_file cases/oscillating_plate.opts -plate_ny 4 -progress_every 0 -t_end 0.01 -output_interval 0.01 -output_dir "$OUT/plate2d" > "$OUT/plate2d.log" 2>&1
python3 - "$OUT/slab" "$OUT/plate2d" <<'PY'
import sys
t3, t2 = ([float(l.split(",")[1]) for l in open(d + "/probes.csv").read().split("\n")[1:] if l] for d in sys.argv[1:3])
swing = max(abs(v) for v in t2); d = max(abs(a - b) for a, b in zip(t3, t2))
print(f"3d plate slab (periodic in z) against the 2D plate: tip differs by at most {1e6*d:.2f} um, {100*d/swing:.3f} % of the 2D swing {1e3*swing:.3f} mm (bound 0.5 %)")
assert len(t3) == len(t2) and d < 0.005 * swing, "the periodic 3D slab does not move as the 2D plate"
PY
timeout 300 $MPI1 $BIN $S3 -output_dir "$OUT/slab_rank1" > "$OUT/slab_rank1.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/slab_rank1" "$OUT/slab" 0) || { echo "3d solid: 1 and 2 ranks differ: $r"; exit 1; }
echo "3d solid ranks (1 against 2): $r"
timeout 300 $MPI $BIN $S3 -checkpoint_interval 0.005 -max_steps 200 -output_dir "$OUT/slab_restart" > "$OUT/slab_restart1.log" 2>&1
timeout 300 $MPI $BIN $S3 -restart "$OUT/slab_restart/checkpoint.h5" -output_dir "$OUT/slab_restart" > "$OUT/slab_restart2.log" 2>&1
r=$(python3 tests/compare_snapshots.py "$OUT/slab" "$OUT/slab_restart" 0) || { echo "3d solid: the restarted run differs: $r"; exit 1; }
echo "3d solid restart: $r"
G="-options_file cases/elastic_gate.opts -dx 0.0016667 -dx_coarse 0.0016667 -t_end 0.005 -probe_interval 0.001 -output_interval 0 -progress_every 0"
timeout 300 $MPI $BIN $G -output_dir "$OUT/gate2d" > "$OUT/gate2d.log" 2>&1
timeout 600 $MPI $BIN $G -dim 3 -output_dir "$OUT/gate3d" > "$OUT/gate3d.log" 2>&1
python3 - "$OUT/gate3d" "$OUT/gate2d" <<'PY'
import sys, json
rows = [[[float(v) for v in l.split(",")] for l in open(d + "/probes.csv").read().split("\n")[1:] if l] for d in sys.argv[1:3]]
r3, r2 = rows
d = max(abs(a[1] - b[1]) for a, b in zip(r3, r2)); load = abs(r3[-1][4] / r2[-1][4] - 1)
s3 = json.load(open(sys.argv[1] + "/summary.json"))
print(f"3d gate slab (ISPH, {s3['particles']} particles, {s3['steps']} steps) against the 2D gate: tip_dx {1e3*r3[-1][1]:.4f} / {1e3*r2[-1][1]:.4f} mm at t = {r3[-1][0]:.3f} s, "
      f"largest difference {1e3*d:.4f} mm (bound 0.1 mm), load {r3[-1][4]:.2f} / {r2[-1][4]:.2f} N/m ({100*load:.1f} %, bound 5 %)")
assert len(r3) == len(r2) and r3[-1][1] > 2e-4, "the gate did not open"
assert d < 1e-4, "the 3D gate slab's tip differs from the 2D gate's"
assert load < 0.05, "the 3D gate slab's load differs from the 2D gate's"
PY
# WCSPH's gate slab (Eq. 41's repulsion scaled in 3D to the 2D one's total next to a flat solid):
# tip within 0.05 mm of the 2D run's, the load within 5 % at 5 ms (measured 0.0008 mm and 0.4-0.8 %: the last bits of the scale move it;
# unscaled, the 3D load fell to -2 N/m against 17 N/m at 10 ms)
W="-options_file cases/elastic_gate_wcsph.opts -dx 0.0016667 -dx_coarse 0.0016667 -t_end 0.005 -probe_interval 0.001 -output_interval 0 -progress_every 0"
timeout 300 $MPI $BIN $W -output_dir "$OUT/gate2d_wcsph" > "$OUT/gate2d_wcsph.log" 2>&1
timeout 600 $MPI $BIN $W -dim 3 -output_dir "$OUT/gate3d_wcsph" > "$OUT/gate3d_wcsph.log" 2>&1
python3 - "$OUT/gate3d_wcsph" "$OUT/gate2d_wcsph" <<'PY'
import sys
r3, r2 = ([[float(v) for v in l.split(",")] for l in open(d + "/probes.csv").read().split("\n")[1:] if l] for d in sys.argv[1:3])
d = max(abs(a[1] - b[1]) for a, b in zip(r3, r2)); load = abs(r3[-1][4] / r2[-1][4] - 1)
print(f"3d gate slab (WCSPH) against the 2D gate: tip_dx {1e3*r3[-1][1]:.4f} / {1e3*r2[-1][1]:.4f} mm at t = {r3[-1][0]:.4f} s, largest difference {1e3*d:.4f} mm (bound 0.05 mm), load {r3[-1][4]:.2f} / {r2[-1][4]:.2f} N/m ({100*load:.1f} %, bound 5 %)")
assert len(r3) == len(r2) and d < 5e-5 and load < 0.05, "the 3D WCSPH gate slab differs from the 2D gate"
PY
# the gate between side walls (-gate_side_walls, here 0.02 m wide): the walls on both sides of the
# whole section, and the gate opening in +x in its first steps
timeout 300 $MPI $BIN $G -dim 3 -gate_side_walls -gate_width 0.02 -max_steps 3 -probe_interval 1e-4 -output_interval 0 -output_dir "$OUT/gate_walls" > "$OUT/gate_walls.log" 2>&1
python3 - "$OUT/gate_walls" <<'PY'
import sys, json
s = json.load(open(sys.argv[1] + "/summary.json"))
r = [[float(v) for v in l.split(",")] for l in open(sys.argv[1] + "/probes.csv").read().split("\n")[1:] if l]
print(f"3d gate between side walls (0.02 m): {s['particles']} particles, {s['steps']} steps, tip_dx {1e3*r[-1][1]:.4f} mm at t = {r[-1][0]:.4f} s")
assert s["steps"] == 3 and r[-1][1] > 0, "the gate between side walls did not start to open"
PY
echo "3d solid: the cantilever against beam theory, the periodic slab against the 2D plate (ranks and restart equal), the gate slab against the 2D gate"
