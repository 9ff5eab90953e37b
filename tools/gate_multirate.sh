#!/usr/bin/env bash
# Multi-rate benchmark (issue 5; not a test): the elastic gate with the solid sub-cycled inside each
# fluid step (-solid_subcycle 1, the default) against one step for both (0, the paper's way), in both
# fluid schemes, on 2 ranks, to T (default 0.05 s) at dx 1.25 mm.  Reports wall times, steps, the
# speed-up and the largest difference of the tip motion over the run.  Writes
# out/gate_multirate/table.md.
#   tools/gate_multirate.sh [T] [DX]
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-} -n 2"
T=${1:-0.05}; DX=${2:-0.00125}
OUT=out/gate_multirate; mkdir -p $OUT
for f in isph wcsph; do
  for sc in 1 0; do
    $MPI bin/sphfsi -overwrite -options_file cases/elastic_gate.opts -fluid $f -dx $DX -dx_coarse $DX -t_end $T -probe_interval 0.001 \
      -output_interval 0 -progress_every 0 -solid_subcycle $sc -output_dir $OUT/${f}_sub$sc > $OUT/${f}_sub$sc.log 2>&1 \
      || { echo "run failed: $OUT/${f}_sub$sc.log" >&2; exit 1; }
  done
done
python3 - "$OUT" "$T" "$DX" <<'PY' | tee $OUT/table.md
import csv, json, sys
import numpy as np
out, T, DX = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
def probes(d):
    r = list(csv.DictReader(open(f"{out}/{d}/probes.csv")))
    return np.array([float(q["t"]) for q in r]), np.array([float(q["tip_dx"]) for q in r]), np.array([float(q["tip_dy"]) for q in r])
print(f"Elastic gate to t = {T} s, dx {1000*DX:g} mm, 2 ranks: solid sub-cycled in the fluid step (multi-rate) vs one step for both\n")
print("| fluid | multi-rate | steps | solid sub-steps per step | wall s | tip_dx(T) mm | max diff tip_dx / tip_dy (mm) | speed-up |")
print("|---|---|---|---|---|---|---|---|")
for f in ("isph", "wcsph"):
    s1 = json.load(open(f"{out}/{f}_sub1/summary.json")); s0 = json.load(open(f"{out}/{f}_sub0/summary.json"))
    t1, x1, y1 = probes(f"{f}_sub1"); t0, x0, y0 = probes(f"{f}_sub0")
    dxm = 1000 * np.max(np.abs(np.interp(t0, t1, x1) - x0)); dym = 1000 * np.max(np.abs(np.interp(t0, t1, y1) - y0))
    print(f"| {f} | yes | {s1['steps']} | {s1.get('solid_substeps_max', '-')} | {s1['wall_s']:.1f} | {1000*x1[-1]:.2f} | | |")
    print(f"| {f} | no | {s0['steps']} | 1 | {s0['wall_s']:.1f} | {1000*x0[-1]:.2f} | {dxm:.3f} / {dym:.3f} | **{s0['wall_s']/s1['wall_s']:.1f}x** |")
PY
