#!/usr/bin/env bash
# PPE scaling benchmark (not a test): ISPH dam break (cases/dam_break.opts) for a fixed number of
# steps at dx = a/N for each N in BENCH_PPE_DIVS (a = column width 0.05715 m; halving dx gives
# ~4x the particles). Reports the pressure-solver iterations per step (CG + BoomerAMG, from
# summary.json) and the share of the -log_view stages (PPE assembly, PPE solve, Neighbours,
# Halo+migrate, Physics, Output; "set-up" = Main Stage = everything outside the stages), the
# preconditioner set-up time per step and the time of one preconditioner application (V-cycle),
# from the PCSetUp/PCApply events of the "PPE solve" stage.
# Also repeats every resolution with a zero initial guess (the production runs start CG from the
# last pressure, which hides part of the cost) and some with -ppe_ksp_type gmres -ppe_pc_type gamg.
# Writes out/bench/ppe/ppe.md (and one directory + log per run).
#
# Environment: MPIEXEC, MPIEXEC_FLAGS (as tools/bench.sh), BENCH_NP (ranks, 1),
#   BENCH_PPE_DIVS (a/dx values, "64 128 256 512"), BENCH_PPE_STEPS (steps per run, 50),
#   BENCH_PPE_GAMG (a/dx values of the gmres+gamg runs, "64 256"; empty = skip),
#   BENCH_PPE_ZERO_GUESS (1: repeat every resolution with -ppe_ksp_initial_guess_nonzero false, i.e.
#   a zero initial guess instead of the last pressure; empty = skip),
#   BENCH_TIMEOUT (seconds per run, 900), BENCH_ARGS (extra sphfsi options for every run).
cd "$(dirname "$0")/.."
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-}"
NP=${BENCH_NP:-1}
OUT=out/bench/ppe; mkdir -p $OUT
A=0.05715
DIVS=${BENCH_PPE_DIVS:-64 128 256 512}
STEPS=${BENCH_PPE_STEPS:-50}
GAMG=${BENCH_PPE_GAMG-64 256}
COLD=${BENCH_PPE_ZERO_GUESS-1}
TMO=${BENCH_TIMEOUT:-900}
[ -x bin/sphfsi ] || { echo "bin/sphfsi missing: run make first" >&2; exit 1; }

# run NAME DIV [extra options...]: one ISPH dam-break run, then print its table row
run() {
  local name=$1 div=$2; shift 2
  local dx; dx=$(python3 -c "print(f'{$A/$div:.7g}')")
  local dir=$OUT/$name
  rm -rf $dir; mkdir -p $dir
  local t0=$SECONDS
  timeout $TMO $MPI -n $NP bin/sphfsi -overwrite -options_file cases/dam_break.opts -fluid isph -dx $dx \
    -max_steps $STEPS -output_interval 0 -probe_interval 0 -progress_every 0 -output_dir $dir \
    -log_view :$dir/log_view.txt ${BENCH_ARGS:-} "$@" > $OUT/$name.log 2>&1
  local rc=$?
  echo "$name: dx $dx, exit $rc, $((SECONDS - t0)) s elapsed" >&2
  if [ $rc -ne 0 ] || [ ! -f $dir/summary.json ]; then
    echo "| $* | a/$div = $dx | run failed (exit $rc), see $OUT/$name.log |"
    return 1
  fi
  python3 - "$dir" "$div" "$*" <<'PY'
import json, re, sys, csv
d, div, extra = sys.argv[1], sys.argv[2], sys.argv[3]
s = json.load(open(f"{d}/summary.json"))
stages, events, stage = {}, {}, None
for line in open(f"{d}/log_view.txt"):
    m = re.match(r"\s*\d+:\s+(.+?):\s+(\S+)\s+([\d.]+)%", line)
    if m and stage is None: stages[m.group(1).strip()] = (float(m.group(2)), float(m.group(3)))
    m = re.match(r"--- Event Stage \d+: (.+)", line)
    if m: stage = m.group(1).strip()
    m = re.match(r"(PCSetUp|PCApply)\s+(\d+)\s+\S+\s+(\S+)", line)
    if m and stage == "PPE solve": events[m.group(1)] = (int(m.group(2)), float(m.group(3)))
pct = lambda k: f"{stages[k][1]:.1f}" if k in stages else "-"
t = None
with open(f"{d}/probes.csv") as f:
    for row in csv.reader(f): t = row[0]
opt = dict(re.findall(r"-ppe_(ksp_type|pc_type|ksp_initial_guess_nonzero)\s+(\S+)", extra))
solver = f"{opt.get('ksp_type', 'cg')}+{opt.get('pc_type', 'boomeramg')}"
solver += ", zero guess" if opt.get("ksp_initial_guess_nonzero") in ("false", "0", "no") else ""
steps = s["steps"]
ppe_ms = 1e3 * stages.get("PPE solve", (0, 0))[0] / steps
setup_ms = 1e3 * events["PCSetUp"][1] / steps if "PCSetUp" in events else float("nan")
cycle_ms = 1e3 * events["PCApply"][1] / events["PCApply"][0] if "PCApply" in events else float("nan")
print(f"| {solver} | {s['particles']} | a/{div} = {s['dx']:.5g} | {steps} | {float(t):.3g} | "
      f"{s['ksp_its_mean']:.2f} ({s['ksp_its_max']}) | {pct('PPE assembly')} | {pct('PPE solve')} | "
      f"{pct('Neighbours')} | {pct('Halo+migrate')} | {pct('Physics')} | {pct('Output')} | {pct('Main Stage')} | "
      f"{ppe_ms:.1f} | {setup_ms:.1f} | {cycle_ms:.2f} | {s['wall_s'] / steps:.4g} |")
PY
}

{
  echo "ISPH dam break (cases/dam_break.opts -fluid isph), $STEPS steps from rest, $NP rank(s); stage shares in % of the -log_view total time"
  echo
  echo "| solver | particles | dx (m) | steps | t reached (s) | PPE its/step mean (max) | PPE assembly % | PPE solve % | Neighbours % | Halo+migrate % | Physics % | Output % | set-up % | PPE solve ms/step | PC setup ms/step | PC apply ms | wall s/step |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for div in $DIVS; do run isph_a$div $div; done
  if [ -n "$COLD" ]; then for div in $DIVS; do run isph_a${div}_zeroguess $div -ppe_ksp_initial_guess_nonzero false; done; fi
  for div in $GAMG; do run isph_a${div}_gamg $div -ppe_ksp_type gmres -ppe_pc_type gamg; done
} | tee $OUT/ppe.md
