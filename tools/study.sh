#!/usr/bin/env bash
# Speed-versus-error study of issue 6 (not a test; `make study`, ~30 min on 2 idle cores).
# For each validated scene, each scheme at 3 resolutions (Taylor-Green 4) on NP ranks, then tools/study_report.py
# writes out/study/study.md (table with the observed convergence order, and per scene which scheme
# reaches a given error faster) and out/study/<scene>.png (error against wall time, log-log).
#   dam_break           cases/dam_break.opts, WCSPH and ISPH, dx = a/20, a/40, a/80, to 0.3 s;
#                       error: surge front against Martin & Moyce (rms, relative); and the front's
#                       self-convergence (rms change of its curve from the coarser run)
#   dam_break_lobovsky  cases/dam_break_lobovsky.opts, WCSPH and ISPH, dx = H/20, H/40, H/80, to
#                       t sqrt(g/H) = 4; error: water levels H1-H4 against Lobovsky et al. 2014
#   dam_break_impact    cases/dam_break_lobovsky.opts, both fluids, H/20-H/80, to t sqrt(g/H) = 3.7;
#                       error: sensor 1's first peak against the experiment's (and its impulse)
#   dam_break_buchner   cases/dam_break_buchner.opts, both fluids, H/20-H/80, to t sqrt(g/H) = 7;
#                       error: rms of P1 against Buchner 2002 over 2.4 <= t sqrt(g/H) <= 7
#   taylor_green        cases/taylor_green.opts (ISPH with shifting A = 20; WCSPH without: -wcsph_shift came later), dx = L/25, L/50,
#                       L/100, L/200, to 1 s; error: L2 velocity error at t = 1 s (relative)
#   poiseuille          cases/poiseuille.opts, WCSPH and ISPH, dx = Hc/10, Hc/20, Hc/40, to 2 s;
#                       error: L2 velocity error at t = 2 s (relative)
#   oscillating_plate   cases/oscillating_plate.opts (WCSPH solid), 6, 10, 14 particles across, to
#                       0.8 s; error: |period - thin-plate period| / thin-plate period
#   cantilever          cases/cantilever.opts (total-Lagrangian solid, static load, dynamic relaxation),
#                       5, 7, 10 particles across, to 0.12 s; error: |sag - Euler-Bernoulli| / E-B
#                       (plane strain; a 2D FEM of the clamped plate is 0.08 % below it)
#   turek_hron_csm1     cases/turek_hron_csm1.opts (St Venant-Kirchhoff flag under gravity, dynamic
#                       relaxation to 2 s), 4, 8, 16 particles across; error: uy_A against the
#                       benchmark (ux_A beside it).  Not in the default list: 16 across costs ~40 min
#                       on 1 rank
#   turek_hron_csm3     cases/turek_hron_csm3.opts (the same flag swinging to 10 s), 4, 8, 16 across;
#                       error: uy_A's frequency against the benchmark (its amplitude beside it).  Not
#                       in the default list: 16 across costs ~2 h on 1 rank
#   turek_hron_cfd1, _cfd3, _fsi2, _fsi3  cases/turek_hron_*.opts (the channel with the rigid or the
#                       elastic flag, open boundaries), both fluids, 2, 4, 8 particles across the flag
#                       (fsi: 4, 6, 8, even with the fluid; FSI2 kicked at 2 s, to 7 s); error: drag (cfd1), the lift's
#                       amplitude (cfd3), uy_A's amplitude (fsi) against the benchmark.  Not in the
#                       default list: 8 across costs hours on 2 ranks
#   elastic_gate        cases/elastic_gate.opts (ISPH + solid), cases/elastic_gate_wcsph.opts (WCSPH +
#                       solid), uniform dx (-dx_coarse = -dx) 1.667, 1.25, 1 mm (3, 4, 5 particles
#                       across the gate; the scene needs at least 3; the case files' 1 mm at the gate
#                       and 2 mm further away would mix two spacings), to 0.4 s (the case's t_end:
#                       the experiment's 10 points); error: rms of tip_dx against the experiment (m)
# Each run: out/study/<scene>/<scheme>_<res>/ (summary.json, run.json with the exit code, elapsed
# and CPU seconds and the load average before and after; FAILED when the exit code is not 0) and
# out/study/<scene>/<scheme>_<res>.log; out/study/<scene>/plan.tsv lists the runs of the scene.
# A run that fails stays in the table as failed with its exit code and message.
#
# Environment:
#   NP             ranks per run (2)
#   STUDY_SCENES   subset, space-separated (dam_break dam_break_lobovsky taylor_green poiseuille oscillating_plate
#                  cantilever elastic_gate; also dam_break_impact dam_break_buchner turek_hron_csm1 turek_hron_csm3 turek_hron_cfd1 turek_hron_cfd3
#                  turek_hron_fsi2 turek_hron_fsi3, not run by default); the
#                  report covers every scene with a plan.tsv in out/study
#   STUDY_REUSE=1  keep the result of an earlier run with the same options (its run.json)
#   STUDY_SIZE     default | cluster | quick.  cluster: 4-5 resolutions per scheme (the default ones and
#                  finer ones: dam break to a/320, Taylor-Green to L/400, Poiseuille to Hc/80,
#                  plate to 30 across, elastic gate to 0.5 mm), i.e. days on 2
#                  cores, hours on 64+ ranks: on a cluster, e.g. in a batch job,
#                     make study STUDY_SIZE=cluster NP=64 STUDY_TIMEOUT=86400
#                  with MPIEXEC=srun MPIEXEC_FLAGS= for SLURM (the finest runs are what costs; the
#                  coarse ones waste ranks, so several scenes may go to separate jobs with
#                  STUDY_SCENES=... and a last `STUDY_SIZE=cluster STUDY_REUSE=1 make study` for the
#                  report, or `python3 tools/study_report.py out/study`).
#                  quick: tiny runs that check the script; not numbers to quote
#   STUDY_TIMEOUT  seconds per run (3600)
#   MPIEXEC, MPIEXEC_FLAGS, BINDIR (bin), SPHFSI_REFDATA (see tools/lib_runs.sh)
cd "$(dirname "$0")/.."
. tools/lib_runs.sh
BIN=${BINDIR:-bin}
NP=${NP:-2}
OUT=out/study
SIZE=${STUDY_SIZE:-default}
SCENES=${STUDY_SCENES:-dam_break dam_break_lobovsky taylor_green poiseuille oscillating_plate cantilever elastic_gate}
TMO=${STUDY_TIMEOUT:-3600}
[ -x $BIN/sphfsi ] || { echo "$BIN/sphfsi missing: run make first (or make study)" >&2; exit 1; }
case $SIZE in default|cluster|quick) ;; *) echo "STUDY_SIZE must be default, cluster or quick" >&2; exit 1;; esac
find_refdata
mkdir -p $OUT
T0=$SECONDS

