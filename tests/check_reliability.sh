#!/usr/bin/env bash
# Reliability on a cluster (issue 8), through the program as a batch job runs it:
#  - SIGTERM to one rank mid-run: all ranks stop after the step, write a checkpoint, say so, exit 3;
#    the restart completes (exit 0) and its probes.csv equals the uninterrupted run's, byte for byte;
#    a restart with another physics option (-wcsph_alpha) says so;
#  - -max_wall_time: the same by itself, stopping within the limit;
#  - faults exit 4 with what, where and when, and a finite, restartable last good state:
#    a -dt far too large (particle leaves the domain), the pressure solve not converging (ISPH,
#    DIVERGED_ITS; with a -ppe_ksp_rtol looser than the default, a hint says so), the time step below
#    -dt_min; last_good.xmf (and particles.xmf after a restart) name datasets of the files with
#    their shapes;
#  - a rank that fails at start (it cannot see the output directory, as on nodes without a shared
#    file system; here: rank 1 runs in another directory) stops every rank with the message, no hang.
#   tests/check_reliability.sh "MPIEXEC -n P" OUTDIR
MPI=$1; OUT=$2
rm -rf "$OUT"; mkdir -p "$OUT"
fail() { echo "FAIL: $*"; exit 1; }
RUN="bin/sphfsi -case dam_break -dx 0.006 -probe_interval 0.002 -output_interval 0.2 -progress_every 1"
xmf_ok() { # every DataItem of an XDMF file names an existing dataset of its dimensions, or holds
  # that many values as text (a topology's list of points after the outflow removed particles)
  python3 -c "import h5py, math, os, sys, xml.etree.ElementTree as ET
d = os.path.dirname(sys.argv[1]); n = 0
for it in ET.parse(sys.argv[1]).iter('DataItem'):
    dims = tuple(int(x) for x in it.get('Dimensions').split())
    if it.get('Format') == 'XML':
        if len(it.text.split()) != math.prod(dims): sys.exit('%d values as text, the XDMF says %s' % (len(it.text.split()), dims))
        n += 1; continue
    f, ds = it.text.strip().split(':')
    shape = h5py.File(os.path.join(d, f))[ds].shape
    if shape[:len(dims)] != dims or any(x != 1 for x in shape[len(dims):]): sys.exit('%s:%s has shape %s, the XDMF says %s' % (f, ds, shape, dims))
    n += 1
sys.exit(0 if n else 'no DataItem')" "$1"
}
finite() { # every dataset of an HDF5 file is finite
  python3 -c "import h5py, numpy as np, sys
f = h5py.File(sys.argv[1]); bad = [k for k in f if not np.all(np.isfinite(f[k][:]))]
sys.exit('non-finite datasets: %s' % bad if bad else 0)" "$1"
}

# the uninterrupted reference
timeout 120 $MPI $RUN -t_end 1 -output_dir "$OUT/ref" > "$OUT/ref.log" 2>&1 || fail "reference run: status $?"

# SIGTERM to rank 1 (the batch system signals every task; one is enough: the ranks agree each step)
timeout 120 $MPI $RUN -t_end 5 -output_dir "$OUT/sig" > "$OUT/sig.log" 2>&1 &
job=$!
# signalled 0.3 s into the time loop: well before t = 1 (the restart's end) however fast the machine
for i in $(seq 1 600); do grep -q "^sphfsi: case" "$OUT/sig.log" 2>/dev/null && break; sleep 0.1; done
sleep 0.3
mpi=$(pgrep -P $job | head -n 1)
rank=$(pgrep -P "$mpi" | tail -n 1) # one rank's process
[ -n "$rank" ] || fail "no rank process found under mpiexec ($mpi)"
kill -TERM "$rank"
wait $job; rc=$?
[ $rc -eq 3 ] || fail "SIGTERM: status $rc, expected 3; $(tail -3 "$OUT/sig.log")"
grep -q "stopped at step .*received SIGTERM" "$OUT/sig.log" || fail "SIGTERM: no stop message"
grep -q '"status": "stopped"' "$OUT/sig/summary.json" || fail "SIGTERM: summary.json status is not stopped"
[ -f "$OUT/sig/checkpoint.h5" ] || fail "SIGTERM: no checkpoint"
tsig=$(grep -o "stopped at step [0-9]*, t = [0-9.e+-]*" "$OUT/sig.log")
timeout 120 $MPI $RUN -t_end 1 -output_dir "$OUT/sig" -restart "$OUT/sig/checkpoint.h5" > "$OUT/sig_restart.log" 2>&1 || fail "restart after SIGTERM: status $?"
cmp -s "$OUT/ref/probes.csv" "$OUT/sig/probes.csv" || fail "after SIGTERM and restart probes.csv differs from the uninterrupted run's"
xmf_ok "$OUT/sig/particles.xmf" || fail "particles.xmf after the restart does not match the snapshots"
! grep -q "options differ" "$OUT/sig_restart.log" || fail "restart with the same options: $(grep -m1 'options differ' "$OUT/sig_restart.log")"
timeout 60 $MPI $RUN -t_end 1 -wcsph_alpha 0.3 -max_steps 1 -output_dir "$OUT/opts" -restart "$OUT/sig/checkpoint.h5" > "$OUT/opts.log" 2>&1 || fail "restart with another -wcsph_alpha: status $?"
grep -q "options differ from the checkpointed run's: -wcsph_alpha (unset) -> 0.3;" "$OUT/opts.log" || fail "a changed -wcsph_alpha at restart is not reported"

