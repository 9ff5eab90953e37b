#!/usr/bin/env bash
# The throughput rows of issue 57 (part "targets" of `make bench`, or alone; ~5 min on 2 cores):
#   3D WCSPH  SPHERIC Test 2 at dx 0.02 m (180k particles), the first 200 steps    target 3.5 x 10^6
#   2D WCSPH  dam break of a 1 m wide, 2 m high column at dx 0.01 m, to t = 0.1 s  target 10 x 10^6
#   2D ISPH   the same dam break to t = 0.1 s                                       target 1.5 x 10^6
# particle-steps/s of the time loop on 2 ranks (summary.json).  The machine is shared and its speed
# drifts within minutes, so each row runs BENCH_REPS times (3), the rows alternating, and the report
# gives the median and the range.  With BENCH_BASE=path/to/other/sphfsi every run is paired with the
# same run of that binary (A, B, then B, A, ...: a change against the previous commit's build; the order
# swaps each run, so that neither build is always first; a build whose hot loops were the same
# machine code as the base's came out at 0.85-1.03x of it: a ratio within ~15 % of 1 is the host's), and the
# report gives both medians and their ratio.  Writes out/bench/targets.md.
# Environment as tools/bench.sh (MPIEXEC, MPIEXEC_FLAGS, BINDIR, BENCH_TIMEOUT).
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-}"
BIN=${BINDIR:-bin}
OUT=out/bench/targets; rm -rf $OUT; mkdir -p $OUT
TMO=${BENCH_TIMEOUT:-1800}
REPS=${BENCH_REPS:-3}
BASE=${BENCH_BASE:-}
[ -z "$BASE" ] || [ -x "$BASE" ] || { echo "BENCH_BASE=$BASE is not an executable" >&2; exit 1; }
COL="-options_file cases/dam_break.opts -column_width 1 -column_height 2 -dx 0.01 -t_end 0.1 -output_interval 0 -probe_interval 0.01"
declare -A ROW=(
  [wcsph3d]="-options_file cases/spheric_test2.opts -dx 0.02 -max_steps 200 -output_interval 0"
  [wcsph2d]="$COL -fluid wcsph"
  [isph2d]="$COL -fluid isph"
)
FAILS=""
for rep in $(seq 1 $REPS); do
  for row in wcsph3d wcsph2d isph2d; do
    order="A ${BASE:+B}"; [ -n "$BASE" ] && [ $((rep % 2)) -eq 0 ] && order="B A" # the pair's order swaps each run: the host drifts within a pair
    for who in $order; do
      bin=$BIN/sphfsi; [ $who = B ] && bin=$BASE
      dir=$OUT/${row}_${who}_$rep
      timeout $TMO $MPI -n 2 $bin ${ROW[$row]} -overwrite -progress_every 0 -output_dir $dir > $dir.log 2>&1 || FAILS="$FAILS ${row}_${who}_$rep"
      echo "targets: $row $who run $rep: $(cut -d' ' -f1 /proc/loadavg) load" >&2
    done
  done
done
python3 - $OUT "$REPS" "${BASE:+1}" <<'PY'
import json, os, statistics, sys
out, reps, paired = sys.argv[1], int(sys.argv[2]), bool(sys.argv[3])
rows = [("wcsph3d", "3D WCSPH, SPHERIC Test 2, dx 0.02 m, 200 steps", 3.5e6),
        ("wcsph2d", "2D WCSPH, 1 m x 2 m column, dx 0.01 m, to 0.1 s", 10e6),
        ("isph2d", "2D ISPH, the same column, to 0.1 s", 1.5e6)]
def pss(row, who):
    v = []
    for r in range(1, reps + 1):
        f = f"{out}/{row}_{who}_{r}/summary.json"
        if os.path.exists(f): v.append(json.load(open(f))["particle_steps_per_s"] / 1e6)
    return v
head = "| row | particles | 10⁶ particle-steps/s, median (range) | target | met |"
md = ["## Issue 57's throughput rows (2 ranks)", "", f"{reps} runs of each, rows alternating" + (", each paired with BENCH_BASE's build (B)" if paired else "") + ".", "",
      head + (" B's median (range) | A / B |" if paired else ""), "|---|---|---|---|---|" + ("---|---|" if paired else "")]
for row, what, target in rows:
    a = pss(row, "A")
    f = f"{out}/{row}_A_1/summary.json"
    n = json.load(open(f))["particles"] if os.path.exists(f) else "?"
    fmt = lambda v: f"{statistics.median(v):.2f} ({min(v):.2f}–{max(v):.2f})" if v else "–"
    line = f"| {what} | {n} | {fmt(a)} | {target / 1e6:g} | {'yes' if a and statistics.median(a) * 1e6 >= target else 'no'} |"
    if paired:
        b = pss(row, "B")
        line += f" {fmt(b)} | {statistics.median(a) / statistics.median(b):.3f} |" if a and b else " – | – |"
    md.append(line)
open(f"{out}/../targets.md", "w").write("\n".join(md) + "\n")
print("\n".join(md))
PY
[ -z "$FAILS" ] || { echo "targets: failed:$FAILS (logs in $OUT)" >&2; exit 1; }
