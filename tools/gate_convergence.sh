#!/usr/bin/env bash
# Elastic gate against the experiment at several resolutions across the gate (not a test): both
# fluids, both solid formulations, uniform dx = 5 mm / n.  Writes out/gate_convergence/table.md.
#   tools/gate_convergence.sh [N ...]        (default 3 4 5 6; NP ranks, default 2; SPHFSI binary;
#                                             FORMS="updated total", FLUIDS="isph wcsph", GATE_OUT)
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1} OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:---oversubscribe} -n ${NP:-2}"
OUT=${GATE_OUT:-out/gate_convergence}; mkdir -p $OUT
NS=${*:-3 4 5 6}
{
  echo "| fluid | solid | across | dx (mm) | particles | steps | tip_dx RMS (mm) | tip_dy RMS (mm) | peak tip_dx (mm) | wall s |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for fluid in ${FLUIDS:-isph wcsph}; do
    for form in ${FORMS:-updated total}; do
      for n in $NS; do
        dx=$(python3 -c "print(f'{0.005/$n:.7f}')")
        d=$OUT/${fluid}_${form}_n$n
        case=cases/elastic_gate.opts; [ $fluid = wcsph ] && case=cases/elastic_gate_wcsph.opts
        $MPI ${SPHFSI:-bin/sphfsi} -overwrite -options_file $case -dx $dx -dx_coarse $dx -solid_formulation $form $([ $form = total ] && echo -solid_cfl 0.25) -output_interval 0 -progress_every 0 -output_dir $d > $d.log 2>&1 || { echo "| $fluid | $form | $n | failed: $d.log |"; continue; }
        python3 -c "
import json, csv; s = json.load(open('$d/summary.json')); e = s['errors']
peak = max(float(r['tip_dx']) for r in csv.DictReader(open('$d/probes.csv')))
print(f\"| $fluid | $form | $n | {1000*$dx:.3g} | {s['particles']} | {s['steps']} | {1000*e['tip_dx_err_rms']:.2f} | {1000*e['tip_dy_err_rms']:.2f} | {1000*peak:.1f} | {s['wall_s']:.0f} |\")"
      done
    done
  done
} | tee $OUT/table.md