# -max_wall_time by itself
# (0.5 s: the stop must come before t = 1, the restart's end, on an idle machine too)
timeout 120 $MPI $RUN -t_end 5 -max_wall_time 0.5 -output_dir "$OUT/wall" > "$OUT/wall.log" 2>&1; rc=$?
[ $rc -eq 3 ] || fail "-max_wall_time: status $rc, expected 3"
grep -q "stopped at step .*-max_wall_time 0.5" "$OUT/wall.log" || fail "-max_wall_time: no stop message"
python3 -c "import json,sys; w=json.load(open(sys.argv[1]))['wall_s']; sys.exit(0 if w < 1.0 else 'loop ran %.2f s, past -max_wall_time 0.5 (+0.5 s for a loaded machine)' % w)" "$OUT/wall/summary.json" || fail "-max_wall_time overrun"
timeout 120 $MPI $RUN -t_end 1 -output_dir "$OUT/wall" -restart "$OUT/wall/checkpoint.h5" > "$OUT/wall_restart.log" 2>&1 || fail "restart after -max_wall_time: status $?"
cmp -s "$OUT/ref/probes.csv" "$OUT/wall/probes.csv" || fail "after -max_wall_time and restart probes.csv differs from the uninterrupted run's"

# faults: status 4, what/where/when, a finite last good state one can restart from
fault() { # name, expected message (regex), options...
  local name=$1 want=$2; shift 2
  timeout 120 $MPI bin/sphfsi -progress_every 0 -output_dir "$OUT/$name" "$@" > "$OUT/$name.log" 2>&1; local rc=$?
  [ $rc -eq 4 ] || fail "$name: status $rc, expected 4"
  grep -q "sphfsi: FAULT: .*$want" "$OUT/$name.log" || fail "$name: no FAULT message matching '$want': $(grep -m1 FAULT "$OUT/$name.log")"
  grep -q '"status": "fault"' "$OUT/$name/summary.json" || fail "$name: summary.json status is not fault"
  finite "$OUT/$name/last_good.h5" || fail "$name: last_good.h5 is not finite"
  xmf_ok "$OUT/$name/last_good.xmf" || fail "$name: last_good.xmf does not match last_good.h5"
  ! grep -qi "nan\|inf" "$OUT/$name/probes.csv" || fail "$name: NaN/Inf in probes.csv"
}
fault dt_large "in step [0-9]* (from t = .*left the domain .*e.g. id [0-9]* (fluid) at (" -case hydrostatic -dx 0.01 -dt 0.01
timeout 120 $MPI bin/sphfsi -progress_every 0 -case hydrostatic -dx 0.01 -dt 0.0002 -t_end 0.05 -output_dir "$OUT/dt_large_restart" -restart "$OUT/dt_large/last_good.h5" > "$OUT/dt_large_restart.log" 2>&1 || fail "restart from last_good.h5 with a smaller -dt: status $?"
fault ksp "DIVERGED_ITS" -case hydrostatic -fluid isph -dx 0.01 -ppe_ksp_max_it 1
! grep -q "looser than the default" "$OUT/ksp.log" || fail "ksp: the hint on a loose -ppe_ksp_rtol at the default tolerance"
fault ksp_loose "DIVERGED_ITS" -case hydrostatic -fluid isph -dx 0.01 -ppe_ksp_max_it 1 -ppe_ksp_rtol 1e-3
grep -q "solved to -ppe_ksp_rtol 0.001, looser than the default 0.0001" "$OUT/ksp_loose.log" || fail "ksp_loose: no hint on the loose -ppe_ksp_rtol"
fault dt_floor "time step .* fell below its floor 1. s (-dt_min) at step 0, t = 0.*particle id [0-9]*" -case dam_break -dx 0.008 -dt_min 1

# a rank that fails at start: rank 1 runs elsewhere and cannot see the relative output directory
mkdir -p "$OUT/elsewhere"
here=$(pwd); args="-options_file $here/cases/hydrostatic.opts -dx 0.01 -progress_every 0 -output_dir $OUT/start"
mpirun=${MPI% -n *}
timeout 60 $mpirun -n 1 -wdir "$here" "$here/bin/sphfsi" $args : -n 1 -wdir "$here/$OUT/elsewhere" "$here/bin/sphfsi" $args > "$OUT/start.log" 2>&1; rc=$?
[ $rc -ne 0 ] && [ $rc -lt 124 ] || fail "a rank failing at start: status $rc (124 = hung until the timeout)"
grep -q "Rank 1 cannot see the output directory" "$OUT/start.log" || fail "a rank failing at start: no message"

echo "reliability: SIGTERM ($tsig) and -max_wall_time stop with status 3 and a checkpoint, restarts equal the uninterrupted run (probes.csv), a changed -wcsph_alpha is reported; faults (dt too large, DIVERGED_ITS, dt floor) status 4 with a finite last good state and its XDMF, a hint when -ppe_ksp_rtol was looser than the default; a rank failing at start stops all"
