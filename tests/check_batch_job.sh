#!/usr/bin/env bash
# What a cluster does to a batch job, and the files it leaves (issue 45, items 2, 3, 4 and 6):
#  - a full disk (a 2 MB tmpfs as -output_dir; root only, else skipped with a note): one line
#    "no space left on device writing FILE", status 5, summary.json io_error, the last checkpoint
#    whole and restartable; a truncated checkpoint or a snapshot given to -restart: one line, status 2;
#  - -restart FILE alone, from another directory: the scene and options come from the checkpoint,
#    output goes on beside it, -t_end given overrides; probes.csv equals an uninterrupted run's and
#    particles.xmf lists exactly the snapshots there, before and after; a restart into a new
#    -output_dir lists only the snapshots it has;
#  - output directories: a new run into an earlier run's refuses (status 2, one line) unless
#    -overwrite, which leaves none of the earlier run's files; a second run into a directory in use
#    stops (status 2); the lock of a killed run is taken over with a note;
#  - a signal during set-up stops it (status 3, summary.json stopped) instead of waiting for step 1;
#  - -help and --help list both fluids' and the pressure solver's options with their values and exit
#    0 without running or writing; -progress_every -1 is bad input.
#   tests/check_batch_job.sh "MPIEXEC -n P" OUTDIR
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd); BIN=$(pwd)/bin/sphfsi; HERE=$(pwd)
fail() { echo "FAIL: $*"; exit 1; }
RUN="-case dam_break -dx 0.006 -probe_interval 0.002 -output_interval 0.05 -progress_every 0 -t_end 0.2"
one_error() { # LOG, STATUS, EXPECTED STATUS, PATTERN: one error line, no trace
  [ "$2" -eq "$3" ] || fail "$1: status $2, expected $3: $(grep -m2 'error' "$1")"
  [ "$(grep -c '^sphfsi: error:' "$1")" -eq 1 ] || fail "$1: not one error line: $(grep 'error' "$1" | head -3)"
  grep -q "^sphfsi: error: .*$4" "$1" || fail "$1: the error does not say '$4': $(grep '^sphfsi: error' "$1")"
  ! grep -q "PETSC ERROR\|HDF5-DIAG" "$1" || fail "$1: a trace"
}
xmf_exact() { # DIR: particles.xmf names every particles_*.h5 in DIR, and only those
  python3 - "$1" <<'PY'
import glob, os, sys, xml.etree.ElementTree as ET
d = sys.argv[1]
named = {it.text.strip().split(':')[0] for it in ET.parse(d + '/particles.xmf').iter('DataItem')}
there = {os.path.basename(f) for f in glob.glob(d + '/particles_*.h5')}
if named != there: sys.exit('particles.xmf names %s; the directory has %s' % (sorted(named - there), sorted(there - named)))
PY
}

# the uninterrupted reference
timeout 120 $MPI $BIN $RUN -output_dir "$OUT/ref" > "$OUT/ref.log" 2>&1 || fail "reference run: status $?"

# 3. -restart alone, from elsewhere: a run stopped by -max_steps with a checkpoint, then continued
timeout 120 $MPI $BIN $RUN -max_steps 300 -checkpoint_interval 0.03 -output_dir "$OUT/cont" > "$OUT/cont.log" 2>&1 || fail "first half: status $?"
xmf_exact "$OUT/cont" || fail "the first half's particles.xmf"
mkdir -p "$OUT/elsewhere"
(cd "$OUT/elsewhere" && timeout 120 $MPI $BIN -restart "$OUT/cont/checkpoint.h5" > "$OUT/cont_restart.log" 2>&1) || fail "-restart alone: status $?: $(grep -m1 error "$OUT/cont_restart.log")"
cmp -s "$OUT/ref/probes.csv" "$OUT/cont/probes.csv" || fail "-restart alone: probes.csv differs from the uninterrupted run's"
xmf_exact "$OUT/cont" || fail "after -restart alone, particles.xmf"
grep -q '"restarted_from"' "$OUT/cont/summary.json" || fail "-restart alone: no summary.json beside the checkpoint"
[ ! -e "$OUT/elsewhere/out" ] || fail "-restart alone wrote into the current directory's out/"
# into a new directory: particles.xmf lists only what is there; -t_end given overrides the checkpoint's
timeout 120 $MPI $BIN -restart "$OUT/cont/checkpoint.h5" -output_dir "$OUT/moved" -t_end 0.25 > "$OUT/moved.log" 2>&1 || fail "restart into a new -output_dir: status $?"
xmf_exact "$OUT/moved" || fail "restart into a new -output_dir, particles.xmf"
grep -q '"t_end": 0.25' "$OUT/moved/summary.json" || fail "-t_end on the command line did not override the checkpoint's"

