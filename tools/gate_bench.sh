#!/usr/bin/env bash
# Elastic gate speed benchmark (issue 5; not a test): the whole case file (cases/elastic_gate.opts:
# ISPH + solid, 1 / 2 mm particles, 0.4 s; or the file given) on NP ranks (default 2), with
# -log_view.  Reports wall time, steps, solid sub-steps, the stage shares, the tip errors against the
# experiment and the load average before and after (the machine may be shared: a wall time is only
# as good as the load allowed).  Target of issue 5: under 3 minutes on 2 ranks.
#   tools/gate_bench.sh [CASE_FILE] [extra sphfsi options]      -> out/gate_bench/<case>/report.md
cd "$(dirname "$0")/.."
CASE=${1:-cases/elastic_gate.opts}; shift
NAME=$(basename "$CASE" .opts)
OUT=out/gate_bench/$NAME; rm -rf $OUT; mkdir -p $OUT
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-} -n ${NP:-2}"
load() { cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo "?"; }
L0=$(load)
$MPI bin/sphfsi -overwrite -options_file "$CASE" -output_interval 0 -progress_every 30 -output_dir $OUT -log_view :$OUT/log_view.txt "$@" > $OUT/run.log 2>&1
rc=$?
L1=$(load)
python3 - "$OUT" "$rc" "$L0" "$L1" "$CASE $*" <<'PY' | tee $OUT/report.md
import json, re, sys
out, rc, l0, l1, args = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
print(f"Elastic gate benchmark: `{args}`, exit status {rc}, load average {l0} before, {l1} after\n")
try:
    s = json.load(open(f"{out}/summary.json"))
except OSError:
    sys.exit(f"no summary.json: see {out}/run.log")
e = s["errors"]
print(f"| particles | steps | solid sub-steps max | wall s | under 3 min | tip_dx RMS / max (mm) | tip_dy RMS / max (mm) |")
print("|---|---|---|---|---|---|---|")
print(f"| {s['particles']} | {s['steps']} | {s.get('solid_substeps_max', '-')} | {s['wall_s']:.1f} | {'yes' if s['wall_s'] < 180 else 'no'} | "
      f"{1000*e.get('tip_dx_err_rms', float('nan')):.1f} / {1000*e.get('tip_dx_err_max', float('nan')):.1f} | {1000*e.get('tip_dy_err_rms', float('nan')):.1f} / {1000*e.get('tip_dy_err_max', float('nan')):.1f} |")
stages = {}
for line in open(f"{out}/log_view.txt"):
    m = re.match(r"\s*\d+:\s+([A-Za-z+ ]+?):\s+([0-9.e+-]+)\s+([0-9.]+)%", line)
    if m: stages[m.group(1)] = float(m.group(3))
if stages:
    print("\n-log_view stage shares (%): " + ", ".join(f"{k} {v:.1f}" for k, v in stages.items()))
PY
exit $rc
