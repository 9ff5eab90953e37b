#!/usr/bin/env bash
# A run too large for the memory stops at set-up, before its particles exist: status 2 and one line
# "sphfsi: error: ..." naming the particle count, the estimate per rank and the limit (no malloc
# trace, no kill by the kernel).  (a) the dam break at -dx 1e-6 (6.5e9 particles) within seconds;
# (b) an ordinary small run with -max_memory 50M; (c) the same run without it, and with -max_memory
# 8G, runs; (d) the -dx 1e-6 run under ulimit -v 4000000 (a subshell) ends with the one line too;
# (e) a malformed -max_memory is bad input.
#   tests/check_size_guard.sh "MPIEXEC -n P" OUTDIR         (SPHFSI: the program, default bin/sphfsi)
MPI=$1; OUT=$2
BIN=${SPHFSI:-bin/sphfsi}
mkdir -p "$OUT"
bad=0; n=0; msg=""
refused() { # name, words the line must hold (|-separated), arguments...: status 2, one line, no trace
  local name=$1 want=$2; shift 2
  n=$((n + 1))
  local t0=$SECONDS
  timeout 20 $MPI $BIN -progress_every 0 -output_dir "$OUT/$name" "$@" > "$OUT/$name.log" 2>&1
  local rc=$? el=$((SECONDS - t0)) line
  line=$(grep '^sphfsi: error: ' "$OUT/$name.log")
  if [ $rc -ne 2 ] || [ "$(grep -c '^sphfsi: error: ' "$OUT/$name.log")" -ne 1 ] || grep -qi "PETSC ERROR\|MPI_ABORT\|malloc\|Segmentation\|signal\|killed" "$OUT/$name.log"; then
    echo "FAIL $name ($*): status $rc after $el s, expected 2 and one line 'sphfsi: error: ...' ($OUT/$name.log)"; bad=$((bad + 1)); return
  fi
  IFS='|' read -ra words <<< "$want"
  for w in "${words[@]}"; do
    echo "$line" | grep -q -- "$w" || { echo "FAIL $name: the line lacks '$w': $line"; bad=$((bad + 1)); return; }
  done
  echo "ok   $name: status 2 after $el s: $line"
  msg="$msg $name ${el}s"
}
runs() { # name, arguments...: status 0
  local name=$1; shift
  n=$((n + 1))
  timeout 120 $MPI $BIN -progress_every 0 -output_dir "$OUT/$name" "$@" > "$OUT/$name.log" 2>&1
  local rc=$?
  if [ $rc -ne 0 ]; then echo "FAIL $name ($*): status $rc, expected 0 ($OUT/$name.log)"; bad=$((bad + 1)); else echo "ok   $name: runs"; fi
}
SMALL="-options_file cases/hydrostatic.opts -max_steps 2 -output_interval 0"
# the count (6.5e9: "at least" when the count stopped at the limit), the estimate per rank, the node's limit
refused a_dx_1e-6 "at least 6[0-9]\{9\} particles|per rank on|per rank a node allows|larger -dx|more nodes|-max_memory" -options_file cases/dam_break.opts -dx 1e-6
refused b_max_memory "particles at -dx|per rank on|50.0 MiB: -max_memory|-max_memory" $SMALL -max_memory 50M
runs    c_without $SMALL
runs    c_max_memory_8G $SMALL -max_memory 8G
n=$((n + 1)) # (d) in a subshell: its counts stay there, its status comes back
( ulimit -v 4000000; refused d_ulimit_v "at least 6[0-9]\{9\} particles|of address space per rank|ulimit -v|larger -dx" -options_file cases/dam_break.opts -dx 1e-6; exit $bad ) || bad=$((bad + 1))
refused e_malformed "-max_memory 8X is not a size" $SMALL -max_memory 8X
echo "size_guard: $((n - bad)) of $n checks passed (refused within:$msg)"
[ $bad -eq 0 ]
