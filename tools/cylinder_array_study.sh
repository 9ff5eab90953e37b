#!/usr/bin/env bash
# The cylinder-array validation (issue 48 item 4, docs/geometry.md): cases/boxes/cylinder_array.opts
# at phi = 0.1 and 0.2, L/dx = 20, 40, 80, both fluids; prints one row per run (drag against
# Sangani & Acrivos at phi and at the lattice's phi, wall time) and the observed order of each series.
#   tools/cylinder_array_study.sh OUTDIR [NS] [PHIS] [FLUIDS]     (defaults "20 40 80" "0.1 0.2" "wcsph isph")
# JOBS (default 2) runs at a time, each on NP (default 1) ranks.
OUT=${1:-out/cylinder_array}; NS=${2:-20 40 80}; PHIS=${3:-0.1 0.2}; FLUIDS=${4:-wcsph isph}
cd "$(dirname "$0")/.." || exit 2
mkdir -p "$OUT"
FLAGS=${MPIEXEC_FLAGS-$(${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte" && echo --oversubscribe)}
one() { # fluid n phi
  local f=$1 n=$2 phi=$3 d="$OUT/${1}_${3}_$2"
  local a; a=$(python3 -c "import math; print(0.1 * math.sqrt($phi / math.pi))")
  local t; t=$(python3 -c "print(4000 if $phi < 0.15 else 2400)")
  [ -f "$d/summary.json" ] && grep -q '"completed"' "$d/summary.json" && return
  ${MPIEXEC:-mpiexec} $FLAGS -n "${NP:-1}" bin/sphfsi -options_file cases/boxes/cylinder_array.opts -fluid "$f" -dx "$(python3 -c "print(0.1 / $n)")" -cylinder_1 "0.05,0.05,$a" -t_end "$t" -output_interval "$t" -progress_every 0 -overwrite -output_dir "$d" > "$d.log" 2>&1
}
for phi in $PHIS; do for f in $FLUIDS; do for n in $NS; do
  while [ "$(jobs -rp | wc -l)" -ge "${JOBS:-2}" ]; do wait -n; done
  one "$f" "$n" "$phi" &
done; done; done
wait
python3 tools/array_study_table.py "$OUT" "$NS" "$PHIS" "$FLUIDS" cylinder
