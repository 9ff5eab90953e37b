#!/usr/bin/env bash
# Reference data are found without depending on the current directory (issue "A batch job loses
# nothing", item 7), and a scene that cannot find its reference says so:
#  (a) the built program, run from another directory with $SPHFSI_REFDATA unset, finds the reference
#      data beside the source tree it was built from (summary.json has the dam break's errors);
#  (b) a copy of the program with the data in a folder refdata/ beside it reads them there (a
#      surge curve of its own, so the error differs from (a)'s);
#  (c) -refdata_dir /nonexistent: one warning line per missing file on stdout (rank 0 only), the
#      files listed in summary.json's reference_missing, no errors against them, and probes.csv
#      the same as in (a) and (b) (where the data are looked up changes no result).
#   tests/check_refdata.sh "MPIEXEC -n P" OUTDIR
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT/elsewhere" "$OUT/exe"; OUT=$(cd "$OUT" && pwd)
BIN=$(cd "${BINDIR:-bin}" && pwd)/sphfsi
SRC_REF=$(cd .. && pwd)/shared/refdata   # beside this checkout: what the build compiles in
REF=${SPHFSI_REFDATA:-$SRC_REF}          # run_tests.sh sets it for a clone without ../shared
unset SPHFSI_REFDATA
ARGS="-case dam_break -dx 0.005 -t_end 0.1 -output_interval 0 -progress_every 0"
bad=0
fail() { echo "refdata: $*"; bad=1; }
run() { # name, program, options...: run in $OUT/elsewhere, output in $OUT/elsewhere/name
  local name=$1 prog=$2; shift 2
  ( cd "$OUT/elsewhere" && timeout 120 $MPI "$prog" $ARGS -output_dir "$name" "$@" > "$name.log" 2>&1 ) || fail "$name: status $?: $(tail -2 "$OUT/elsewhere/$name.log")"
}
# errors and reference_missing of a run's summary.json, one line: "front=RMS|no missing=a.csv,b.csv"
summary() {
  python3 - "$OUT/elsewhere/$1/summary.json" <<'PY'
import json, sys
try:
    s = json.load(open(sys.argv[1]))
except (OSError, ValueError) as e:
    print(f"front=unreadable missing=({e})"); sys.exit()
print(f"front={s['errors'].get('front_rel_err_rms', 'no')} missing={','.join(s.get('reference_missing', ['(no member)']))}")
PY
}
SURGE=martin_moyce1952_surge_n2eq2_a2.25in__pysph.csv
HEIGHT=martin_moyce1952_height_n2eq2_a2.25in_table6__ocellaris.csv
[ -r "$REF/$SURGE" ] || { echo "refdata: no reference data beside the checkout ($SRC_REF) nor in \$SPHFSI_REFDATA: cannot test"; exit 1; }

# (a) the source tree's reference data, from another directory
if [ -d "$SRC_REF" ]; then
  run source "$BIN"
  got=$(summary source)
  [[ "$got" =~ ^front=[0-9.e-]+\ missing=$ ]] || fail "(a) run from $OUT/elsewhere with \$SPHFSI_REFDATA unset: $got (want front=RMS missing=): the source tree's $SRC_REF not found"
  grep -q "warning" "$OUT/elsewhere/source.log" && fail "(a) warns: $(grep warning "$OUT/elsewhere/source.log" | head -1)"
  a="the program finds $SRC_REF from another directory; "
else
  a="(no ../shared/refdata beside this checkout: the source-tree lookup not tested); "
fi

# (b) a copy of the program with refdata/ beside it, whose surge front is twice the experiment's:
# that folder comes before the source tree's
mkdir -p "$OUT/exe/refdata" && cp "$BIN" "$OUT/exe/sphfsi" && cp "$REF/$HEIGHT" "$OUT/exe/refdata/"
awk -F, -v OFS=, '/^[0-9]/ { $2 = 2 * $2 } 1' "$REF/$SURGE" > "$OUT/exe/refdata/$SURGE"
run beside "$OUT/exe/sphfsi"
got=$(summary beside)
[[ "$got" =~ ^front=[0-9.e-]+\ missing=$ ]] && [ "$got" != "$(summary source 2>/dev/null)" ] || fail "(b) $OUT/exe/sphfsi with $OUT/exe/refdata: $got (want front=RMS missing=, another RMS than (a)'s $(summary source 2>/dev/null))"

# (c) a folder without the data
run missing "$BIN" -refdata_dir /nonexistent
got=$(summary missing)
[ "$got" = "front=no missing=$SURGE,$HEIGHT" ] || fail "(c) -refdata_dir /nonexistent: summary.json $got (want front=no missing=$SURGE,$HEIGHT)"
for file in $SURGE $HEIGHT; do
  n=$(grep -c "^sphfsi: warning: reference data $file not found in /nonexistent.*summary.json has no errors against it" "$OUT/elsewhere/missing.log")
  [ "$n" = 1 ] || fail "(c) $n warning lines for $file on stdout (want 1): $(grep -i "warning\|$file" "$OUT/elsewhere/missing.log" | head -3)"
done
for run in beside missing; do
  [ -d "$OUT/elsewhere/source" ] || break
  cmp -s "$OUT/elsewhere/source/probes.csv" "$OUT/elsewhere/$run/probes.csv" || fail "probes.csv of run $run differs from run source"
done

[ $bad -eq 0 ] && echo "refdata: ${a}a copy reads the refdata/ beside it; -refdata_dir /nonexistent warns once per file (rank 0) and lists them in reference_missing; probes.csv the same"
exit $bad
