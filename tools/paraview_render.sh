#!/usr/bin/env bash
# Render a run's snapshots with ParaView's pvbatch (Debian: apt-get install paraview; xvfb for a
# machine without a display).  Arguments: see tools/paraview_render.py.
#   tools/paraview_render.sh out/dam_break docs/dam_break_paraview 0.1 0.2 --field p
here=$(cd "$(dirname "$0")" && pwd)
command -v pvbatch > /dev/null || { echo "paraview_render: pvbatch not found (Debian: apt-get install paraview)" >&2; exit 1; }
run() {
  if [ -n "$DISPLAY" ]; then pvbatch "$here/paraview_render.py" "$@"
  elif command -v xvfb-run > /dev/null; then xvfb-run -a -s "-screen 0 1920x1080x24" pvbatch "$here/paraview_render.py" "$@"
  else pvbatch --force-offscreen-rendering "$here/paraview_render.py" "$@"; fi
}
# pvbatch under a fresh virtual display aborts now and then at start: try again
for try in 1 2 3; do run "$@" 2> /tmp/paraview_render.$$.err && { rm -f /tmp/paraview_render.$$.err; exit 0; }; done
grep -v "^\s*[0-9]* *0x" /tmp/paraview_render.$$.err | tail -5 >&2; rm -f /tmp/paraview_render.$$.err
exit 1