# Per scene: SCHEMES ("name:options", ';'-separated), RES ("label:nominal dx:options", ';'-separated,
# coarse to fine), COMMON (options of every run).  Resolutions as divisions of a length: the dam-break
# column width a, the Taylor-Green box L, the Poiseuille channel height Hc, the plate thickness
# (particles across) and the gate thickness (5 mm).
f7() { python3 -c "print(f'{$1:.7g}')"; }
pick() { case $SIZE in default) echo "$1";; cluster) echo "$2";; quick) echo "$3";; esac; }
# fluid CASE LENGTH LABEL DIVS_DEFAULT DIVS_CLUSTER DIVS_QUICK: WCSPH and ISPH, -dx LENGTH/div
fluid() {
  SCHEMES="wcsph:-options_file cases/$1.opts -fluid wcsph;isph:-options_file cases/$1.opts -fluid isph"
  for d in $(pick "$4" "$5" "$6"); do RES="$RES;$3$d:$(f7 $2/$d):-dx $(f7 $2/$d)"; done
}
scene() {
  local d
  RES=""; COMMON="-output_interval 0 -progress_every 0"
  case $1 in
  dam_break)    fluid dam_break 0.05715 a "20 40 80" "20 40 80 160 320" "10 14" ;;
  dam_break_lobovsky) # to t sqrt(g/H) = 4: the front and the first wave, where the experiment's
    # repetitions agree (its gauges' two series differ by 0.005-0.010 H rms); after it the wave breaks
    fluid dam_break_lobovsky 0.3 H "20 40 80" "20 40 80 160" "10 20"; COMMON="$COMMON -t_end 0.7" ;;
  dam_break_impact) # cases/dam_break_lobovsky.opts to t sqrt(g/H) = 3.7: the first impact on the far wall
    fluid dam_break_lobovsky 0.3 H "20 40 80" "20 40 80 160" "10 20"; COMMON="$COMMON -t_end 0.65 -probe_interval 0.0002" ;;
  dam_break_buchner) fluid dam_break_buchner 0.6 H "20 40 80" "20 40 80 160" "10 20" ;;
  taylor_green) fluid taylor_green 1 L "25 50 100 200" "25 50 100 200 400" "10 20" ;;
  poiseuille)   fluid poiseuille 1e-3 Hc "10 20 40" "10 20 40 80" "10 20" ;;
  oscillating_plate)
    SCHEMES="solid:-options_file cases/oscillating_plate.opts"
    for d in $(pick "6 10 14" "6 10 14 20 30" "4 6"); do RES="$RES;ny$d:$(f7 0.02/$d):-plate_ny $d"; done ;;
  cantilever) # the static cantilever's sag (cases/cantilever.opts): 5 across 14 s, 10 across 126 s here
    SCHEMES="solid:-options_file cases/cantilever.opts"
    for d in $(pick "5 7 10" "5 10 20 40" "4 5"); do RES="$RES;ny$d:$(f7 0.005/$d):-plate_ny $d"; done ;;
  turek_hron_csm1|turek_hron_csm3) # Turek-Hron's solid cases (cases/turek_hron_csm*.opts); flag 0.02 m thick
    SCHEMES="solid:-options_file cases/$1.opts"
    for d in $(pick "4 8 16" "4 8 16 32" "4 5"); do RES="$RES;ny$d:$(f7 0.02/$d):-flag_ny $d"; done ;;
  turek_hron_cfd1|turek_hron_cfd3|turek_hron_fsi2|turek_hron_fsi3) # Turek-Hron's channel (cases/turek_hron_*.opts), both fluids; even counts across the flag
    SCHEMES="wcsph:-options_file cases/$1.opts;isph:-options_file cases/$1.opts -fluid isph -h_factor 1.3 -fluid_shift_correct 0 -isph_shift 5 -isph_alpha 0"
    # the fluid-structure cases: ISPH's recipe of cases/turek_hron_fsi2.opts; FSI3's flag, as dense as
    # the water, also needs its pressure rows' inertia at the particles' own mass
    case $1 in *fsi*) divs=$(pick "4 6 8" "4 6 8 12" "4"); SCHEMES="$SCHEMES -solid_h_factor 1.3 -isph_solid_eq14 0 -solid_alpha 1 -fsi_mean_acc 0";; *) divs=$(pick "2 4 8" "2 4 8 16" "2");; esac
    [ $1 = turek_hron_fsi3 ] && SCHEMES="$SCHEMES -fsi_row_stiffness 0 -fluid_shift_ceiling 1"
    # FSI2's flutter grows from round-off for 5 s: a pulse of gravity at 2 s (the flag, 10 times as
    # dense as the water, sinks) starts it; at 6 across its limit cycle holds from 5 s (docs/turek_hron_fsi2.md).
    # FSI3's flag is as dense as the water, which a pulse of gravity does not push; it starts by itself.
    [ $1 = turek_hron_fsi2 ] && COMMON="$COMMON -gravity_pulse 0,-4,2,2.2 -t_end 7"
    for d in $divs; do RES="$RES;ny$d:$(f7 0.02/$d):-flag_ny $d"; done ;;
  elastic_gate)
    SCHEMES="isph:-options_file cases/elastic_gate.opts;wcsph:-options_file cases/elastic_gate_wcsph.opts"
    for d in $(pick "3 4 5" "3 4 5 7 10" "3"); do
      RES="$RES;$(python3 -c "print(f'{5/$d:.3g}')")mm:$(f7 0.005/$d):-dx $(f7 0.005/$d) -dx_coarse $(f7 0.005/$d)"
    done ;;
  *) echo "unknown scene $1 (STUDY_SCENES)" >&2; return 1;;
  esac
  # every scene runs to its case file's t_end, but for STUDY_SIZE=quick
  [ $SIZE = quick ] && COMMON="$COMMON -t_end $(case $1 in oscillating_plate) echo 0.3;; cantilever) echo 0.02;; turek_hron_csm1) echo 0.1;; turek_hron_csm3) echo 2;; turek_hron_cfd*|turek_hron_fsi*) echo 0.5;; elastic_gate) echo 0.01;; dam_break_impact) echo 0.65;; dam_break_buchner) echo 1.74;; *) echo 0.1;; esac)"
  RES=${RES#;}
}

