#!/usr/bin/env bash
# The option names before the modules' prefixes (version 0.9.0, docs/history/options.md: -alpha is now
# -wcsph_alpha, -c0 -fluid_c0, ...): an old name works on with PETSc's one-line deprecation note, one
# per old name used, and gives the run of its new name bit for bit (probes.csv); given both names the
# new one wins; an ISPH run accepts WCSPH's old -alpha as it does -wcsph_alpha; a checkpoint that
# holds the old names (an earlier version's) restarts as one with the new names does, without an
# "options differ" warning.
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT"
bad=0
fail() { echo "old_names: $*"; bad=1; }
BIN="${BINDIR:-bin}"/sphfsi
RUN="$BIN -case dam_break -dx 0.004 -t_end 0.02 -probe_interval 0.002 -progress_every 0 -wcsph_shift 1"
NEW="-wcsph_alpha 0.2 -wcsph_delta 0.05 -fluid_xsph 0.3 -fluid_c0 30 -fluid_start_jitter 0.05 -fluid_shift_correct"
OLD="-alpha 0.2 -delta 0.05 -xsph 0.3 -c0 30 -start_jitter 0.05 -shift_correct"
timeout 120 $MPI $RUN $NEW -checkpoint_interval 0.01 -output_dir "$OUT/new" > "$OUT/new.log" 2>&1 || fail "new names: status $?"
timeout 120 $MPI $RUN $OLD -output_dir "$OUT/old" > "$OUT/old.log" 2>&1 || fail "old names: status $?"
timeout 120 $MPI $RUN $NEW -alpha 0.5 -c0 50 -output_dir "$OUT/both" > "$OUT/both.log" 2>&1 || fail "old and new names: status $?"
cmp -s "$OUT/new/probes.csv" "$OUT/old/probes.csv" || fail "the old names give another run than the new ones (probes.csv)"
cmp -s "$OUT/new/probes.csv" "$OUT/both/probes.csv" || fail "given both names, the new ones do not win (probes.csv)"
grep -q "DEPRECATION" "$OUT/new.log" && fail "the new names print a deprecation note"
[ "$(grep -c "DEPRECATION" "$OUT/old.log")" -eq 6 ] || fail "6 old names, $(grep -c "DEPRECATION" "$OUT/old.log") deprecation lines (one each expected)"
for pair in alpha:wcsph_alpha delta:wcsph_delta xsph:fluid_xsph c0:fluid_c0 start_jitter:fluid_start_jitter shift_correct:fluid_shift_correct; do
  grep -q "the option -${pair%%:*} is deprecated as of version .* Please use the option -${pair#*:} instead" "$OUT/old.log" || fail "no note for -${pair%%:*} -> -${pair#*:}"
done
grep -q "^-wcsph_alpha 0.2$" "$OUT/old/options_used" && ! grep -q "^-alpha " "$OUT/old/options_used" || fail "options_used of the old names' run does not list them by their new names"
# an ISPH run: -alpha (now -wcsph_alpha) belongs to the other scheme and passes, as before
timeout 120 $MPI $BIN -case dam_break -dx 0.004 -fluid isph -max_steps 2 -progress_every 0 -alpha 0.2 -output_dir "$OUT/isph" > "$OUT/isph.log" 2>&1 || fail "ISPH with -alpha: status $?, $(grep -m1 error "$OUT/isph.log")"
# a checkpoint of an earlier version: its options by the old names
for d in ck_new ck_old; do cp -r "$OUT/new" "$OUT/$d"; done
python3 - "$OUT/ck_old/checkpoint.h5" <<'PY' || fail "cannot rewrite the checkpoint's options"
import re, sys
import h5py, numpy as np
old = {"wcsph_alpha": "alpha", "wcsph_delta": "delta", "fluid_xsph": "xsph", "fluid_c0": "c0", "fluid_start_jitter": "start_jitter", "fluid_shift_correct": "shift_correct"}
with h5py.File(sys.argv[1], "r+") as f:
    s = f.attrs["options"]
    s = s.decode() if isinstance(s, bytes) else str(s)
    t = re.sub(r"(?<!\S)-(" + "|".join(old) + r")(?!\S)", lambda m: "-" + old[m.group(1)], s)
    assert t != s and "-alpha 0.2" in t, t
    del f.attrs["options"]
    f.attrs.create("options", np.bytes_(t.encode()))
PY
for d in ck_new ck_old; do
  timeout 120 $MPI $BIN -restart "$OUT/$d/checkpoint.h5" -t_end 0.03 > "$OUT/$d.log" 2>&1 || fail "restart $d: status $?"
done
cmp -s "$OUT/ck_new/probes.csv" "$OUT/ck_old/probes.csv" || fail "the restart of the checkpoint with the old names differs from the new names' (probes.csv)"
[ "$(grep -c "DEPRECATION" "$OUT/ck_old.log")" -eq 6 ] || fail "the restart with the old names: $(grep -c "DEPRECATION" "$OUT/ck_old.log") deprecation lines, 6 expected"
grep -q "options differ" "$OUT/ck_old.log" "$OUT/ck_new.log" && fail "restart: $(grep -h -m1 'options differ' "$OUT/ck_old.log" "$OUT/ck_new.log")"
[ $bad -eq 0 ] && echo "old_names: 6 old option names give the new names' run bit for bit with one deprecation line each, the new name wins over the old, ISPH accepts -alpha, a checkpoint with the old names restarts bit for bit like one with the new"
exit $bad