# 4. output directories
timeout 60 $MPI $BIN $RUN -output_dir "$OUT/ref" > "$OUT/reuse.log" 2>&1; rc=$?
one_error "$OUT/reuse.log" $rc 2 "holds an earlier run's output"
timeout 60 $MPI $BIN $RUN -t_end 0.06 -output_dir "$OUT/ref" -overwrite > "$OUT/overwrite.log" 2>&1 || fail "-overwrite: status $?"
xmf_exact "$OUT/ref" || fail "-overwrite left another run's snapshots"
[ "$(ls "$OUT"/ref/particles_*.h5 | wc -l)" -eq 2 ] || fail "-overwrite: $(ls "$OUT"/ref/particles_*.h5 | wc -l) snapshots, the new run wrote 2"
timeout 120 $MPI $BIN $RUN -t_end 5 -output_dir "$OUT/busy" > "$OUT/busy1.log" 2>&1 &
job=$!
for i in $(seq 1 600); do grep -q "^sphfsi: case" "$OUT/busy1.log" 2>/dev/null && break; sleep 0.05; done
timeout 60 $MPI $BIN $RUN -output_dir "$OUT/busy" -overwrite > "$OUT/busy2.log" 2>&1; rc=$?
one_error "$OUT/busy2.log" $rc 2 "is in use by another run (process [0-9]* on "
kill -KILL $(pgrep -P "$(pgrep -P $job | head -n 1)") 2>/dev/null; wait $job
timeout 60 $MPI $BIN $RUN -t_end 0.01 -output_dir "$OUT/busy" -overwrite > "$OUT/busy3.log" 2>&1 || fail "after the first run was killed: status $?"
grep -q "^sphfsi: note: .*sphfsi.lock was left by process [0-9]*, which no longer runs" "$OUT/busy3.log" || fail "the killed run's lock was not reported as taken over"
[ ! -e "$OUT/busy/sphfsi.lock" ] || fail "the lock stayed after the run"

# 2. I/O faults
timeout 60 $MPI $BIN -restart "$OUT/ref/particles_00001.h5" > "$OUT/snap_restart.log" 2>&1; rc=$?
one_error "$OUT/snap_restart.log" $rc 2 "is not an sphfsi checkpoint"
size=$(stat -c %s "$OUT/cont/checkpoint.h5"); head -c $((size / 2)) "$OUT/cont/checkpoint.h5" > "$OUT/truncated.h5"
timeout 60 $MPI $BIN -restart "$OUT/truncated.h5" > "$OUT/truncated.log" 2>&1; rc=$?
one_error "$OUT/truncated.log" $rc 2 "is damaged"
full="skipped (not root, or no tmpfs mount here)"
if [ "$(id -u)" = 0 ] && mkdir -p "$OUT/full" && mount -t tmpfs -o size=2m tmpfs "$OUT/full" 2>/dev/null; then
  timeout 120 $MPI $BIN $RUN -dx 0.0028575 -t_end 0.3 -output_interval 0.01 -checkpoint_interval 0.05 -output_dir "$OUT/full/run" > "$OUT/full.log" 2>&1; rc=$?
  cp -r "$OUT/full/run" "$OUT/full_run"; umount "$OUT/full"
  one_error "$OUT/full.log" $rc 5 "no space left on device writing $OUT/full/run/"
  grep -q '"status": "io_error"' "$OUT/full_run/summary.json" || fail "full disk: summary.json does not say io_error"
  timeout 120 $MPI $BIN -restart "$OUT/full_run/checkpoint.h5" -max_steps 1 -output_dir "$OUT/full_restart" > "$OUT/full_restart.log" 2>&1 || fail "full disk: the last checkpoint does not restart: status $?"
  full="status 5 at $(grep -o 'writing [^ ]*' "$OUT/full.log" | head -1 | sed 's|.*\/||'), checkpoint restartable"
