# Shell functions shared by the study and benchmark scripts (sourced, not run).
#   find_refdata          export SPHFSI_REFDATA when it is unset and ../shared/refdata does not exist
#                         but the shared/refdata beside the repository this one was cloned from does
#                         (a clone elsewhere, e.g. in /tmp, still finds it); warns when none is found
#   run_sphfsi DIR LOG TIMEOUT NP [sphfsi options...]
#                         one run of $BIN/sphfsi (BIN default bin) on NP ranks with $MPIEXEC
#                         $MPIEXEC_FLAGS, under `timeout TIMEOUT`, output into DIR (emptied first),
#                         stdout+stderr into LOG.  Writes DIR/run.json: exit code, elapsed seconds of
#                         the whole run (set-up included), CPU seconds (user + system), the 1-minute
#                         load average before and after, the command line; DIR/FAILED holds the exit
#                         code of a run that did not exit 0.  Returns the run's exit code.

find_refdata() {
  if [ -z "${SPHFSI_REFDATA:-}" ] && [ ! -d ../shared/refdata ]; then
    local origin; origin=$(git config --get remote.origin.url 2>/dev/null)
    [ -n "$origin" ] && [ -d "$origin/../shared/refdata" ] && export SPHFSI_REFDATA=$(cd "$origin/../shared/refdata" && pwd)
  fi
  [ -n "${SPHFSI_REFDATA:-}" ] || [ -d ../shared/refdata ] || echo "warning: no reference data found (set SPHFSI_REFDATA): no errors in the tables" >&2
}

run_sphfsi() {
  local dir=$1 log=$2 tmo=$3 np=$4; shift 4
  rm -rf "$dir"; mkdir -p "$dir"
  local load0; load0=$(cut -d' ' -f1 /proc/loadavg)
  local t0; t0=$(date +%s.%N)
  local TIMEFORMAT="%U %S"   # CPU seconds (user, system) of the whole run, set-up included
  { time timeout "$tmo" ${MPIEXEC:-mpiexec} ${MPIEXEC_FLAGS:-} -n "$np" "${BIN:-bin}/sphfsi" "$@" -output_dir "$dir" > "$log" 2>&1 ; } 2> "$dir/cpu_s"
  local rc=$?
  local el; el=$(python3 -c "print(f'{$(date +%s.%N) - $t0:.2f}')")
  local cpu; cpu=$(awk '{printf "%.2f", $(NF-1) + $NF}' "$dir/cpu_s" 2>/dev/null)
  python3 - "$dir/run.json" "$rc" "$el" "${cpu:-null}" "$load0" "$(cut -d' ' -f1 /proc/loadavg)" "$np" "$*" <<'PY'
import json, sys
f, rc, el, cpu, l0, l1, np_, cmd = sys.argv[1:]
json.dump({"rc": int(rc), "elapsed_s": float(el), "cpu_s": None if cpu == "null" else float(cpu),
           "load_before": float(l0), "load_after": float(l1), "np": int(np_), "options": cmd}, open(f, "w"))
PY
  [ $rc -eq 0 ] || echo "$rc" > "$dir/FAILED"
  return $rc
}
