#!/usr/bin/env bash
# Performance benchmark of issue 7 (not a test; `make bench`, ~10-20 min on 2 cores).
#   1. dam break, dx = a/100 (25 187 particles): WCSPH 0.01 s on 1 and 2 ranks, ISPH to the case's
#      t_end (0.3 s, the whole run) on 2 ranks (throughput)
#   2. the same dam break to t = 0.5 s on 2 ranks with ISPH and with WCSPH (wall time to 0.5 s) in a
#      tank 1 m high instead of 3 column heights (0.34 m): the run-up jet at the far wall of the
#      ISPH run leaves the default box at t = 0.35-0.40 s (and a 0.5 m one at 0.38 s)
#   3. oscillating plate (cases/oscillating_plate.opts), 0.2 s on 2 ranks
#   4. strong scaling at dx = a/440 (410 023 particles): WCSPH 100 steps and ISPH 20 steps on 1 and
#      2 ranks, alternately and twice (the efficiency from the faster run of each: the machine's speed
#      drifts by 10-20 % within minutes; the WCSPH runs of 1. likewise); memory from -memory_view (maximum resident set, summed over
#      ranks) and an empty-problem baseline
#   5. partition statistics of the dam break (a/700, 1.02 M particles) and the elastic gate
#      (dx 0.12 mm everywhere, 1.04 M) for 2..1024 ranks (bin/partition_model) and the scaling model
#      (tools/scaling_model.py) from them and the costs measured in 4.
# particle-steps/s = particles x steps / wall seconds of the time loop (summary.json).  Every run
# keeps its -log_view in out/bench/NAME/log_view.txt.  The load average is recorded next to each
# run: on a shared machine the wall times are only as good as the load allowed.
# Writes out/bench/bench.md (goals, measured, ratio to the anchors), out/bench/scaling_model.md/png.
# Environment: MPIEXEC, MPIEXEC_FLAGS, BINDIR (bin), BENCH_TIMEOUT (s per run, 1800),
#   BENCH_QUICK=1 (smaller sizes and times: a check of the script, not numbers to quote),
#   BENCH_ONLY (space-separated subset of: throughput t05 plate scaling model 3d targets).
#   6. (3d) the three-dimensional benchmarks of tools/bench3d.sh: SPHERIC Test 2 throughput, CG
#      iterations and memory of the 3D pressure equation up to 1.1 M particles, the 3D cell graph's
#      partition; out/bench/bench3d.md
#   7. (targets) issue 57's three throughput rows, alternating runs with their median and range
#      (tools/bench_targets.sh; BENCH_BASE=other/sphfsi pairs each run with another build's)
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-}"
BIN=${BINDIR:-bin}
OUT=out/bench; mkdir -p $OUT
TMO=${BENCH_TIMEOUT:-1800}
ONLY=${BENCH_ONLY:-throughput t05 plate scaling model 3d targets}
A=0.05715
div() { python3 -c "print(f'{$A/$1:.7g}')"; }
if [ -n "${BENCH_QUICK:-}" ]; then
  D25=$(div 40) T03=0.03 T05=0.05 TPL=0.02 DSC=$(div 100) WST=20 IST=5 DDB=$(div 200) DGATE=5e-4 NPMAX=64
else
  D25=$(div 100) T03=0.3 T05=0.5 TPL=0.2 DSC=$(div 440) WST=100 IST=20 DDB=$(div 700) DGATE=1.2e-4 NPMAX=1024
fi
[ -x $BIN/sphfsi ] && [ -x $BIN/partition_model ] && [ -x $BIN/roofline ] || { echo "run make bench (needs $BIN/sphfsi, $BIN/partition_model and $BIN/roofline)" >&2; exit 1; }
has() { [[ " $ONLY " == *" $1 "* ]]; }
T0=$SECONDS

# run NAME NP [sphfsi options...]: one run with -log_view and -memory_view; load average recorded
run() {
  local name=$1 np=$2; shift 2
  local dir=$OUT/$name
  rm -rf $dir; mkdir -p $dir
  cut -d' ' -f1-3 /proc/loadavg > $dir/load_before
  local t0=$SECONDS
  timeout $TMO $MPI -n $np $BIN/sphfsi "$@" -overwrite -progress_every 0 -output_dir $dir -log_view :$dir/log_view.txt -memory_view > $OUT/$name.log 2>&1
  local rc=$?
  cut -d' ' -f1-3 /proc/loadavg > $dir/load_after
  echo "$name: $np rank(s), exit $rc, $((SECONDS - t0)) s, load $(cat $dir/load_before) -> $(cat $dir/load_after)" | tee -a $OUT/runs.txt >&2
  [ $rc -eq 0 ] || { echo $rc > $dir/FAILED; FAILS="$FAILS $name"; }
}
FAILS=""
: > $OUT/runs.txt
DB="-options_file cases/dam_break.opts -output_interval 0"
if has throughput; then # the machine's limits first (tools/roofline.c; docs/performance.md), 1 and 2 ranks
  { $MPI -n 1 $BIN/roofline; $MPI -n 2 $BIN/roofline; } 2>&1 | grep '^roofline:' | grep -v checksum > $OUT/roofline.txt || FAILS="$FAILS roofline"

  for rep in "" _r2; do # twice, alternating: the report takes the faster of each (the machine's speed drifts)
    run wcsph_25k_np1$rep 1 $DB -dx $D25 -t_end 0.01 -probe_interval 0.001
    run wcsph_25k_np2$rep 2 $DB -dx $D25 -t_end 0.01 -probe_interval 0.001
  done
  run isph_25k_np2 2 $DB -fluid isph -dx $D25 -t_end $T03
