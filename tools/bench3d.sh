#!/usr/bin/env bash
# Three-dimensional benchmarks of issue 26 (not a test; part "3d" of `make bench`, or alone).
#   1. throughput on SPHERIC Test 2 (cases/spheric_test2.opts) at dx = 0.02 m (180 000 particles):
#      WCSPH to t = 0.05 s and ISPH 10 steps, on 1 and 2 ranks, alternately and twice (the faster of
#      each is reported: the machine's speed drifts)
#   2. CG + BoomerAMG iterations per 3D pressure equation against its size: the same case, ISPH, 3
#      steps from a zero initial guess (-ppe_ksp_initial_guess_nonzero 0, so the count is the
#      solver's, not the warm start's) at dx = 0.04 .. 0.009 m (36 000 .. 1.5 M particles), 2 ranks;
#      memory per particle (maximum resident set over ranks, summed) at each size
#   3. partition statistics of the 3D cell graph (bin/partition_model) at dx = 0.01 m (1.05 M) and
#      0.0046 m (8.7 M) for 2..1024 ranks (tools/scaling_model.py turns them into modelled times
#      with the costs of part 4: out/bench/scaling_model.md, run by tools/bench.sh)
#   4. 2-rank efficiency at ~1 M particles: the same case at dx = 0.01 m (1.05 M), WCSPH 10 steps and
#      ISPH 3 steps on 1 and 2 ranks: particle-steps/s on 2 over twice that on 1
# Writes out/bench/bench3d.md.  Environment as tools/bench.sh (MPIEXEC, MPIEXEC_FLAGS, BINDIR,
# BENCH_TIMEOUT); BENCH3D_SIZES (the dx list of part 2), BENCH3D_ONLY (subset of: throughput cg partition efficiency).
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-}"
BIN=${BINDIR:-bin}
OUT=out/bench; mkdir -p $OUT
TMO=${BENCH_TIMEOUT:-1800}
ONLY=${BENCH3D_ONLY:-throughput cg partition efficiency}
SIZES=${BENCH3D_SIZES:-0.04 0.03 0.02 0.015 0.012 0.01 0.009}
has() { [[ " $ONLY " == *" $1 "* ]]; }
S2="-options_file cases/spheric_test2.opts -output_interval 0" # probes every 2 ms of physical time, as the case file
FAILS=""
run() { # NAME NP [sphfsi options...]
  local name=$1 np=$2; shift 2
  local dir=$OUT/$name t0=$SECONDS
  rm -rf $dir; mkdir -p $dir
  cut -d' ' -f1-3 /proc/loadavg > $dir/load_before
  timeout $TMO $MPI -n $np $BIN/sphfsi "$@" -overwrite -progress_every 0 -output_dir $dir -log_view :$dir/log_view.txt > $OUT/$name.log 2>&1
  local rc=$?
  cut -d' ' -f1-3 /proc/loadavg > $dir/load_after
  echo "$name: $np rank(s), exit $rc, $((SECONDS - t0)) s, load $(cat $dir/load_before) -> $(cat $dir/load_after)" | tee -a $OUT/runs3d.txt >&2
  [ $rc -eq 0 ] || FAILS="$FAILS $name"
}
: > $OUT/runs3d.txt
if has throughput; then
  for rep in "" _r2; do
    run s2_wcsph_np1$rep 1 $S2 -dx 0.02 -t_end 0.05
    run s2_wcsph_np2$rep 2 $S2 -dx 0.02 -t_end 0.05
    run s2_isph_np1$rep 1 $S2 -fluid isph -dx 0.02 -max_steps 10
    run s2_isph_np2$rep 2 $S2 -fluid isph -dx 0.02 -max_steps 10
  done
fi
if has cg; then
  for dx in $SIZES; do run s2_cg_$dx 2 $S2 -fluid isph -dx $dx -max_steps 3 -ppe_ksp_initial_guess_nonzero 0; done
