#!/usr/bin/env bash
# The sphere-array validation (issue 48 item 4, docs/geometry.md): cases/boxes/sphere_array.opts
# (Stokes flow through a simple cubic array of spheres) at phi = 0.064 and 0.216, L/dx = 10, 20, 30;
# prints one row per run (K against Zick & Homsy 1982 at phi and at the lattice's phi, wall time) and
# the observed order of each series.
#   tools/sphere_array_study.sh OUTDIR [NS] [PHIS] [FLUIDS]     (defaults "10 20 30" "0.064 0.216" "wcsph")
# JOBS (default 1) runs at a time, each on NP (default 1) ranks, of BIN (default bin/sphfsi).
OUT=${1:-out/sphere_array}; NS=${2:-10 20 30}; PHIS=${3:-0.064 0.216}; FLUIDS=${4:-wcsph}
cd "$(dirname "$0")/.." || exit 2
mkdir -p "$OUT"
FLAGS=${MPIEXEC_FLAGS-$(${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte" && echo --oversubscribe)}
one() { # fluid n phi
  local f=$1 n=$2 phi=$3 d="$OUT/${1}_${3}_$2"
  local a; a=$(python3 -c "import math; print(0.1 * (3 * $phi / (4 * math.pi)) ** (1 / 3))")
  local t; t=$(python3 -c "print(8000 if $phi < 0.1 else 3000)") # 8 settling times
  [ -f "$d/summary.json" ] && grep -q '"completed"' "$d/summary.json" && return
  ${MPIEXEC:-mpiexec} $FLAGS -n "${NP:-1}" "${BIN:-bin/sphfsi}" -options_file cases/boxes/sphere_array.opts -fluid "$f" -dx "$(python3 -c "print(0.1 / $n)")" -sphere_1 "0.05,0.05,0.05,$a" -t_end "$t" -output_interval "$t" -progress_every 0 -overwrite -output_dir "$d" > "$d.log" 2>&1
}
for phi in $PHIS; do
  for f in $FLUIDS; do
    for n in $NS; do # JOBS at a time
      while [ "$(jobs -rp | wc -l)" -ge "${JOBS:-1}" ]; do wait -n; done
      one "$f" "$n" "$phi" &
    done
  done
done
wait
python3 tools/array_study_table.py "$OUT" "$NS" "$PHIS" "$FLUIDS" sphere