fi
if has t05; then
  run isph_t05_np2 2 $DB -fluid isph -dx $D25 -t_end $T05 -tank_height 1.0
  run wcsph_t05_np2 2 $DB -fluid wcsph -dx $D25 -t_end $T05 -tank_height 1.0
fi
if has plate; then
  run plate_np2 2 -options_file cases/oscillating_plate.opts -t_end $TPL -output_interval 0
fi
if has scaling; then
  for rep in "" _r2; do # 1 and 2 ranks alternately, twice: the efficiency from the faster of each
    run wcsph_400k_np1$rep 1 $DB -dx $DSC -max_steps $WST -probe_interval 0
    run wcsph_400k_np2$rep 2 $DB -dx $DSC -max_steps $WST -probe_interval 0
  done
  for rep in "" _r2; do
    run isph_400k_np1$rep 1 $DB -fluid isph -dx $DSC -max_steps $IST -probe_interval 0
    run isph_400k_np2$rep 2 $DB -fluid isph -dx $DSC -max_steps $IST -probe_interval 0
  done
  # memory of an (almost) empty ISPH problem: MPI, PETSc, hypre and the binary
  run isph_empty_np1 1 $DB -fluid isph -dx $(div 4) -max_steps 2 -probe_interval 0
  run isph_empty_np2 2 $DB -fluid isph -dx $(div 4) -max_steps 2 -probe_interval 0
fi
if has model; then
  # Cost of a solid particle per fluid step in work units (a wall particle = 1): 4 + n_sub c_solid / c_work,
  # with c_solid from the plate (rank-seconds per solid particle-step), c_work from the 400k WCSPH run,
  # n_sub = 8 solid sub-steps per fluid step of the gate.  The gate is partitioned as the code does
  # (solids a second METIS constraint, -decomp_split_solids) and with the solids weighted by that cost.
  SC=$(python3 - $OUT <<'PY' 2>/dev/null || echo 36
import json, re, sys
o = sys.argv[1]
p = json.load(open(f"{o}/plate_np2/summary.json")); w = json.load(open(f"{o}/wcsph_400k_np1/summary.json"))
line = next(l for l in open(f"{o}/wcsph_400k_np1.log") if l.startswith("Particles:"))
n = {b: int(a) for b, a in re.findall(r"(fluid|wall|dummy|solid|clamp) (\d+)", line)}
work = 4 * n.get("fluid", 0) + n.get("wall", 0) + n.get("dummy", 0)
c_work = w["wall_s"] / w["steps"] / work; c_solid = 2.0 / p["particle_steps_per_s"]
print(f"{4 + 8 * c_solid / c_work:.0f}")
PY
)
  for s in "dam_break $DDB dam_break" "elastic_gate $DGATE elastic_gate -dx_coarse $DGATE -solid_cost $SC -split_solids" "elastic_gate $DGATE elastic_gate_solidw -dx_coarse $DGATE -solid_cost $SC -solid_weight $SC"; do
    set -- $s
    echo "partition_model: $1, dx $2 ${*:4}" >&2
    timeout $TMO $BIN/partition_model -options_file cases/$1.opts -dx $2 -nparts_max $NPMAX "${@:4}" > $OUT/partition_$3.csv 2> $OUT/partition_$3.log || { echo "partition_model $3 failed: $OUT/partition_$3.log" >&2; FAILS="$FAILS partition_$3"; }
  done
  echo "$SC" > $OUT/solid_cost.txt
fi
if has 3d; then
  BINDIR=$BIN bash tools/bench3d.sh || FAILS="$FAILS 3d"
fi
if has targets; then
  BINDIR=$BIN bash tools/bench_targets.sh || FAILS="$FAILS targets"
fi
echo "bench: $((SECONDS - T0)) s" | tee -a $OUT/runs.txt >&2
python3 tools/scaling_model.py $OUT || { echo "scaling model failed" >&2; FAILS="$FAILS scaling_model"; }
python3 tools/bench_report.py $OUT $((SECONDS - T0)) || FAILS="$FAILS report"
! has targets || [ ! -f $OUT/targets.md ] || { echo; cat $OUT/targets.md; } >> $OUT/bench.md
cat $OUT/bench.md
# a part that failed is named at the end and makes `make bench` fail (its numbers are missing)
[ -z "$FAILS" ] || { echo "bench: failed:$FAILS (logs in $OUT)" >&2; exit 1; }
