#!/usr/bin/env bash
# Still water stays still: 0.1 m of water at rest, dx = H/40, held 2 s.  A tank at rest must be a
# fixed point of the scheme up to the solver's tolerance, so after the first second nothing moves
# faster than 1 % of sqrt(g H) and no particle has moved by more than 0.5 dx from its start lattice
# (make hard holds the same tank 10 s against 1 % of sqrt(g H) and 1 dx: docs/hard.md).  The side
# wall's pressure after the first second, read as a wall sensor reads it, is within 2 % of rho g H
# of rho g (H - y) (rms over 8 heights and the samples; issue 56).
set -e
MPI=$1; OUT=$2; shift 2 # further arguments go to sphfsi (e.g. -fluid isph)
$MPI bin/sphfsi -options_file cases/hydrostatic.opts -t_end 2 -output_interval 2 -output_dir "$OUT" -progress_every 0 "$@"
python3 - "$OUT" <<'PY'
import csv, glob, json, math, sys
import h5py, numpy as np
out = sys.argv[1]
s = json.load(open(out + "/summary.json")); dx = s["dx"]; H = 0.1
rows = list(csv.DictReader(open(out + "/probes.csv")))
vmax = max(float(r["v_max"]) for r in rows if float(r["t"]) >= 1.0)
snaps = sorted(glob.glob(out + "/particles_*.h5"))
def fluid(f):
    d = h5py.File(f, "r"); k = d["kind"][:].ravel() == 0; i = d["id"][:].ravel()[k]
    return i[np.argsort(i)], d["x"][:][k][np.argsort(i)]
(i0, x0), (i1, x1) = fluid(snaps[0]), fluid(snaps[-1])
assert len(snaps) >= 2 and np.array_equal(i0, i1), "the fluid particles changed"
drift = np.linalg.norm(x1 - x0, axis=1).max() / dx
vb = 0.01 * math.sqrt(9.81 * H)
print(f"still tank ({s['fluid']}): v_max {vmax:.2g} m/s for t >= 1 s (bound {vb:.2g}), largest displacement {drift:.2f} dx in 2 s (bound 0.5)")
e = s["errors"]
print(f"still tank ({s['fluid']}): side-wall pressure after 1 s, rms deviation from rho g (H - y) {100*e['p_wall_spread']:.2f} % of rho g H (bound 2 %), largest {100*e['p_wall_dev_max']:.2f} %")
assert vmax <= vb, "water at rest moves"
assert e["p_wall_spread"] <= 0.02, "the wall pressure of still water is noisy"
assert drift <= 0.5, "the lattice drifts"
PY