fi

# 5. a signal during set-up (a 3D scene of ~0.9 M particles takes seconds to build): seen between its phases
timeout 120 $MPI $BIN -options_file cases/spheric_test2.opts -dx 0.01 -progress_every 0 -output_dir "$OUT/setup" > "$OUT/setup.log" 2>&1 &
job=$!
for i in $(seq 1 600); do [ -e "$OUT/setup/sphfsi.lock" ] && break; sleep 0.05; done # the lock: set-up has begun, the handlers are in
t0=$SECONDS
kill -TERM "$(pgrep -P "$(pgrep -P $job | head -n 1)" | tail -n 1)"
wait $job; rc=$?; setup_s=$((SECONDS - t0))
[ $rc -eq 3 ] || fail "SIGTERM during set-up: status $rc, expected 3: $(tail -2 "$OUT/setup.log")"
grep -q "^sphfsi: stopped: received SIGTERM during set-up" "$OUT/setup.log" || fail "SIGTERM during set-up: not seen in set-up: $(grep -m1 stopped "$OUT/setup.log")"
grep -q '"status": "stopped"' "$OUT/setup/summary.json" || fail "SIGTERM during set-up: summary.json does not say stopped"

# 6. -help
timeout 60 $MPI $BIN -options_file cases/dam_break.opts -help -output_dir "$OUT/help" > "$OUT/help.log" 2>&1 || fail "-help: status $?"
for o in -wcsph_shift -isph_shift -ppe_ksp_rtol -ppe_pc_type -wcsph_alpha -column_width -overwrite; do grep -q "^  $o " "$OUT/help.log" || grep -q "^  $o:" "$OUT/help.log" || fail "-help does not list $o"; done
! grep -q "steps in" "$OUT/help.log" || fail "-help ran the simulation"
[ ! -e "$OUT/help" ] || fail "-help created the output directory"
timeout 60 $MPI $BIN -options_file cases/dam_break.opts -fluid isph --help -output_dir "$OUT/help" > "$OUT/help2.log" 2>&1 || fail "--help: status $?"
grep -q "^  -wcsph_shift" "$OUT/help2.log" || fail "--help under ISPH does not list the WCSPH options"
timeout 60 $MPI $BIN -help > "$OUT/help3.log" 2>&1 || fail "-help without a case: status $?"
grep -q "NAME is one of: .*dam_break" "$OUT/help3.log" || fail "-help without a case does not name the scenes"
timeout 60 $MPI $BIN $RUN -progress_every -1 -output_dir "$OUT/neg" > "$OUT/neg.log" 2>&1; rc=$?
one_error "$OUT/neg.log" $rc 2 "-progress_every -1 must be >= 0"

echo "batch_job: -restart alone from elsewhere continues beside its checkpoint (probes equal, xmf exact); reuse refused, -overwrite clean, a busy directory refused, a killed run's lock taken over; a truncated checkpoint and a snapshot refused in one line; full disk: $full; SIGTERM in set-up stops it after ${setup_s} s; -help/--help list both fluids and -ppe_ and run nothing"
