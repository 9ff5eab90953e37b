#!/usr/bin/env bash
# make install PREFIX=...: the installed program runs an installed case file from another directory
# and finds the installed reference data (summary.json has the dam break's errors).
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT/elsewhere"; OUT=$(cd "$OUT" && pwd)
make --no-print-directory install PREFIX="$OUT/prefix" > "$OUT/install.log" 2>&1 || { echo "install: make install failed: $(tail -2 "$OUT/install.log")"; exit 1; }
( cd "$OUT/elsewhere" && timeout 120 $MPI "$OUT/prefix/bin/sphfsi" -options_file "$OUT/prefix/share/sphfsi/cases/dam_break.opts" -t_end 0.02 -progress_every 0 -output_dir run > run.log 2>&1 ) || { echo "install: the installed program failed: $(tail -2 "$OUT/elsewhere/run.log")"; exit 1; }
grep -q '"front_rel_err_rms": [0-9]' "$OUT/elsewhere/run/summary.json" || { echo "install: the installed program did not find the installed reference data"; exit 1; }
echo "install: make install PREFIX=$OUT/prefix; the installed sphfsi runs an installed case from another directory with the installed reference data"