for sc in $SCENES; do
  scene $sc || exit 1
  mkdir -p $OUT/$sc
  plan=$OUT/$sc/plan.tsv
  printf '# size %s, %s ranks, options of every run: %s\n' "$SIZE" "$NP" "$COMMON" > $plan.part
  IFS=';' read -ra schemes <<< "$SCHEMES"; IFS=';' read -ra resl <<< "$RES"
  # resolution by resolution, the schemes one after the other: on a shared machine the two runs at
  # the same dx then see about the same load
  for r in "${resl[@]}"; do
    IFS=':' read -r rlab rdx ropts <<< "$r"
    for s in "${schemes[@]}"; do
      sname=${s%%:*}; sopts=${s#*:}
      name=${sname}_$rlab; dir=$OUT/$sc/$name
      printf '%s\t%s\t%s\t%s\t%s\n' "$sname" "$rlab" "$rdx" "$name" "$sopts $ropts" >> $plan.part
      if [ -n "${STUDY_REUSE:-}" ] && [ -f $dir/run.json ] && \
         python3 -c "import json, sys; sys.exit(json.load(open('$dir/run.json'))['options'] != sys.argv[1])" "$(echo $sopts $ropts $COMMON)"; then
        echo "$sc $name: reusing the earlier result (same options)" >&2; continue
      fi
      run_sphfsi $dir $OUT/$sc/$name.log $TMO $NP $sopts $ropts $COMMON
      echo "$sc $name: exit $?, $(python3 -c "import json; r = json.load(open('$dir/run.json')); print(f\"{r['elapsed_s']:.1f} s, load {r['load_before']} -> {r['load_after']}\")")" >&2
    done
  done
  mv $plan.part $plan
done
echo "study: $((SECONDS - T0)) s for the runs of: $SCENES" >&2
python3 tools/study_report.py $OUT