fi
if has efficiency; then
  for np_ in 1 2; do
    run s2_eff_wcsph_np$np_ $np_ $S2 -dx 0.01 -max_steps 10
    run s2_eff_isph_np$np_ $np_ $S2 -fluid isph -dx 0.01 -max_steps 3
  done
fi
if has partition; then
  timeout $TMO $BIN/partition_model $S2 -dx 0.01 -nparts_max 1024 > $OUT/partition_spheric_test2.csv 2> $OUT/partition_spheric_test2.log || FAILS="$FAILS partition"
  # ~8.5k particles per rank at 1024 ranks, the issue's scale for the scaling model (1.6 GB, ~20 s)
  timeout $TMO $BIN/partition_model $S2 -dx 0.0046 -nparts_max 1024 > $OUT/partition_spheric_test2_9M.csv 2> $OUT/partition_spheric_test2_9M.log || FAILS="$FAILS partition_9M"
fi
python3 - $OUT "$SIZES" <<'PY' || FAILS="$FAILS report"
import json, os, sys
o, sizes = sys.argv[1], sys.argv[2].split()
def summ(n):
    p = f"{o}/{n}/summary.json"
    return json.load(open(p)) if os.path.exists(p) else None
L = ["# 3D benchmarks (tools/bench3d.sh)", ""]
rows = []
for f in ("wcsph", "isph"):
    for np_ in (1, 2):
        runs = [s for s in (summ(f"s2_{f}_np{np_}"), summ(f"s2_{f}_np{np_}_r2")) if s]
        if runs:
            b = max(runs, key=lambda s: s["particle_steps_per_s"])
            rows.append(f"| {f} | {np_} | {b['particles']} | {b['steps']} | {b['wall_s']:.1f} | {b['particle_steps_per_s']/1e6:.2f} | " + " / ".join(f"{s['particle_steps_per_s']/1e6:.2f}" for s in runs) + " |")
if rows:
    L += ["SPHERIC Test 2 at dx = 0.02 m: particle-steps/s (the faster of two runs; both given).", "",
          "| fluid | ranks | particles | steps | wall s | 10^6 particle-steps/s | runs |", "|---|---|---|---|---|---|---|"] + rows + [""]
rows = []
for dx in sizes:
    s = summ(f"s2_cg_{dx}")
    if s:
        rows.append(f"| {dx} | {s['particles']} | {s['ksp_its_mean']:.1f} | {s['ksp_its_max']} | {s['peak_resident_bytes_per_particle']:.0f} | {s['bytes_per_particle']} |")
if rows:
    L += ["ISPH pressure equation, 3 steps from a zero initial guess, 2 ranks: CG iterations per solve, memory.", "",
          "| dx (m) | particles | CG its mean | max | peak resident B/particle | field B/particle |", "|---|---|---|---|---|---|"] + rows + [""]
rows = []
for f in ("wcsph", "isph"):
    s1, s2 = summ(f"s2_eff_{f}_np1"), summ(f"s2_eff_{f}_np2")
    if s1 and s2:
        e = s2["particle_steps_per_s"] / (2 * s1["particle_steps_per_s"])
        rows.append(f"| {f} | {s1['particles']} | {s1['steps']} | {s1['particle_steps_per_s']/1e6:.3f} | {s2['particle_steps_per_s']/1e6:.3f} | {100*e:.0f} % |")
if rows:
    L += ["2-rank efficiency at dx = 0.01 m (time loop only): particle-steps/s on 2 ranks over twice that on 1.", "",
          "| fluid | particles | steps | 10^6 particle-steps/s, 1 rank | 2 ranks | efficiency |", "|---|---|---|---|---|---|"] + rows + [""]
if os.path.exists(f"{o}/partition_spheric_test2.csv"):
    L += ["Partition of the 3D cell graph at dx = 0.01 m: out/bench/partition_spheric_test2.csv.", ""]
open(f"{o}/bench3d.md", "w").write("\n".join(L))
print("\n".join(L))
PY
[ -z "$FAILS" ] || { echo "bench3d: failed:$FAILS (logs in $OUT)" >&2; exit 1; }
