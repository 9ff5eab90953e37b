#!/usr/bin/env bash
# The test suite on 2 MPI ranks.  Ends with 'N passed, N failed'; exit status 1 on any failure.
#   tests/run_tests.sh [--unit-only]
cd "$(dirname "$0")/.."
NP=${NP_TEST:-2}
MPI="${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-} -n $NP"
PY=${PYTHON:-python3}
OUT=out/tests
mkdir -p "$OUT"
pass=0; fail=0; failed=()

run() { # name, command...
  local name=$1; shift
  local t0=$SECONDS
  if "$@" > "$OUT/$name.log" 2>&1; then
    pass=$((pass + 1)); echo "PASS $name ($((SECONDS - t0)) s): $(grep -E '^(#|[a-z0-9_ ]+:)' "$OUT/$name.log" | tail -n 1)"
  else
    fail=$((fail + 1)); failed+=("$name"); echo "FAIL $name ($((SECONDS - t0)) s); last lines of $OUT/$name.log:"; tail -n 15 "$OUT/$name.log" | sed 's/^/    /'
  fi
}

# Unit and parallel-machinery tests (C programs)
for t in "${BINDIR:-bin}"/test_*; do
  run "$(basename "$t")" $MPI "$t"
done

if [ "${1:-}" != "--unit-only" ]; then
  # Physics regression tests against analytic and experimental references
  run hydrostatic_wcsph bash tests/check_hydrostatic.sh "$MPI" "$OUT/hydrostatic_wcsph"
  run dam_break_wcsph_front bash tests/check_dam_break.sh "$MPI" "$OUT/dam_break_wcsph"
  # Bad input: clear message, non-zero status, no crash
  run bad_input bash tests/check_bad_input.sh "$MPI" "$OUT/bad_input"
fi

[ ${#failed[@]} -gt 0 ] && echo "failed: ${failed[*]}"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
