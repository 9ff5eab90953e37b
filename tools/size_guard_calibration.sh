#!/usr/bin/env bash
# The size guard's estimate against the measured peak resident memory (docs/cluster.md, "Size
# guard"): runs of 5 steps (no snapshots) on NP ranks (default 2), each with -size_guard_count 1
# -info (the estimate for the counted particles), and a markdown table of summary.json's
# peak_resident_bytes (summed over the ranks) against the estimate times the ranks.
#   tools/size_guard_calibration.sh [OUTDIR] [quick]    (quick: the three smaller sizes of each; the
#   whole table takes ~30 min on 2 cores, most of it the 3D ISPH runs); BIN: the directory of sphfsi (bin)
OUT=${1:-out/size_guard_calibration}; QUICK=${2:-}
cd "$(dirname "$0")/.." || exit 2
mkdir -p "$OUT"
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS-$(${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -q "Open MPI" && echo --oversubscribe)} -n ${NP:-2}"
DB=cases/dam_break.opts; HY="cases/hydrostatic.opts -dim 3"
runs=(
  "dam break 2D, WCSPH|$DB -dx 4e-4" "dam break 2D, WCSPH|$DB -dx 2e-4" "dam break 2D, WCSPH|$DB -dx 8e-5"
  "dam break 2D, ISPH|$DB -fluid isph -dx 4e-4" "dam break 2D, ISPH|$DB -fluid isph -dx 2e-4" "dam break 2D, ISPH|$DB -fluid isph -dx 8e-5"
  "hydrostatic 3D, WCSPH|$HY -dx 0.002" "hydrostatic 3D, WCSPH|$HY -dx 0.00135" "hydrostatic 3D, WCSPH|$HY -dx 0.00105"
  "hydrostatic 3D, ISPH|$HY -fluid isph -dx 0.002" "hydrostatic 3D, ISPH|$HY -fluid isph -dx 0.00135" "hydrostatic 3D, ISPH|$HY -fluid isph -dx 0.00105"
  "SPHERIC Test 2 3D, WCSPH|cases/spheric_test2.opts -dx 0.012" "SPHERIC Test 2 3D, ISPH|cases/spheric_test2.opts -fluid isph -dx 0.012"
  "oscillating plate 2D|cases/oscillating_plate.opts -plate_ny 200" "cantilever 3D|cases/boxes/cantilever_3d.opts -dx 0.0009"
  "elastic gate 2D, ISPH|cases/elastic_gate.opts -dx 0.00025 -dx_coarse 0.0005" "elastic gate 2D, WCSPH|cases/elastic_gate_wcsph.opts -dx 0.00025 -dx_coarse 0.0005"
  "Taylor-Green 3D, ISPH, 2h = 4 dx|cases/taylor_green.opts -dim 3 -dx 0.02"
)
[ -n "$QUICK" ] && runs=("${runs[0]}" "${runs[1]}" "${runs[3]}" "${runs[4]}" "${runs[6]}" "${runs[7]}" "${runs[9]}")
echo "| case | ranks | particles | measured B/particle | estimated B/particle | estimate / measured |"
echo "|---|---|---|---|---|---|"
k=0
for r in "${runs[@]}"; do
  k=$((k + 1)); name=${r%%|*}; args=${r#*|}; d=$OUT/run$k
  $MPI "${BIN:-bin}"/sphfsi -options_file $args -max_steps 5 -output_interval 0 -progress_every 0 -size_guard_count 1 -info -output_dir "$d" > "$d.log" 2>&1 || { echo "| $name ($args) | failed: $d.log | | | | |"; continue; }
  python3 - "$d/summary.json" "$d.log" "$name" <<'PY'
import json, re, sys
s = json.load(open(sys.argv[1])); log = open(sys.argv[2]).read()
est = float(re.search(r"Size guard: the dry count found \d+ particles \(\d+ solid\): estimate (\S+) B", log).group(1)) * s["ranks"]
n, m = s["particles"], s["peak_resident_bytes"]
print(f"| {sys.argv[3]} | {s['ranks']} | {n} | {m / n:.0f} | {est / n:.0f} | {est / m:.2f} |")
PY
done
