#!/usr/bin/env bash
# WCSPH dam break at a/40 to t = 0.15 s (walls clipped at p = 0, -wcsph_wall_clip, the default): the
# film the collapsing column leaves on the wall behind it stays off the wall.  Bound: every fluid
# centre inside the tank box (between the walls' inner faces, dx/2 in front of the first wall row) in
# every snapshot.  Without the clip (-wcsph_wall_clip 0) the wall's negative (extrapolated) pressure
# holds the film: a centre 0.24 dx inside the wall layer at t = 0.09 s here, up to 0.45 dx later in
# make hard's longer run (tools/hard_check.py checks the same box there).
set -e
MPI=$1; OUT=$2; shift 2
A=0.05715
$MPI bin/sphfsi -options_file cases/dam_break.opts -dx $(python3 -c "print(f'{$A/40:.9g}')") -tank_height 1.0 -t_end 0.15 -output_interval 0.01 -probe_interval 0 -output_dir "$OUT" -progress_every 0 "$@"
python3 - "$OUT" <<'PY'
import glob, json, sys
sys.path.insert(0, "tools")
from hard_check import snap, tank_box, box_clearance  # the tank box of make hard's dam-break check
snaps = sorted(glob.glob(sys.argv[1] + "/particles_*.h5"))
assert len(snaps) >= 15, f"{len(snaps)} snapshots"
dx = json.load(open(sys.argv[1] + "/summary.json"))["dx"]
box = tank_box(snap(snaps[0]), dx)
worst = (float("inf"), None)
for s in snaps:
    d = snap(s)
    c = box_clearance(d["x"][d["kind"] == 0], box, dx)
    if c.min() < worst[0]: worst = (c.min(), d["time"])
print(f"wall_clip: closest fluid centre to a wall face {worst[0]:+.2f} dx (t = {worst[1]:.3f} s) over {len(snaps)} snapshots (bound >= 0)")
assert worst[0] >= 0, "a fluid centre is inside a wall's particle layer"
PY
