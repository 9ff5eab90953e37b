#!/usr/bin/env bash
# ParaView draws the particles of particles.xmf with the reader it picks itself (OpenDataFile:
# Xdmf3, the GUI's first choice) and with the legacy XDMF reader: short runs in 2D (dam break),
# 3D (SPHERIC Test 2 at dx = 0.05 m), a fault's last_good.xmf, and 2D with an outflow that removes
# particles (then the XDMF lists the points as text, not by the snapshot's ids); for each file and
# reader at the last time, N points, N cells (N: the particles of the HDF5 file) and a render of the
# default representation that is not blank (tools/paraview_check.py).  Skipped without pvbatch, or
# without a display or xvfb-run.
#   tests/check_paraview.sh "MPIEXEC -n P" OUTDIR
MPI=$1; OUT=$2
BIN="${BINDIR:-bin}"/sphfsi
here=$(cd "$(dirname "$0")/.." && pwd)
command -v pvbatch > /dev/null || { echo "paraview: skipped (pvbatch not installed; Debian: apt-get install paraview xvfb)"; exit 0; }
if [ -n "${DISPLAY:-}" ]; then PV=(pvbatch)
elif command -v xvfb-run > /dev/null; then PV=(xvfb-run -a -s "-screen 0 640x480x24" pvbatch)
else echo "paraview: skipped (no display and no xvfb-run: Debian's pvbatch cannot render without one)"; exit 0; fi
rm -rf "$OUT"; mkdir -p "$OUT"
fail() { echo "paraview: FAIL: $*"; exit 1; }
run() { # name, options...
  local name=$1; shift
  timeout 120 $MPI $BIN -progress_every 0 "$@" -output_dir "$OUT/$name" > "$OUT/$name.log" 2>&1 || fail "$name run: status $? (tail: $(tail -2 "$OUT/$name.log"))"
}
run 2d -options_file cases/dam_break.opts -dx 0.01 -t_end 0.02 -output_interval 0.01
run 3d -options_file cases/spheric_test2.opts -dx 0.05 -t_end 0.01 -output_interval 0.005
run 2d_outflow -case boxes -dx 0.01 -tank_1 0,0.3,0,0.2 -tank_1_sides left -fluid_box_1 0,0,0.15,0.1 -outflow -domain -0.05,-0.05,0.3,0.3 -t_end 0.3 -output_interval 0.1
# a fault (the step below -dt_min at once): last_good.xmf over last_good.h5 (IOWriteXDMFOne)
timeout 120 $MPI $BIN -progress_every 0 -case dam_break -dx 0.01 -dt_min 1 -output_dir "$OUT/fault" > "$OUT/fault.log" 2>&1
[ $? -eq 4 ] || fail "fault run: not status 4 (tail: $(tail -2 "$OUT/fault.log"))"
args=()
for xmf in 2d/particles 3d/particles fault/last_good 2d_outflow/particles; do # the particles of the first and the last file
  n=($(python3 -c "import glob, h5py, sys; s = sorted(glob.glob(sys.argv[1] + '*.h5')); print(*(len(h5py.File(f)['id']) for f in (s[0], s[-1])))" "$OUT/$xmf")) || fail "$xmf: no HDF5 file"
  args+=("$OUT/$xmf.xmf" "${n[1]}")
done
[ "${n[1]}" -lt "${n[0]}" ] || fail "2d_outflow: no particle left (${n[0]} -> ${n[1]}), so the case does not test the XDMF's list of points"
# pvbatch under a fresh virtual display aborts now and then at start (tools/paraview_render.sh):
# another try then; status 1 is the check's verdict
for try in 1 2 3; do
  "${PV[@]}" "$here/tools/paraview_check.py" "$OUT/shot.png" "${args[@]}" > "$OUT/pvbatch.log" 2>&1; status=$?
  [ $status -le 1 ] && break
done
grep ': default \|: XDMFReader ' "$OUT/pvbatch.log"
[ $status -eq 1 ] && fail "a reader did not make one cell per particle or drew nothing (FAIL above)"
[ $status -eq 0 ] || fail "pvbatch status $status; last lines of $OUT/pvbatch.log: $(grep -v "^ *[0-9]* *0x" "$OUT/pvbatch.log" | tail -3)"
echo "paraview: particles.xmf of a 2D, a 3D and a 2D outflow run and a fault's last_good.xmf: the default reader ($(grep -o -m1 'default ([A-Za-z0-9]*' "$OUT/pvbatch.log" | cut -d'(' -f2)) and XDMFReader make one cell per particle and draw them"
