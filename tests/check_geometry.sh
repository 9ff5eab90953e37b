#!/usr/bin/env bash
# Shapes in -case boxes (issue 48, docs/geometry.md), short:
#  1. the cylinder array (cases/boxes/cylinder_array.opts, phi = 0.1) at L/dx = 20, both fluids, to
#     steady Stokes flow: the layout (no water inside the circle, walls within dx of it, dummies
#     deeper, the water's volume within 2 % of the cell less the circle, no water particle closer
#     than dx to a wall particle) and the drag F/(mu U) within 3 % of Sangani & Acrivos at the
#     fraction the lattice makes (measured: WCSPH -0.4 %, ISPH +1.3 %) and within 10 % at phi = 0.1
#     (+7 %, +9 %: at L/dx = 20 the circle holds 44 lattice points for its 40 dx^2).  The same
#     cylinder across the periodic corner gives the same drag (a shape across a periodic boundary); the
#     fluid's force on the cylinder (-body_force) balances the water's weight along x within 0.5 %
#     with WCSPH (measured -0.047 %; ISPH's -1.4 % is printed, not bounded: docs/turek_hron.md);
#     two cylinders as two bodies (-cylinder_2_body 2) get equal forces that add up to both's;
#  2. still water over a half-cylinder trough (cases/boxes/still_trough.opts, ISPH, 1 s): after
#     0.5 s no water faster than 0.01 sqrt(g H), no particle farther than 0.5 dx from its start;
#  3. still water in a hemispherical bowl (cases/boxes/still_bowl.opts, 3D, ISPH, 1 s), the same bounds
#     with H = 0.06 m (the depth over the flat floor);
#  4. STL surfaces (3D): SPHERIC Test 2 with its box from an STL file (cases/boxes/spheric_test2_stl.opts)
#     is the boxes run bit for bit over 3 steps; a sphere obstacle from an STL icosphere (5120
#     triangles) against -sphere_1 of the same radius: the same water, walls and dummies but for
#     lattice points within the icosphere's chord error (0.2 % of r) of the sphere.
MPI=$1; OUT=$2
mkdir -p "$OUT"
bad=0
BIN="${BINDIR:-bin}"/sphfsi
for f in wcsph isph; do
  timeout 300 $MPI $BIN -options_file cases/boxes/cylinder_array.opts -fluid $f -dx 0.005 -body_force -output_interval 4000 -progress_every 0 -output_dir "$OUT/cyl_$f" > "$OUT/cyl_$f.log" 2>&1 || { echo "geometry: the cylinder array ($f) failed"; bad=1; continue; }
  python3 - "$OUT/cyl_$f" <<'PY' || bad=1
import glob, json, math, sys
import h5py, numpy as np
out = sys.argv[1]
s = json.load(open(out + "/summary.json")); e = s["errors"]; dx = s["dx"]
with h5py.File(sorted(glob.glob(out + "/particles_*.h5"))[0]) as f:
    x, k, m = f["x"][:], f["kind"][:].ravel(), f["m"][:]
