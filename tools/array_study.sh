#!/usr/bin/env bash
# The periodic-array validations of issue 48 (docs/geometry.md): Stokes flow through a square array of
# cylinders (2D, against Sangani & Acrivos 1982; cases/boxes/cylinder_array.opts) or a simple cubic
# array of spheres (3D, against Zick & Homsy 1982; cases/boxes/sphere_array.opts), one cell of side
# L = 0.1 m at L/dx in NS.  Prints one row per run (the drag against the table at phi and at the
# lattice's phi, wall time) and the observed order of each series (tools/array_study_table.py).
#   tools/array_study.sh cylinder|sphere OUTDIR [NS] [PHIS] [FLUIDS]
#     cylinder defaults: "20 40 80" "0.1 0.2" "wcsph isph";  sphere: "10 20 30" "0.064 0.216" "wcsph"
# JOBS runs at a time (default 2 for cylinders, 1 for spheres), each on NP (default 1) ranks of BIN
# (default bin/sphfsi).
SHAPE=$1
case "$SHAPE" in
  cylinder) DNS="20 40 80"; DPHIS="0.1 0.2"; DFLUIDS="wcsph isph"; DJOBS=2 ;;
  sphere)   DNS="10 20 30"; DPHIS="0.064 0.216"; DFLUIDS="wcsph"; DJOBS=1 ;;
  *) echo "usage: $0 cylinder|sphere OUTDIR [NS] [PHIS] [FLUIDS]" >&2; exit 2 ;;
esac
OUT=${2:-out/${SHAPE}_array}; NS=${3:-$DNS}; PHIS=${4:-$DPHIS}; FLUIDS=${5:-$DFLUIDS}
cd "$(dirname "$0")/.." || exit 2
mkdir -p "$OUT"
# Open MPI binds rank 0 of every mpiexec to core 0 (at most 2 ranks a job): jobs run side by side
# would share that core (each had half of it), so none is bound here
FLAGS=${MPIEXEC_FLAGS-$(${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte" && echo --oversubscribe --bind-to none)}
one() { # fluid n phi: the body's radius from phi; run to steady flow (about 8 settling times)
  local f=$1 n=$2 phi=$3 d="$OUT/${1}_${3}_$2" a t body
  if [ "$SHAPE" = cylinder ]; then
    a=$(python3 -c "import math; print(0.1 * math.sqrt($phi / math.pi))")
    t=$(python3 -c "print(4000 if $phi < 0.15 else 2400)"); body="-cylinder_1 0.05,0.05,$a"
  else
    a=$(python3 -c "import math; print(0.1 * (3 * $phi / (4 * math.pi)) ** (1 / 3))")
    t=$(python3 -c "print(8000 if $phi < 0.1 else 3000)"); body="-sphere_1 0.05,0.05,0.05,$a"
  fi
  [ -f "$d/summary.json" ] && grep -q '"completed"' "$d/summary.json" && return
  ${MPIEXEC:-mpiexec} $FLAGS -n "${NP:-1}" "${BIN:-bin/sphfsi}" -options_file "cases/boxes/${SHAPE}_array.opts" -fluid "$f" -dx "$(python3 -c "print(0.1 / $n)")" $body -t_end "$t" -output_interval "$t" -progress_every 0 -overwrite -output_dir "$d" > "$d.log" 2>&1
}
for phi in $PHIS; do for f in $FLUIDS; do for n in $NS; do
  while [ "$(jobs -rp | wc -l)" -ge "${JOBS:-$DJOBS}" ]; do wait -n; done
  one "$f" "$n" "$phi" &
done; done; done
wait
python3 tools/array_study_table.py "$OUT" "$NS" "$PHIS" "$FLUIDS" "$SHAPE"
