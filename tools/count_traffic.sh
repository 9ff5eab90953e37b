#!/usr/bin/env bash
# The scaling model's inputs, counted (issue 46, items 2 and 3): runs on 1 .. 64 ranks, oversubscribed
# on this machine, with every MPI call counted (tools/count_mpi.c, an LD_PRELOAD shim: PETSc's, the
# code's own and hypre's messages, which -log_view does not see) and the partition recorded after
# every rebuild (-decomp_log_stats: ghosts, owned particles, work, neighbour ranks; ISPH's PPE rows).
# Oversubscribed runs are counted, never timed: their wall times are not performance figures.
#   strong  whole flows, with rebalancing, each P of COUNT_NPS (default 1 2 4 8 16 32 64; 2 is the
#           rank count the model's message and reduction counts come from):
#           dam_wcsph  2D dam break, WCSPH, dx = a/40 (5 282 particles), to t = 0.3 s (the case's end)
#           dam_isph   the same with ISPH (CG + BoomerAMG: iterations per solve at every P)
#           s2_wcsph   3D SPHERIC Test 2, WCSPH, dx = 0.04 m (35 901 particles), to t = COUNT_S2_T
#                      (default 0.6 s: the collapse, the front's run to the box and its impact; the
#                      whole 6 s would take ~14 000 steps)
#           s2_isph    3D SPHERIC Test 2, ISPH, dx = 0.025 m (~100k particles), 5 steps, at 1, 8, 64 ranks
#                      only: the CG + BoomerAMG iterations of one 3D problem against P
#           dam_isph100  dam_isph's first 100 steps at 1, 8, 64 ranks (its whole flow on 64 oversubscribed
#                      ranks did not finish in 35 min here; not in the default COUNT_CASES)
#   levels  BoomerAMG's levels (-ppe_pc_hypre_boomeramg_print_statistics), 1 step of dam_isph at 1, 8, 64
#   weak    3D SPHERIC Test 2 at ~10.5k particles per rank (dx from N(dx) = 0.6557 dx^-3 + 39.2 dx^-2,
#           fitted to 180 000 at 0.02 m and 1 047 844 at 0.01 m), P = 1 2 4 8 16 32 64 (COUNT_WEAK_NPS;
#           P = 1 at dx = 0.053 m, 18k particles: the box must be 3 particles across):
#           WCSPH 20 steps (one rebuild and balance check in them, as every 20 steps of a run) and ISPH
#           4 steps (two rebuilds and a PPE each); the counts per step are the point, not the flow
#   partition  bin/partition_model at each run's dx: what tools/scaling_model.py assumes for that P
# Every run is made twice: to its end, and with -max_steps 0 (the set-up alone); the counts per step
# are the difference over the steps.  A run whose summary.json exists is not run again (resume).
# Output: OUTDIR (default out/count)/NAME_npP/{run,mpi,setup/{run,mpi}}, partition_*.csv; then
# tools/count_report.py OUTDIR writes OUTDIR/count.md and the plot.
# Environment: COUNT_ONLY (subset of: partition strong levels weak), COUNT_NPS, COUNT_WEAK_NPS,
# COUNT_CASES (subset of the strong runs), COUNT_WEAK_FLUIDS (wcsph isph), MPIEXEC, BINDIR,
# COUNT_TIMEOUT (s per run, 3600).
cd "$(dirname "$0")/.." || exit 2
OUT=${1:-out/count}
BIN=${BINDIR:-bin}
NPS=${COUNT_NPS:-1 2 4 8 16 32 64}
WNPS=${COUNT_WEAK_NPS:-1 2 4 8 16 32 64}
ONLY=${COUNT_ONLY:-partition strong levels weak}
CASES=${COUNT_CASES:-dam_wcsph dam_isph s2_wcsph s2_isph}
S2T=${COUNT_S2_T:-0.6}
TMO=${COUNT_TIMEOUT:-3600}
has() { [[ " $1 " == *" $2 "* ]]; }
mkdir -p "$OUT" build
[ -x $BIN/sphfsi ] && [ -x $BIN/partition_model ] || { echo "make all bin/partition_model first" >&2; exit 2; }
SHIM=$PWD/build/libcount_mpi.so
mpicc -shared -fPIC -O2 tools/count_mpi.c -o "$SHIM" -ldl || exit 2
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1} OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
# more ranks than cores: ranks yield the core while they wait, none is bound to one
MPI="${MPIEXEC:-mpiexec} --oversubscribe --bind-to none --mca mpi_yield_when_idle 1"
DAM="-options_file cases/dam_break.opts -dx 0.00142875"
S2="-options_file cases/spheric_test2.opts"
FAILS=""

