#!/usr/bin/env bash
# summary.json stays valid JSON when a scene's error is not finite: the hydrostatic tank without
# gravity has a zero reference pressure, so its relative error is 0/0; it must read as null.
#   tests/check_summary_json.sh "MPIEXEC -n P" OUTDIR
set -e
MPI=$1; OUT=$2
rm -rf "$OUT"
$MPI ${BINDIR:-bin}/sphfsi -case hydrostatic -dx 0.01 -gravity 0,0 -t_end 0.01 -output_interval 0 -progress_every 0 -output_dir "$OUT"
python3 - "$OUT" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))  # fails on nan/inf tokens
e = s["errors"]
print(f"summary json: valid JSON; p_bottom_rel_err {e['p_bottom_rel_err']} (no gravity: 0/0), p_bottom_ref {e['p_bottom_ref']}")
assert e["p_bottom_rel_err"] is None, "a non-finite error must be written null"
assert e["p_bottom_ref"] == 0
PY
