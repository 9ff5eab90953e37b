#!/usr/bin/env bash
# Past two ranks (issue 46): small cases on 3, 8 and 16 ranks against 1 rank (`make ranks`; the ranks
# are oversubscribed on a small machine: Open MPI then yields when idle by itself).  Every check prints
# 'PASS|FAIL NAME: measured (bound)' and the suite writes out/ranks/ranks.md; it ends with
# 'N passed, N failed' (exit status 1 on any failure).  Comparisons: tools/ranks_compare.py, every
# dataset of every snapshot (and of checkpoint.h5 where said) by particle id, and probes.csv.
# Bounds, stated before the runs:
#  - WCSPH and the solid: 0 (bit for bit).  Neighbour sums run in an order that does not depend on
#    the decomposition (tests/test_rank_agreement.c), so any difference is a bug.  Probe columns that
#    sum over particles reduce across ranks in another order: 1e-12 of the column's largest value.
#  - ISPH: 1e-8 of each field's largest value at -ppe_ksp_rtol 1e-10, the bound of the 2-rank tests
#    (test_rank_agreement_isph, _fsi_isph, check_3d.sh): the preconditioner differs with the ranks, so
#    the runs agree to the solver's tolerance (100x margin) over these short runs (t_end as there).
#    Through the dam break's collapse and impact (t = 0.2 s) the flow amplifies a difference ~10^3
#    (measured 1 against 2 ranks: p 7e-11 at 0.05 s, 9e-8 at 0.2 s at rtol 1e-10; 1e-10 at 0.2 s at
#    rtol 1e-12, i.e. the solver's tolerance and not the ranks): those runs use -ppe_ksp_rtol 1e-12
#    and keep the bound 1e-8.
# Checks (case: what):
#  db_wcsph_{3,16}, db_wcsph_8_drain: the WCSPH dam break of test_rank_agreement (dx 4 mm, delta-SPH,
#    AV, XSPH) to 0.2 s (the surge reaches the far wall at ~0.17 s), snapshots every 0.025 s and the
#    final checkpoint by id against 1 rank.  8 ranks never repartition (-rebalance_threshold 1000):
#    the ranks that held the top of the column lose all their particles as it collapses
#    (summary.json ranks_empty_max >= 1 asserted).  16 ranks: the sparse exchange (the default from
#    9 ranks) with the default rebalancing, repartitions >= 1 asserted.
#  db_isph_{3,8,16}: the ISPH dam break (cases/dam_break.opts) at dx 4 mm to 0.05 s, snapshots and
#    checkpoint; db_isph_8_drain: to 0.2 s at rtol 1e-12 without repartitioning (ranks lose all; a
#    balance check at every step to see it, and the same -rebalance_every on 1 rank).
#  d3_{wcsph,isph}_{3,8,16}: a 3D dam break (-case boxes -dim 3, dx 1 cm, a 6 x 5 x 12 cm column in a
#    24 x 5 cm tank, 5550 particles) to 0.05 s; ISPH with check_3d.sh's BoomerAMG settings for 3D.
#  gate_{wcsph,isph}_{3,8,16}: the elastic gate as test_rank_agreement_fsi and _fsi_isph (dx 1.25 mm,
#    to 3 ms and 10 ms), snapshots and checkpoint.  ISPH: the solid's acceleration, which the
#    checkpoint holds, with test_restart_fsi_isph's bound 1e-6 (it answers a position difference dx
#    with ~c0^2 dx / h^2; measured 1.5-2.3e-8 while every other field is within 1.2e-9).
#  restart_{wcsph,isph}_{8to3,3to8}: stopped after half the steps (-max_steps) on one rank count,
#    restarted from its checkpoint on the other, against the uninterrupted 1-rank run (every snapshot
#    of the chain, probes.csv, the final checkpoint).
#  empty_start_{wcsph,isph}_16: 16 ranks on the dam break at dx 2 cm (177 particles): METIS leaves
#    ranks without a cell (ranks_empty_max >= 1 after -max_steps 1, i.e. at the start), then the run to
#    0.2 s against 1 rank; empty_start_restart: that 1-step run's checkpoint (some ranks wrote no
#    particle into it) restarted on 3 ranks, against the uninterrupted 1-rank run.
#  too_many_ranks: 16 ranks on the hydrostatic tank at dx 5 cm: status 2 and one line
#    'sphfsi: error: ... at most N ranks'; N ranks then run (status 0, bit for bit with 1 rank) and
#    N + 1 stop the same way, so N is the largest count that runs.
#  rebalance_{wcsph,isph}_8: -rebalance_every 1 -rebalance_threshold 1 (a repartition at every step
#    whose work is not exactly balanced) to 0.05 s: repartitions >= half the steps and agreement with
#    1 rank run with the same -rebalance_every (the rebuild schedule follows it).
# Environment:
#   RANKS_CHECKS  a subset of the groups: db_wcsph db_isph d3 gate restart empty_start too_many_ranks
#                 rebalance (default: all)
#   RANKS_REUSE=1 keep the runs that completed before (out/ranks/RUN/rc): only compare again
#   BINDIR (bin), MPIEXEC (mpiexec), MPIEXEC_FLAGS (--oversubscribe added for Open MPI when missing),
#   RANKS_TIMEOUT (s per run, 900), RANKS_OUT (out/ranks)
cd "$(dirname "$0")/.." || exit 2
BIN=${BINDIR:-bin}/sphfsi
OUT=${RANKS_OUT:-out/ranks}
TMO=${RANKS_TIMEOUT:-900}
ALL="db_wcsph db_isph d3 gate restart empty_start too_many_ranks rebalance"
CHECKS=${RANKS_CHECKS:-$ALL}
for c in $CHECKS; do [[ " $ALL " == *" $c "* ]] || { echo "RANKS_CHECKS: unknown group $c (groups: $ALL)" >&2; exit 2; }; done
[ -x "$BIN" ] || { echo "run make ranks (needs $BIN)" >&2; exit 1; }
# more ranks than cores: Open MPI wants --oversubscribe, and then yields when idle by itself
# (mpi_yield_when_idle "will default to 1 when oversubscribing nodes", ompi_info; measured through
# MPI_T: 0 at 2 ranks on 2 cores with or without --oversubscribe, 1 from 3 ranks on)
FLAGS=${MPIEXEC_FLAGS:-}
if [[ " $FLAGS " != *" --oversubscribe "* ]] && ${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte"; then FLAGS+=" --oversubscribe"; fi
MPI="${MPIEXEC:-mpiexec} $FLAGS"
[ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 # as the Makefile
if [ -z "${SPHFSI_REFDATA:-}" ] && [ ! -d ../shared/refdata ]; then # as tests/run_tests.sh
  origin=$(git config --get remote.origin.url 2>/dev/null || true)
  if [ -n "$origin" ] && [ -d "$origin/../shared/refdata" ]; then export SPHFSI_REFDATA=$(cd "$origin/../shared/refdata" && pwd); fi
fi
mkdir -p "$OUT"
: > "$OUT/results.tsv"
T0=$SECONDS
LOAD0=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null) # the suite's wall time means little on a shared machine
pass=0; fail=0

# run NAME NP sphfsi-options...: one run into $OUT/NAME (log NAME.log, exit status in NAME/rc)
run() {
  local name=$1 np=$2; shift 2
  local dir=$OUT/$name
  if [ -n "${RANKS_REUSE:-}" ] && [ "$(cat "$dir/rc" 2>/dev/null)" = 0 ]; then return 0; fi
  rm -rf "$dir"; mkdir -p "$dir"
  timeout "$TMO" $MPI -n "$np" "$BIN" "$@" -progress_every 0 -overwrite -output_dir "$dir" > "$OUT/$name.log" 2>&1
  echo $? > "$dir/rc"
}
# resume NAME NP CHECKPOINT sphfsi-options...: the second half of a restarted run, into the same directory
resume() {
  local name=$1 np=$2 ck=$3; shift 3
  local dir=$OUT/$name
  if [ -n "${RANKS_REUSE:-}" ] && [ "$(cat "$dir/rc2" 2>/dev/null)" = 0 ]; then return 0; fi
  timeout "$TMO" $MPI -n "$np" "$BIN" "$@" -restart "$ck" -progress_every 0 -output_dir "$dir" > "$OUT/$name.2.log" 2>&1
  echo $? > "$dir/rc2"
}
rc() { cat "$OUT/$1/${2:-rc}" 2>/dev/null || echo none; }
js() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$OUT/$1/summary.json" "$2" 2>/dev/null || echo none; }
# result NAME RANKS MEASURED BOUND OK(0|1) [WHY]
result() {
  local r=PASS
  [ "$5" = 0 ] || { r=FAIL; fail=$((fail + 1)); }
  [ $r = PASS ] && pass=$((pass + 1))
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "$r" "${6:-}" >> "$OUT/results.tsv"
  echo "$r $1 ($2 ranks): $3 (bound $4)${6:+; $6}"
}
# compare NAME RANKS REF RUN TOL [--checkpoint]: every snapshot (and the checkpoint) of RUN against REF by id
compare() {
  local name=$1 np=$2 ref=$3 run=$4 tol=$5; shift 5
  local why="" out ok=0
  for d in $ref $run; do
    [ "$(rc "$d")" = 0 ] || why+="run $d exited $(rc "$d") ($OUT/$d.log); "
    [ -f "$OUT/$d/rc2" ] && [ "$(rc "$d" rc2)" != 0 ] && why+="restart of $d exited $(rc "$d" rc2) ($OUT/$d.2.log); "
  done
  if [ -n "$why" ]; then result "$name" "$np" "-" "$tol" 1 "$why"; return; fi
  out=$(python3 tools/ranks_compare.py "$OUT/$ref" "$OUT/$run" --tol "$tol" "$@") || ok=1
  echo "$out" > "$OUT/$name.cmp"
  local nums extra="" xb=""; nums=($(head -n 1 <<< "$out"))
  [ ${#nums[@]} -gt 2 ] && extra=", ${nums[*]:2}" && xb=", $(grep -o -- '--field_tol [^ ]*' <<< "$*" | cut -d' ' -f2 | tr '=' ' ')"
  result "$name" "$np" "state ${nums[0]}, probes ${nums[1]}$extra" "$tol (probes $([ "$tol" = 0 ] && echo 1e-12 || echo "$tol")$xb)" $ok "$([ $ok = 0 ] && echo "${NOTE:-$(empties "$run")}" || tail -n 1 <<< "$out")"
}
# empties RUN: the ranks without particles / fluid at the balance checks (summary.json), when any
empties() {
  local e f; e=$(js "$1" ranks_empty_max); f=$(js "$1" ranks_without_fluid_max)
  [ "$e$f" = 00 ] || [ "$e" = none ] || echo "at most $e rank(s) without particles and $f without fluid at a balance check"
}
# atleast NAME RANKS RUN KEY MIN WHAT: a count from summary.json
atleast() {
  local v; v=$(js "$3" "$4")
  local ok=1; [[ "$v" =~ ^[0-9]+$ ]] && [ "$v" -ge "$5" ] && ok=0
  result "$1" "$2" "$4 = $v" ">= $5" $ok "$6"
}
has() { [[ " $CHECKS " == *" $1 "* ]]; }

# the WCSPH dam break of tests/test_rank_agreement.c (every WCSPH option on), through the collapse
DBW="-case dam_break -dx 0.004 -wcsph_delta 0.1 -wcsph_alpha 0.1 -fluid_xsph 0.5 -output_interval 0.025 -checkpoint_interval 1e9"
DBI="-options_file cases/dam_break.opts -fluid isph -dx 0.004 -output_interval 0.025 -checkpoint_interval 1e9"
if has db_wcsph; then
  run db_wcsph_1 1 $DBW -t_end 0.2
  run db_wcsph_3 3 $DBW -t_end 0.2
  compare db_wcsph_3 3 db_wcsph_1 db_wcsph_3 0 --checkpoint
  run db_wcsph_8_drain 8 $DBW -t_end 0.2 -rebalance_threshold 1000
  compare db_wcsph_8_drain 8 db_wcsph_1 db_wcsph_8_drain 0 --checkpoint
  atleast db_wcsph_8_drain_empty 8 db_wcsph_8_drain ranks_empty_max 1 "ranks that lost all their particles at one balance check (partition of the column at rest kept)"
  run db_wcsph_16 16 $DBW -t_end 0.2
  compare db_wcsph_16 16 db_wcsph_1 db_wcsph_16 0 --checkpoint
  ok=1; grep -q "16 rank(s).*sparse exchanges" "$OUT/db_wcsph_16.log" && ok=0
  result db_wcsph_16_sparse 16 "$(grep -o '[a-z-]* exchanges' "$OUT/db_wcsph_16.log" | head -n 1), $(js db_wcsph_16 repartitions) repartitions" "sparse, >= 1" $([ $ok = 0 ] && [ "$(js db_wcsph_16 repartitions)" -ge 1 ] 2>/dev/null && echo 0 || echo 1)
fi
if has db_isph; then
  run db_isph_1 1 $DBI -t_end 0.05 -ppe_ksp_rtol 1e-10
  for np in 3 8 16; do
    run db_isph_$np $np $DBI -t_end 0.05 -ppe_ksp_rtol 1e-10
    compare db_isph_$np $np db_isph_1 db_isph_$np 1e-8 --checkpoint
  done
  # a balance check at every step (-rebalance_every 1; never repartitioning) counts the ranks that drained
  # (every 20 steps, the default, saw none on 8 ranks); the 1-rank run too (the schedule of rebuilds)
  run db_isph12_1 1 $DBI -t_end 0.2 -ppe_ksp_rtol 1e-12 -rebalance_every 1
  run db_isph_8_drain 8 $DBI -t_end 0.2 -ppe_ksp_rtol 1e-12 -rebalance_every 1 -rebalance_threshold 1000
  compare db_isph_8_drain 8 db_isph12_1 db_isph_8_drain 1e-8 --checkpoint
  atleast db_isph_8_drain_empty 8 db_isph_8_drain ranks_empty_max 1 "ranks that lost all their particles at one balance check (partition of the column at rest kept)"
fi
if has d3; then
  D3="-case boxes -dim 3 -dx 0.01 -tank_1 0,0.24,0,0.05,0,0.2 -fluid_box_1 0,0,0,0.06,0.05,0.12 -wcsph_alpha 0.1 -wcsph_delta 0.1 -t_end 0.05 -output_interval 0.025 -checkpoint_interval 1e9"
  AMG3="-ppe_pc_hypre_boomeramg_coarsen_type HMIS -ppe_pc_hypre_boomeramg_interp_type ext+i -ppe_pc_hypre_boomeramg_P_max 4 -ppe_pc_hypre_boomeramg_agg_nl 1 -ppe_pc_hypre_boomeramg_strong_threshold 0.5"
  run d3_wcsph_1 1 $D3
  run d3_isph_1 1 $D3 -fluid isph -ppe_ksp_rtol 1e-10 $AMG3
  for np in 3 8 16; do
    run d3_wcsph_$np $np $D3
    compare d3_wcsph_$np $np d3_wcsph_1 d3_wcsph_$np 0 --checkpoint
    run d3_isph_$np $np $D3 -fluid isph -ppe_ksp_rtol 1e-10 $AMG3
    compare d3_isph_$np $np d3_isph_1 d3_isph_$np 1e-8 --checkpoint
  done
fi
if has gate; then
  GW="-case elastic_gate -fluid wcsph -dx 0.00125 -t_end 0.003 -output_interval 0.001 -checkpoint_interval 1e9"
  GI="-case elastic_gate -fluid isph -dx 0.00125 -t_end 0.01 -ppe_ksp_rtol 1e-10 -output_interval 0.005 -checkpoint_interval 1e9"
  run gate_wcsph_1 1 $GW
  run gate_isph_1 1 $GI
  for np in 3 8 16; do
    run gate_wcsph_$np $np $GW
    compare gate_wcsph_$np $np gate_wcsph_1 gate_wcsph_$np 0 --checkpoint
    run gate_isph_$np $np $GI
    # the solid's acceleration in the checkpoint answers a position difference dx with ~c0^2 dx / h^2
    # (stiffer at its one-sided surface fits and clamp faces): test_restart_fsi_isph's bound, 1e-6
    compare gate_isph_$np $np gate_isph_1 gate_isph_$np 1e-8 --checkpoint --field_tol acc=1e-6
  done
fi
if has restart; then
  # WCSPH to 0.1 s (1122 steps), ISPH the 0.05 s run of db_isph (its 1-rank run is the reference)
  run rs_wcsph_1 1 $DBW -t_end 0.1
  [ -f "$OUT/db_isph_1/rc" ] || run db_isph_1 1 $DBI -t_end 0.05 -ppe_ksp_rtol 1e-10
  for f in wcsph isph; do
    if [ $f = wcsph ]; then ref=rs_wcsph_1; o="$DBW -t_end 0.1"; tol=0; else ref=db_isph_1; o="$DBI -t_end 0.05 -ppe_ksp_rtol 1e-10"; tol=1e-8; fi
    half=$(( $(js $ref steps) / 2 ))
    for p in "8 3" "3 8"; do
      set -- $p
      name=restart_${f}_${1}to$2
      run $name $1 $o -max_steps $half
      resume $name $2 "$OUT/$name/checkpoint.h5" $o
      compare $name "$1 -> $2" $ref $name $tol --checkpoint
    done
  done
fi
if has empty_start; then
  DBE="-options_file cases/dam_break.opts -dx 0.02 -t_end 0.2 -output_interval 0.05 -checkpoint_interval 1e9"
  run empty_start_probe 16 $DBE -max_steps 1
  atleast empty_start_16 16 empty_start_probe ranks_empty_max 1 "ranks without a particle after the first partition (a 1-step run: only step 0 is checked)"
  for f in wcsph isph; do
    tol=0; x=""; [ $f = isph ] && { tol=1e-8; x="-ppe_ksp_rtol 1e-10"; }
    run empty_${f}_1 1 $DBE -fluid $f $x
    run empty_${f}_16 16 $DBE -fluid $f $x
    compare empty_start_${f}_16 16 empty_${f}_1 empty_${f}_16 $tol --checkpoint
  done
  # the 1-step run's checkpoint, written by 16 ranks of which some hold no particle, restarted on 3
  z=$(python3 -c "import h5py, sys; print(int((h5py.File(sys.argv[1])['rank_counts'][:] == 0).sum()))" "$OUT/empty_start_probe/checkpoint.h5" 2>/dev/null || echo none)
  if [ -z "${RANKS_REUSE:-}" ] || [ "$(rc empty_restart rc2)" != 0 ]; then
    rm -rf "$OUT/empty_restart"; cp -r "$OUT/empty_start_probe" "$OUT/empty_restart"
  fi
  resume empty_restart 3 "$OUT/empty_restart/checkpoint.h5" $DBE -fluid wcsph
  NOTE="checkpoint written with $z rank(s) holding no particle" compare empty_start_restart "16 -> 3" empty_wcsph_1 empty_restart 0 --checkpoint
  [[ "$z" =~ ^[1-9] ]] || result empty_start_restart_counts 16 "$z rank(s) with no particle in the checkpoint" ">= 1" 1
fi
if has too_many_ranks; then
  TM="-case hydrostatic -dx 0.05 -t_end 0.05 -output_interval 0.025 -checkpoint_interval 1e9"
  run too_many_16 16 $TM
  log=$OUT/too_many_16.log
  n=$(grep -o '^sphfsi: error: .*at most [0-9]* ranks' "$log" | grep -o 'at most [0-9]*' | grep -o '[0-9]*$')
  ok=1
  [ "$(rc too_many_16)" = 2 ] && [ "$(grep -c '^sphfsi: error: ' "$log")" = 1 ] && ! grep -q "PETSC ERROR\|Segmentation\|signal" "$log" && [ -n "$n" ] && ok=0
  result too_many_ranks 16 "status $(rc too_many_16): $(grep -m 1 '^sphfsi: error: ' "$log")" "status 2, one line naming the largest count" $ok
  if [ -n "$n" ]; then
    run too_many_1 1 $TM
    run too_many_n $n $TM
    compare too_many_named $n too_many_1 too_many_n 0 --checkpoint
    run too_many_n1 $((n + 1)) $TM
    ok=1; [ "$(rc too_many_n1)" = 2 ] && grep -q "^sphfsi: error: .*at most $n ranks" "$OUT/too_many_n1.log" && ok=0
    result too_many_named_plus_1 $((n + 1)) "status $(rc too_many_n1)" "status 2, 'at most $n ranks'" $ok
  fi
fi
if has rebalance; then
  RB="-rebalance_every 1 -t_end 0.05"
  for f in wcsph isph; do
    if [ $f = wcsph ]; then o=$DBW; tol=0; else o="$DBI -ppe_ksp_rtol 1e-10"; tol=1e-8; fi
    run rebalance_${f}_1 1 $o $RB
    run rebalance_${f}_8 8 $o $RB -rebalance_threshold 1
    compare rebalance_${f}_8 8 rebalance_${f}_1 rebalance_${f}_8 $tol --checkpoint
    s=$(js rebalance_${f}_8 steps)
    atleast rebalance_${f}_8_count 8 rebalance_${f}_8 repartitions $(( ${s/none/2} / 2 )) "of $s steps (a balance check at every step)"
  done
fi

wall=$((SECONDS - T0))
python3 - "$OUT" "$wall" "$LOAD0 -> $(cut -d' ' -f1 /proc/loadavg 2>/dev/null)" "$(git rev-parse --short HEAD 2>/dev/null || echo '?')$(git diff --quiet HEAD -- src include tools 2>/dev/null || echo '+changes')" <<'PY'
import datetime, os, sys
out, wall, load, commit = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
rows = [l.rstrip("\n").split("\t") for l in open(out + "/results.tsv") if l.strip()]
with open(out + "/ranks.md", "w") as f:
    f.write(f"# Past two ranks: 1 rank against 3, 8 and 16 (`make ranks`)\n\n")
    f.write(f"Commit {commit}, {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, {wall // 60} min {wall % 60} s for the suite{' (RANKS_REUSE: earlier runs compared again)' if os.environ.get('RANKS_REUSE') else ''} at a load "
            f"average of {load} (ranks oversubscribed: no timing of the runs here).  Measured: the largest difference relative to each field's "
            "largest value over every snapshot (and the checkpoint) by particle id, then probes.csv; or a count "
            "from summary.json.  Bounds and cases: tools/ranks.sh.\n\n")
    f.write("| check | ranks | measured | bound | result | note |\n|---|---|---|---|---|---|\n")
    for r in rows:
        r += [""] * (6 - len(r))
        f.write("| " + " | ".join(x.replace("|", "/") for x in r[:6]) + " |\n")
    f.write(f"\n{sum(r[4] == 'PASS' for r in rows)} passed, {sum(r[4] == 'FAIL' for r in rows)} failed\n")
PY
echo "table: $OUT/ranks.md ($((wall / 60)) min $((wall % 60)) s)"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