once() { # DIR NP [sphfsi options...]: one counted run into DIR/run, DIR/mpi
  local dir=$1 np=$2; shift 2
  [ -f $dir/run/summary.json ] && return 0
  rm -rf $dir/run $dir/mpi; mkdir -p $dir/mpi
  local t0=$SECONDS
  timeout $TMO $MPI -x LD_PRELOAD=$SHIM -x COUNT_MPI_DIR=$PWD/$dir/mpi -n $np $BIN/sphfsi "$@" -output_interval 0 -progress_every 0 \
    -decomp_log_stats -overwrite -output_dir $dir/run > $dir/log.txt 2>&1
  local rc=$?
  echo "$dir: $np rank(s), exit $rc, $((SECONDS - t0)) s oversubscribed wall (not a timing)" | tee -a $OUT/runs.txt >&2
  [ $rc -eq 0 ] || FAILS="$FAILS $dir"
}
run() { # NAME NP [options]: the run and its set-up alone
  local name=$1 np=$2; shift 2
  once $OUT/${name}_np$np $np "$@"
  once $OUT/${name}_np$np/setup $np "$@" -max_steps 0
}
opts_of() { # the options of a strong case
  case $1 in
    dam_wcsph) echo "$DAM -fluid wcsph" ;;
    dam_isph) echo "$DAM -fluid isph" ;;
    dam_isph100) echo "$DAM -fluid isph -max_steps 100" ;;
    s2_wcsph) echo "$S2 -dx 0.04 -fluid wcsph -t_end $S2T" ;;
    s2_isph) echo "$S2 -dx 0.025 -fluid isph -max_steps 5" ;;
  esac
}
weak_dx() { # NP: dx for ~10.5k particles per rank
  python3 -c "
from math import isclose
N = 10500 * $1; f = lambda d: 0.6557 / d**3 + 39.2 / d**2
lo, hi = 1e-3, 0.2
for _ in range(60):
    m = 0.5 * (lo + hi); lo, hi = (m, hi) if f(m) > N else (lo, m)
print(f'{min(lo, 0.053):.5f}')"
}

if has "$ONLY" partition; then # the model's partition statistics at the runs' sizes
  for spec in "dam_break $DAM" "spheric_test2_0.04 $S2 -dx 0.04" "spheric_test2_0.025 $S2 -dx 0.025"; do
    set -- $spec; name=$1; shift
    [ -s $OUT/partition_$name.csv ] || $BIN/partition_model "$@" -nparts_max 64 > $OUT/partition_$name.csv 2> $OUT/partition_$name.log || FAILS="$FAILS partition_$name"
  done
  for np in $WNPS; do
    [ $np -gt 1 ] || continue
    dx=$(weak_dx $np)
    [ -s $OUT/partition_weak_np$np.csv ] || $BIN/partition_model $S2 -dx $dx -nparts_max $np > $OUT/partition_weak_np$np.csv 2> $OUT/partition_weak_np$np.log || FAILS="$FAILS partition_weak_np$np"
  done
fi
if has "$ONLY" strong; then
  for c in $CASES; do
    for np in $NPS; do
      [ $c = s2_isph ] || [ $c = dam_isph100 ] && ! has "1 8 64" $np && continue # ISPH's iterations at a fixed problem: 1, 8, 64 ranks
      run $c $np $(opts_of $c)
    done
  done
fi
if has "$ONLY" levels; then
  for np in 1 8 64; do
    d=$OUT/levels_np$np; mkdir -p $d
    [ -s $d/levels.txt ] && continue
    $MPI -n $np $BIN/sphfsi $DAM -fluid isph -max_steps 1 -output_interval 0 -progress_every 0 -overwrite -output_dir $d/run \
      -ppe_pc_hypre_boomeramg_print_statistics 1 > $d/log.txt 2>&1 || FAILS="$FAILS levels_np$np"
    awk '/Num levels/ {n++} n==1' $d/log.txt | sed -En '/Num levels/p;/^ *[0-9]+ +[0-9]+ +[0-9]+ +[0-9.]+ /p' | head -40 > $d/levels.txt
  done
fi
if has "$ONLY" weak; then
  for np in $WNPS; do
    dx=$(weak_dx $np)
    has "${COUNT_WEAK_FLUIDS:-wcsph isph}" wcsph && run weak_wcsph $np $S2 -dx $dx -fluid wcsph -max_steps 20
    has "${COUNT_WEAK_FLUIDS:-wcsph isph}" isph && run weak_isph $np $S2 -dx $dx -fluid isph -max_steps 4
  done
fi
[ -z "$FAILS" ] || { echo "failed:$FAILS" >&2; exit 1; }