L, a = 0.1, 0.0178412
d = np.hypot(x[:, 0] - 0.05, x[:, 1] - 0.05) - a
w, du, fl = k == 1, k == 2, k == 0
vol = fl.sum() * dx * dx / (L * L - math.pi * a * a)
near = np.hypot(*(x[fl][:, None, :] - x[w | du][None, :, :]).transpose(2, 0, 1)).min() / dx
print(f"geometry: cylinder array ({s['fluid']}, L/dx 20): water {d[fl].min() / dx:.2f} dx and more from the circle, walls {d[w].min() / dx:.2f} to {d[w].max() / dx:.2f} dx, dummies {d[du].min() / dx:.2f} to {d[du].max() / dx:.2f} dx, water volume {vol:.4f} of the cell's, nearest wall particle {near:.2f} dx")
print(f"geometry: drag F/(mu U) {e['drag_coefficient']:.3f}: {100 * e['drag_rel_err']:+.2f} % against Sangani & Acrivos at phi 0.1 (bound 10 %), {100 * e['drag_rel_err_phi_lattice']:+.2f} % at the lattice's phi {e['phi_lattice']:.3f} (bound 3 %), Re {e['re']:.2g}")
assert d[fl].min() > 0 and d[w].min() > -dx and d[w].max() <= 0 and d[du].max() <= -dx and d[du].min() > -3 * dx, "layout"
assert abs(vol - 1) < 0.02 and near >= 0.999, "water volume or spacing"
assert abs(e["drag_rel_err"]) < 0.10 and abs(e["drag_rel_err_phi_lattice"]) < 0.03, "drag"
# the force on the cylinder (SimBodyForce, -body_force) balances the body force on the water in the
# steady state: the pair forces are exchanged, so sum m_f g_x less the water's momentum change, which
# decays as exp(-t / 600 s): 0.13 % of it is left at 4000 s (bound 0.5 %)
p = np.genfromtxt(out + "/probes.csv", delimiter=",", names=True)
fb = m[fl].sum() * 1.5e-10
wc = s["fluid"] == "wcsph"
print(f"geometry: the fluid's force on the cylinder {p['force_x'][-1]:.6g} N/m against the water's weight along x {fb:.6g} ({100 * (p['force_x'][-1] / fb - 1):+.3f} %, {'bound 0.5 %' if wc else 'not bounded with ISPH: docs/turek_hron.md'}), across it {p['force_y'][-1]:.1e}")
assert not wc or (abs(p["force_x"][-1] / fb - 1) < 0.005 and abs(p["force_y"][-1]) < 1e-3 * fb), "the force on the cylinder does not balance the body force"
PY
done
# two bodies (-cylinder_2_body 2): two cylinders in a cell of two periods along y see the same flow, so
# force_x_2 equals force_x (bound 1e-9, round-off of the sums' order), and the two add up to the force
# on both as one body (bound 1e-12)
TWO="-options_file cases/boxes/cylinder_array.opts -dx 0.005 -domain 0,0,0.1,0.2 -fluid_box_1 0,0,0.1,0.2 -cylinder_1 0.05,0.05,0.0178412 -cylinder_2 0.05,0.15,0.0178412 -body_force -t_end 400 -probe_interval 20 -output_interval 0 -progress_every 0"
for b in 1 2; do
  timeout 300 $MPI $BIN $TWO -cylinder_2_body $b -output_dir "$OUT/two_$b" > "$OUT/two_$b.log" 2>&1 || { echo "geometry: two cylinders (body $b) failed"; bad=1; }
done
python3 - "$OUT/two_2" "$OUT/two_1" <<'PY' || bad=1
import sys, numpy as np
two, one = (np.genfromtxt(d + "/probes.csv", delimiter=",", names=True) for d in sys.argv[1:3])
f1, f2, f = two["force_x"][-1], two["force_x_2"][-1], one["force_x"][-1]
print(f"geometry: two bodies: force_x {f1:.9g}, force_x_2 {f2:.9g} N/m (relative {abs(f2 / f1 - 1):.1e}, bound 1e-9); their sum against both as body 1 {f:.9g} (relative {abs((f1 + f2) / f - 1):.1e}, bound 1e-12)")
assert "force_x_2" not in one.dtype.names and f1 > 0 and abs(f2 / f1 - 1) < 1e-9 and abs((f1 + f2) / f - 1) < 1e-12, "the forces on two bodies"
PY
# the same array with its cylinder across the periodic corner (the cell shifted by half a period, whole
# spacings): the same lattice cut, so the same drag to round-off (bound 1e-6)
timeout 300 $MPI $BIN -options_file cases/boxes/cylinder_array.opts -dx 0.005 -cylinder_1 0,0,0.0178412 -output_interval 4000 -progress_every 0 -output_dir "$OUT/cyl_corner" > "$OUT/cyl_corner.log" 2>&1 || { echo "geometry: the cylinder across the periodic corner failed"; bad=1; }
python3 - "$OUT/cyl_wcsph" "$OUT/cyl_corner" <<'PY' || bad=1
import json, sys
a, b = (json.load(open(d + "/summary.json")) for d in sys.argv[1:3])
da, db = a["errors"]["drag_mean_last_tenth"], b["errors"]["drag_mean_last_tenth"]
print(f"geometry: the cylinder across the periodic corner: {b['particles']} particles ({a['particles']} centred), drag {db:.9g} against {da:.9g} centred (relative {abs(db / da - 1):.1e}, bound 1e-6)")
assert a["particles"] == b["particles"] and abs(db / da - 1) < 1e-6, "a shape across the periodic boundary differs from the same shape inside the cell"
PY
timeout 300 $MPI $BIN -options_file cases/boxes/still_trough.opts -fluid isph -t_end 1 -output_interval 1 -progress_every 0 -output_dir "$OUT/trough" > "$OUT/trough.log" 2>&1 || { echo "geometry: the still trough failed"; bad=1; }
r=$(python3 tools/still_check.py "$OUT/trough" --t0 0.5 --vbound 0.01 --drift 0.5 2>&1) || bad=1
echo "geometry: $r (bounds 0.01 sqrt(gH), 0.5 dx)"
# 3D: still water in a hemispherical bowl, the tank one STL surface (cases/boxes/still_bowl.opts, ISPH, 1 s)
timeout 300 $MPI $BIN -options_file cases/boxes/still_bowl.opts -fluid isph -t_end 1 -output_interval 1 -progress_every 0 -output_dir "$OUT/bowl" > "$OUT/bowl.log" 2>&1 || { echo "geometry: the still bowl failed"; bad=1; }
r=$(python3 tools/still_check.py "$OUT/bowl" --h 0.06 --t0 0.5 --vbound 0.01 --drift 0.5 2>&1) || bad=1
echo "geometry: $r (bounds 0.01 sqrt(gH), 0.5 dx)"
for c in spheric_test2 spheric_test2_stl; do
  timeout 300 $MPI $BIN -options_file cases/boxes/$c.opts -max_steps 3 -output_interval 1e-9 -progress_every 0 -output_dir "$OUT/$c" > "$OUT/$c.log" 2>&1 || { echo "geometry: $c failed"; bad=1; }
