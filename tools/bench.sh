#!/usr/bin/env bash
# Throughput benchmark (not a test): WCSPH dam break with ~25k particles on 1 and 2 ranks.
# particle-steps/s = particles x steps / wall seconds of the time loop (summary.json).
# Writes out/bench/bench.md.
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-}"
OUT=out/bench; mkdir -p $OUT
DX=${BENCH_DX:-0.0005715}   # a/100: 20k fluid + walls
TEND=${BENCH_TEND:-0.01}
row() { python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print(f\"| {s['case']} | {s['fluid']} | {s['ranks']} | {s['particles']} | {s['steps']} | {s['wall_s']:.2f} | {s['particle_steps_per_s']:.3e} |\")" "$1"; }
{
  echo "| case | fluid | ranks | particles | steps | wall s | particle-steps/s |"
  echo "|---|---|---|---|---|---|---|"
  for np in 1 2; do
    $MPI -n $np bin/sphfsi -options_file cases/dam_break.opts -dx $DX -t_end $TEND -output_interval 0 -probe_interval 0.001 -progress_every 0 -output_dir $OUT/dam_break_np$np > $OUT/dam_break_np$np.log 2>&1 || { echo "run failed: $OUT/dam_break_np$np.log" >&2; exit 1; }
    row $OUT/dam_break_np$np/summary.json
  done
} | tee $OUT/bench.md
python3 - <<'PY'
import json
a = json.load(open("out/bench/dam_break_np1/summary.json")); b = json.load(open("out/bench/dam_break_np2/summary.json"))
s = b["particle_steps_per_s"] / a["particle_steps_per_s"]
line = f"\n2-rank speed-up {s:.2f} (parallel efficiency {50*s:.0f} %); anchors on this machine: PySPH / DualSPHysics ~1.7e6 (1 core), ~3.0e6 (2 cores)\n"
print(line); open("out/bench/bench.md", "a").write(line)
PY
