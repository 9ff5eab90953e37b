#!/usr/bin/env bash
# Bit for bit: two builds of sphfsi give the same run.  Every case file (cases/*.opts and
# cases/boxes/*.opts, or those in CASES) runs 20 steps with a snapshot at every step on each number
# of ranks in NPS (default "1 2") with BIN_A and with BIN_B; probes.csv must be byte-equal (cmp) and
# every dataset of every snapshot equal (h5py, numpy.array_equal, NaN equal to NaN).
#   tools/bitcheck.sh BIN_A BIN_B OUTDIR        e.g. tools/bitcheck.sh /work/baseline/sphfsi bin/sphfsi out/bitcheck
# Environment: ARGS (options for both runs), ARGS_A / ARGS_B (for BIN_A / BIN_B only, e.g.
# ARGS_B="-size_guard_count 1"), CASEDIR_A (BIN_A reads its case files from this copy of the tree's
# cases/, e.g. an older version's, whose option names BIN_A knows: `git archive db9434c cases | tar -x
# -C /tmp/old`, CASEDIR_A=/tmp/old), STEPS (20), NPS ("1 2"), CASES (case files), TIMEOUT (s per run,
# 600), MPIEXEC, MPIEXEC_FLAGS.
# Prints one line per case and rank count (same / DIFFERENT / FAILED with why) and ends with
# "# bitcheck: N same, N different"; exit status 1 when any differs or fails.
A=$1; B=$2; OUT=$3
[ -x "$A" ] && [ -x "$B" ] && [ -n "$OUT" ] || { echo "usage: $0 BIN_A BIN_B OUTDIR" >&2; exit 2; }
cd "$(dirname "$0")/.." || exit 2
CASES=${CASES:-$(ls cases/*.opts cases/boxes/*.opts)}
FLAGS=${MPIEXEC_FLAGS-$(${MPIEXEC:-mpiexec} --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte" && echo --oversubscribe)}
same=0; diff=0
for c in $CASES; do
  name=$(echo "${c#cases/}" | sed 's|/|_|g; s|\.opts$||')
  for np in ${NPS:-1 2}; do
    d=$OUT/$name/np$np; rm -rf "$d"; mkdir -p "$d"
    why=""
    for v in a b; do
      bin=$A; extra=${ARGS_A:-}; file=${CASEDIR_A:+$CASEDIR_A/}$c; [ $v = b ] && { bin=$B; extra=${ARGS_B:-}; file=$c; }
      timeout "${TIMEOUT:-600}" ${MPIEXEC:-mpiexec} $FLAGS -n "$np" "$bin" -options_file "$file" ${ARGS:-} $extra -max_steps "${STEPS:-20}" -output_interval 1e-9 -progress_every 0 -output_dir "$d/$v" > "$d/$v.log" 2>&1
      rc=$?
      [ $rc -eq 0 ] || why="$why run $v exited $rc ($d/$v.log);"
    done
    if [ -z "$why" ]; then
      cmp -s "$d/a/probes.csv" "$d/b/probes.csv" || why="probes.csv differs;"
      why="$why$(python3 - "$d/a" "$d/b" <<'PY'
import glob, os, sys
import h5py, numpy as np
a, b = sys.argv[1], sys.argv[2]
fa = sorted(os.path.basename(f) for f in glob.glob(a + "/particles_*.h5"))
fb = sorted(os.path.basename(f) for f in glob.glob(b + "/particles_*.h5"))
if not fa or fa != fb:
    print(f" snapshots: {len(fa)} and {len(fb)};", end=""); sys.exit()
bad = []
for f in fa:
    with h5py.File(os.path.join(a, f)) as A, h5py.File(os.path.join(b, f)) as B:
        na, nb = [], []
        A.visit(lambda k: na.append(k) if isinstance(A[k], h5py.Dataset) else None)
        B.visit(lambda k: nb.append(k) if isinstance(B[k], h5py.Dataset) else None)
        if sorted(na) != sorted(nb):
            bad.append(f"{f}: datasets {sorted(set(na) ^ set(nb))}"); continue
        for k in na:
            x, y = A[k][()], B[k][()]
            nan = x.dtype.kind == "f" and y.dtype.kind == "f"
            if x.shape != y.shape or not np.array_equal(x, y, equal_nan=nan):
                bad.append(f"{f}:{k}")
if bad:
    print(f" {len(bad)} dataset(s) differ, first {bad[0]};", end="")
else:
    print("", end="")
    open(os.path.join(os.path.dirname(a), "snapshots_compared"), "w").write(f"{len(fa)}\n")
PY
)"
    fi
    if [ -z "$why" ]; then
      same=$((same + 1)); echo "same       $c on $np rank(s): probes.csv and $(cat "$d/snapshots_compared") snapshots"
      rm -rf "$d/a" "$d/b" # the snapshots are large; the logs stay
    else
      diff=$((diff + 1)); echo "DIFFERENT  $c on $np rank(s):$why"
    fi
  done
done
echo "# bitcheck: $same same, $diff different or failed ($A${ARGS_A:+ with $ARGS_A}${CASEDIR_A:+ (case files of $CASEDIR_A)} vs $B${ARGS_B:+ with $ARGS_B})"
[ $diff -eq 0 ]
