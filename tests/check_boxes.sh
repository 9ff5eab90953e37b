#!/usr/bin/env bash
# A case without C (issue 27): the dam break (both fluids) and the hydrostatic tank written as data
# (cases/boxes/*.opts, -case boxes) give the same particles and the same state as the built-in scenes
# after 0.05 s on the same ranks, bit for bit; and cases/dam_break_obstacle.opts (a case that is no
# built-in scene) starts and runs.
MPI=$1; OUT=$2
mkdir -p "$OUT"
bad=0
BIN="${BINDIR:-bin}"/sphfsi
same() { # name, built-in case file, boxes case file, options...
  local name=$1 builtin=$2 boxes=$3; shift 3
  timeout 300 $MPI $BIN -options_file "$builtin" "$@" -t_end 0.05 -output_interval 0.05 -progress_every 0 -output_dir "$OUT/${name}_builtin" > "$OUT/${name}_builtin.log" 2>&1 || { echo "boxes: $name built-in run failed"; bad=1; return; }
  timeout 300 $MPI $BIN -options_file "$boxes" "$@" -t_end 0.05 -output_interval 0.05 -progress_every 0 -output_dir "$OUT/${name}_boxes" > "$OUT/${name}_boxes.log" 2>&1 || { echo "boxes: $name boxes run failed"; bad=1; return; }
  local r; r=$(python3 tests/compare_snapshots.py "$OUT/${name}_builtin" "$OUT/${name}_boxes" 0) || { echo "boxes: $name differs from the built-in scene: $r"; bad=1; return; }
  echo "boxes: $name as the built-in scene: $r"
}
same dam_break_wcsph cases/dam_break.opts cases/boxes/dam_break.opts -fluid wcsph
same dam_break_isph cases/dam_break.opts cases/boxes/dam_break.opts -fluid isph
same hydrostatic_wcsph cases/hydrostatic.opts cases/boxes/hydrostatic.opts -fluid wcsph
timeout 300 $MPI $BIN -options_file cases/dam_break_obstacle.opts -t_end 0.02 -output_interval 0.01 -progress_every 0 -output_dir "$OUT/obstacle" > "$OUT/obstacle.log" 2>&1 || { echo "boxes: cases/dam_break_obstacle.opts failed: status $?"; bad=1; }
grep -q '"status": "completed"' "$OUT/obstacle/summary.json" 2>/dev/null || { echo "boxes: cases/dam_break_obstacle.opts did not complete"; bad=1; }
exit $bad
