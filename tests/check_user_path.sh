#!/usr/bin/env bash
# A user's path (issue 27): a shipped case file runs without a warning (each scheme's solver
# options under its own prefix), OUTDIR/options_used lists the options given, chosen and defaulted
# and repeats the run bit for bit, -version names
# the version and the libraries, and an unprefixed PETSc solver option is bad input (status 2)
# with a hint to the -ppe_ prefix.
MPI=$1; OUT=$2
mkdir -p "$OUT"
bad=0
fail() { echo "user_path: $*"; bad=1; }
BIN="${BINDIR:-bin}"/sphfsi
timeout 120 $MPI $BIN -options_file cases/dam_break.opts -t_end 0.01 -progress_every 0 -output_dir "$OUT/wcsph" > "$OUT/wcsph.log" 2>&1 || fail "the WCSPH dam break: status $?"
grep -qi "warning" "$OUT/wcsph.log" && fail "the WCSPH dam break case file warns: $(grep -i warning "$OUT/wcsph.log" | head -1)"
timeout 120 $MPI $BIN -options_file cases/dam_break.opts -fluid isph -t_end 0.01 -progress_every 0 -output_dir "$OUT/isph" > "$OUT/isph.log" 2>&1 || fail "the ISPH dam break: status $?"
grep -qi "warning" "$OUT/isph.log" && fail "the ISPH dam break case file warns: $(grep -i warning "$OUT/isph.log" | head -1)"
[ -s "$OUT/isph/options_used" ] || fail "no options_used in the output directory"
# the defaults the run read are listed too (the CFL number, the kernel, the PPE's free-surface threshold), "choose" defaults not
for want in "^-cfl 0.25$" "^-kernel cubic$" "^-isph_beta 0.9" "^-wall_rows 3$"; do grep -q -- "$want" "$OUT/isph/options_used" || fail "options_used lacks the default $want"; done
grep -q -- "^-t_end -1" "$OUT/isph/options_used" && fail "options_used lists -t_end -1 (a choose-default)"
timeout 120 $MPI $BIN -options_file "$OUT/isph/options_used" -output_dir "$OUT/isph_again" > "$OUT/isph_again.log" 2>&1 || fail "-options_file options_used: status $?"
cmp -s "$OUT/isph/probes.csv" "$OUT/isph_again/probes.csv" || fail "the run repeated from options_used differs (probes.csv)"
grep -q '"version": "' "$OUT/isph/summary.json" && grep -q '"commit": "' "$OUT/isph/summary.json" || fail "summary.json has no version and commit"
$BIN -version > "$OUT/version.log" 2>&1 || fail "-version: status $?"
grep -q "^sphfsi [0-9]" "$OUT/version.log" && grep -q "^Petsc" "$OUT/version.log" && grep -q "^METIS" "$OUT/version.log" || fail "-version does not name sphfsi, PETSc and METIS: $(head -3 "$OUT/version.log")"
timeout 60 $MPI $BIN -options_file cases/dam_break.opts -fluid isph -t_end 0.001 -ksp_rtol 1e-4 -output_dir "$OUT/unprefixed" > "$OUT/unprefixed.log" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q "^sphfsi: error: .*-ksp_rtol 1e-4.*prefix -ppe_" "$OUT/unprefixed.log" || fail "unprefixed -ksp_rtol: status $rc, $(grep 'error' "$OUT/unprefixed.log" | head -1)"
# BoomerAMG's settings are defaults (ppe.c): a case file without them gets them (options_used), an
# option given keeps its value, and another preconditioner runs without a word about them
timeout 60 $MPI $BIN -case hydrostatic -fluid isph -dx 0.01 -max_steps 2 -output_interval 0 -progress_every 0 -ppe_pc_hypre_boomeramg_coarsen_type PMIS -output_dir "$OUT/amg" > "$OUT/amg.log" 2>&1 || fail "ISPH with -ppe_pc_hypre_boomeramg_coarsen_type PMIS: status $?"
for want in "^-ppe_pc_hypre_boomeramg_coarsen_type PMIS$" "^-ppe_pc_hypre_boomeramg_interp_type ext+i$" "^-ppe_pc_hypre_boomeramg_agg_nl 1$"; do grep -q -- "$want" "$OUT/amg/options_used" || fail "options_used lacks $want"; done
timeout 60 $MPI $BIN -case hydrostatic -fluid isph -dx 0.01 -max_steps 2 -output_interval 0 -progress_every 0 -ppe_pc_type gamg -output_dir "$OUT/gamg" > "$OUT/gamg.log" 2>&1 || fail "ISPH with -ppe_pc_type gamg: status $?"
grep -qi "warning\|boomeramg" "$OUT/gamg.log" && fail "-ppe_pc_type gamg: $(grep -i 'warning\|boomeramg' "$OUT/gamg.log" | head -1)"
grep -q "boomeramg" "$OUT/gamg/options_used" && fail "-ppe_pc_type gamg: options_used lists BoomerAMG options"
[ $bad -eq 0 ] && echo "user_path: the case file runs quietly in both schemes, options_used lists the defaults and repeats the ISPH run bit for bit, -version, -ksp_rtol rejected with the -ppe_ hint, BoomerAMG's defaults yield to options"
exit $bad