done
if r=$(python3 tests/compare_snapshots.py "$OUT/spheric_test2" "$OUT/spheric_test2_stl" 0 2>&1); then
  echo "geometry: SPHERIC Test 2 with the box from an STL file: bit for bit the wall box's run (3 steps; $r)"
else bad=1; echo "geometry: the STL box differs from the wall box: $r"; fi
python3 tools/stl_write.py sphere 0.05,0.05,0.05,0.03 "$OUT/ball.stl" --subdiv 4 > /dev/null
ARR="-case boxes -dim 3 -dx 0.005 -domain 0,0,0,0.1,0.1,0.1 -periodic x,y,z -fluid_box_1 0,0,0,0.1,0.1,0.1 -gravity 1e-10,0,0 -fluid_mu 1e-3 -fluid_c0 5e-4 -wcsph_alpha 0 -wcsph_delta 0 -max_steps 1 -output_interval 1e-9 -progress_every 0"
timeout 300 $MPI $BIN $ARR -sphere_1 0.05,0.05,0.05,0.03 -output_dir "$OUT/ball_sphere" > "$OUT/ball_sphere.log" 2>&1 || { echo "geometry: -sphere_1 failed"; bad=1; }
timeout 300 $MPI $BIN $ARR -stl_1 "$OUT/ball.stl" -output_dir "$OUT/ball_stl" > "$OUT/ball_stl.log" 2>&1 || { echo "geometry: -stl_1 (a sphere) failed"; bad=1; }
python3 - "$OUT/ball_sphere" "$OUT/ball_stl" <<'PY' || bad=1
import sys
import h5py, numpy as np
def kinds(d):
    with h5py.File(d + "/particles_00000.h5") as f:
        return {tuple(np.round(p / 1e-7).astype(np.int64)): k for p, k in zip(f["x"][:], f["kind"][:].ravel())}
a, b = kinds(sys.argv[1]), kinds(sys.argv[2])
r, h = 0.03, 0.005
off = [p for p in set(a) | set(b) if a.get(p) != b.get(p)]
far = [p for p in off if min(abs(np.linalg.norm(np.array(p) * 1e-7 - 0.05) - r + c * h) for c in (0, 1, 3)) > 0.002 * r]
print(f"geometry: a sphere from an STL icosphere (5120 triangles) against -sphere_1: {len(a)} and {len(b)} particles, {len(off)} lattice points of another kind, {len(far)} of them farther than 0.2 % of r from a row's boundary")
assert not far and len(off) < 0.01 * len(a), "the STL sphere's particles"
PY
exit $bad
