#!/usr/bin/env bash
# Oscillating plate study (not a test): period and amplitude against the thin-plate analytic values
# at several resolutions (particles across the thickness), for the case's artificial stress
# (e = 0.1) and the paper's (e = 0.3).  Writes out/plate_convergence/table.md.
#   tools/plate_convergence.sh [NY ...]      (default 6 10 20; NP ranks, default 2)
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-} -n ${NP:-2}"
OUT=out/plate_convergence; mkdir -p $OUT
NYS=${*:-6 10 20}
{
  echo "| particles across | e | particles | steps | T c0/L (err) | A/L (err) | energy drift max | last/first swing | wall s |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for e in 0.1 0.3; do
    for ny in $NYS; do
      d=$OUT/ny${ny}_e$e
      $MPI bin/sphfsi -options_file cases/oscillating_plate.opts -plate_ny $ny -solid_art_stress $e -output_interval 0 -progress_every 0 -output_dir $d > $d.log 2>&1 || { echo "run failed: $d.log" >&2; continue; }
      python3 -c "
import json,sys; s=json.load(open('$d/summary.json')); e=s['errors']
print(f\"| $ny | $e | {s['particles']} | {s['steps']} | {e['period_c0_over_L']:.2f} ({100*e['period_rel_err']:+.1f} %) | {e['amplitude_over_L']:.4f} ({100*e['amplitude_rel_err']:+.1f} %) | {100*e['energy_rel_drift_max']:.1f} % | {e['amplitude_last_over_first']:.3f} | {s['wall_s']:.1f} |\")"
    done
  done
  echo
  echo "analytic: T c0/L = 72.44, A/L = 0.1153 (thin plate, plane strain); published SPH (paper Table 1): 80.95-82, 0.124-0.125"
} | tee $OUT/table.md
