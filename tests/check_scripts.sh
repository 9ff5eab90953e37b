#!/usr/bin/env bash
# The scripts users and `make study`/`make bench` run parse: every tools/*.sh and tests/*.sh under
# `bash -n`, every tools/*.py compiled by Python (a comment that swallows a `case` line's end only
# shows when that branch of `make study` runs, hours later).
cd "$(dirname "$0")/.." || exit 2
bad=0; n=0
for f in tools/*.sh tests/*.sh; do n=$((n + 1)); bash -n "$f" || { echo "does not parse: $f"; bad=1; }; done
for f in tools/*.py tests/*.py; do
  [ -e "$f" ] || continue; n=$((n + 1))
  python3 -c "import sys; compile(open(sys.argv[1]).read(), sys.argv[1], 'exec')" "$f" || { echo "does not compile: $f"; bad=1; }
done
[ $bad = 0 ] && echo "scripts: $n shell and Python scripts parse"
exit $bad
