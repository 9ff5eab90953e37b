#!/usr/bin/env bash
# make install PREFIX=...: the installed program runs an installed case file from another directory
# and finds the installed reference data (summary.json has the dam break's errors).
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT/elsewhere"; OUT=$(cd "$OUT" && pwd)
make --no-print-directory install PREFIX="$OUT/prefix" > "$OUT/install.log" 2>&1 || { echo "install: make install failed: $(tail -2 "$OUT/install.log")"; exit 1; }
( cd "$OUT/elsewhere" && timeout 120 $MPI "$OUT/prefix/bin/sphfsi" -options_file "$OUT/prefix/share/sphfsi/cases/dam_break.opts" -t_end 0.02 -progress_every 0 -output_dir run > run.log 2>&1 ) || { echo "install: the installed program failed: $(tail -2 "$OUT/elsewhere/run.log")"; exit 1; }
grep -q '"front_rel_err_rms": [0-9]' "$OUT/elsewhere/run/summary.json" || { echo "install: the installed program did not find the installed reference data"; exit 1; }
echo "install: make install PREFIX=$OUT/prefix; the installed sphfsi runs an installed case from another directory with the installed reference data"

# The library (issue 54): a program of one's own, cases/user_scene/ copied outside the source tree,
# built against the installed prefix with nothing but pkg-config, run on 2 ranks.  Its scene shakes a
# plate's base by A (1 - cos w t) at about a fifth of the plate's first bending frequency: the base
# follows the prescribed motion to the drift's first-order error (w dt ~ 4e-4, bound 1e-3 of 2 A),
# and the tip lags the rising base (tip_rel < 0) by less than 0.2 A (a mass on a spring shaken at
# r = w / w_1 ~ 0.21: 1.57 r^2 / (1 - r^2) A ~ 0.07 A steady, at most twice that with the start's
# transient; 1.57 the cantilever's participation factor at its tip).
USER=$(mktemp -d); trap 'rm -rf "$USER"' EXIT
cp -r cases/user_scene/. "$USER/"
( cd "$USER" && PKG_CONFIG_PATH="$OUT/prefix/lib/pkgconfig" make > build.log 2>&1 ) || { echo "install: the user's scene did not build against the installed prefix: $(tail -3 "$USER/build.log")"; exit 1; }
( cd "$USER" && timeout 120 $MPI ./shaken_plate -options_file shaken_plate.opts -progress_every 0 > run.log 2>&1 ) || { echo "install: the user's program failed: $(tail -3 "$USER/run.log")"; exit 1; }
python3 - "$USER/out/shaken_plate" <<'PY' || exit 1
import csv, json, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/probes.csv")))
s = json.load(open(d + "/summary.json"))
A = 0.002
last = rows[-1]
base_err = abs(float(last["base_y"]) - float(last["base_exact"])) / (2 * A)
lo, hi = s["errors"]["tip_rel_min_over_A"], s["errors"]["tip_rel_max_over_A"]
ok = s["status"] == "completed" and s["ranks"] == 2 and base_err < 1e-3 and lo < 0 and max(-lo, hi) < 0.2
print(f"install: the user's scene out of tree (pkg-config sphfsi, 2 ranks): base {float(last['base_y']):.6g} m against {float(last['base_exact']):.6g} (error {base_err:.1e} of 2 A, bound 1e-3); tip relative to the base {lo:.3f} .. {hi:.3f} A (bound 0.2 A, lagging first) {'ok' if ok else 'FAILED'}")
sys.exit(0 if ok else 1)
PY
