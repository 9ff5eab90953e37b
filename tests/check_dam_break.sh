#!/usr/bin/env bash
# Dam break (both fluids): surge front against Martin & Moyce (1952) (n^2 = 2, a = 2.25 in),
# T = t sqrt(2g/a), bound 10 % at the points 1.5 <= T <= 3.5.  Before T = 1.5 the experiment lags
# every simulation by the time its gate took to clear the column (Martin & Moyce's own remark; SPH
# and MPS results run ahead there too): ISPH at a/80, close to converged, is 11.8-12.6 / 14.5-15.9 %
# ahead at T = 0.832 / 1.219 with either pressure gradient (docs/convergence.md), so those points test the
# experiment's start, not the scheme, and are printed without a bound.
set -e
MPI=$1; OUT=$2; shift 2 # further arguments go to sphfsi (e.g. -fluid isph)
$MPI bin/sphfsi -options_file cases/dam_break.opts -t_end 0.19 -output_interval 0 -output_dir "$OUT" -progress_every 0 "$@"
python3 - "$OUT" <<'PY'
import csv, sys, math, bisect
a, g = 0.05715, 9.81
rows = list(csv.DictReader(open(sys.argv[1] + "/probes.csv")))
t = [float(r["t"]) for r in rows]; f = [float(r["front_x"]) for r in rows]
assert abs(f[0] - a) < 1e-9, "front does not start at the column width"
assert all(f[i + 1] >= f[i] - 1e-9 for i in range(len(f) - 1)), "front moved back"
import os
path = os.path.join(os.environ.get("SPHFSI_REFDATA", "../shared/refdata"), "martin_moyce1952_surge_n2eq2_a2.25in__pysph.csv")
assert os.path.exists(path), f"reference data {path} not found: set SPHFSI_REFDATA to the refdata directory"
ref = [l.strip().split(",") for l in open(path) if l[0] not in "#T"]
worst = 0; n = 0
for T, Z in ((float(T), float(Z)) for T, Z in ref):
    if T > 3.5: break
    tt = T / math.sqrt(2 * g / a)
    i = bisect.bisect(t, tt); zs = (f[i-1] + (f[i] - f[i-1]) * (tt - t[i-1]) / (t[i] - t[i-1])) / a
    err = (zs - Z) / Z
    if T < 1.5:
        print(f"dam_break: T {T:.3f}  Z_exp {Z:.3f}  Z_sph {zs:.3f}  error {100*err:+.1f} % (the experiment's start: no bound)")
        continue
    print(f"dam_break: T {T:.3f}  Z_exp {Z:.3f}  Z_sph {zs:.3f}  error {100*err:+.1f} % (bound 10 %)")
    assert abs(err) <= 0.10, f"front off by {100*err:.1f} % at T = {T}"
    worst = max(worst, abs(err)); n += 1
assert n >= 3
print(f"dam_break: front within bounds at {n} points, worst {100*worst:.1f} %")
PY
