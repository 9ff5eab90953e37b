#!/usr/bin/env bash
# ISPH vs WCSPH benchmark (not a test): the Martin & Moyce dam break (cases/dam_break.opts) to the
# same physical time with both fluid schemes at the same dx, for each dx = a/N in BENCH_CMP_DIVS
# (a = column width 0.05715 m). Reports steps, wall time, mean dt = t_end/steps, PPE iterations and
# the errors of summary.json against Martin & Moyce (surge front and column height, rms and max).
# ISPH runs with the default options and with each option set of BENCH_CMP_VARIANTS: with the
# defaults the ISPH dam break of this version does not survive to 0.3 s at dx < a/20 (a particle
# leaves through a wall; the table says "run failed"). Then ISPH with Fickian particle shifting
# (-isph_shift A for A in BENCH_SHIFT_A) against ISPH without, at a/BENCH_SHIFT_DIV.
# Writes out/bench/isph_vs_wcsph/isph_vs_wcsph.md (and one directory + log per run).
#
# Environment: MPIEXEC, MPIEXEC_FLAGS (as tools/bench.sh), BENCH_NP (ranks, 1),
#   BENCH_CMP_DIVS ("20 40 80"), BENCH_TEND (s, 0.3), BENCH_CMP_VARIANTS (further ISPH runs at every
#   dx, option sets separated by ';', "-isph_shift 1;-isph_gradient corrected"; empty = none),
#   BENCH_SHIFT_DIV (a/dx of the shifting comparison, 20; empty = skip),
#   BENCH_SHIFT_A (shifting coefficients, "1 6"), BENCH_TIMEOUT (s per run, 900),
#   BENCH_REUSE (1: keep the results of an earlier invocation instead of rerunning),
#   BENCH_ARGS (extra sphfsi options for every run), SPHFSI_REFDATA (reference data directory;
#   default ../shared/refdata, else the shared/refdata beside the repository this one was cloned from).
cd "$(dirname "$0")/.."
. tools/lib_runs.sh
NP=${BENCH_NP:-1}
OUT=out/bench/isph_vs_wcsph; mkdir -p $OUT
A=0.05715
DIVS=${BENCH_CMP_DIVS:-20 40 80}
TEND=${BENCH_TEND:-0.3}
VARIANTS=${BENCH_CMP_VARIANTS-"-isph_shift 1;-isph_gradient corrected"}
vname() { echo "$1" | sed 's/-isph_//g; s/[ -]//g'; }   # "-isph_shift 1" -> shift1
SHIFT_DIV=${BENCH_SHIFT_DIV-20}
SHIFT_A=${BENCH_SHIFT_A:-1 6}
TMO=${BENCH_TIMEOUT:-900}
[ -x bin/sphfsi ] || { echo "bin/sphfsi missing: run make first" >&2; exit 1; }
find_refdata

# run NAME DIV FLUID [extra options...]
run() {
  local name=$1 div=$2 fluid=$3; shift 3
  local dx; dx=$(python3 -c "print(f'{$A/$div:.7g}')")
  local dir=$OUT/$name
  [[ " $RAN " == *" $name "* ]] && return 0   # already run by this invocation
  RAN="$RAN $name"
  if [ -n "${BENCH_REUSE:-}" ] && { [ -f $dir/summary.json ] || [ -f $dir/FAILED ]; }; then
    echo "$name: reusing the earlier result in $dir" >&2; return 0
  fi
  local t0=$SECONDS
  run_sphfsi $dir $OUT/$name.log $TMO $NP -options_file cases/dam_break.opts -fluid $fluid -dx $dx -t_end $TEND \
    -output_interval 0 -progress_every 0 ${BENCH_ARGS:-} "$@"
  local rc=$?
  echo "$name: -fluid $fluid -dx $dx $*: exit $rc, $((SECONDS - t0)) s elapsed" >&2
}

RAN=""
for div in $DIVS; do
  run wcsph_a$div $div wcsph
  run isph_a$div $div isph
  IFS=';' read -ra vs <<< "$VARIANTS"
  for v in "${vs[@]}"; do run isph_a${div}_$(vname "$v") $div isph $v; done
done
if [ -n "$SHIFT_DIV" ]; then
  run isph_a$SHIFT_DIV $SHIFT_DIV isph
  for sa in $SHIFT_A; do run isph_a${SHIFT_DIV}_shift$sa $SHIFT_DIV isph -isph_shift $sa; done
fi

VN=""; IFS=';' read -ra vs <<< "$VARIANTS"; for v in "${vs[@]}"; do VN="$VN;$(vname "$v")=$v"; done
python3 - "$OUT" "$TEND" "$NP" "$DIVS" "$SHIFT_DIV" "$SHIFT_A" "$VN" <<'PY' | tee $OUT/isph_vs_wcsph.md
import json, os, sys
out, tend, np_, divs, sdiv, sas = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4].split(), sys.argv[5], sys.argv[6].split()
variants = [v.split("=", 1) for v in sys.argv[7].split(";") if v]

def load(name):
    d = f"{out}/{name}"
    if os.path.exists(f"{d}/FAILED") or not os.path.exists(f"{d}/summary.json"):
        rc = open(f"{d}/FAILED").read().strip() if os.path.exists(f"{d}/FAILED") else "?"
        why, t = "", "?"
        try:
            for line in open(f"{out}/{name}.log"):
                if "left the domain" in line: why = "a particle left the domain"
                elif "did not converge" in line: why = "PPE did not converge: " + line.split("KSP reason ")[-1].split(" after")[0]
            t = open(f"{d}/probes.csv").read().split()[-1].split(",")[0]
            t = f"{float(t):.3f}"
        except (OSError, ValueError, IndexError): pass
        return {"failed": f"exit {rc} at t = {t} s" + (f": {why}" if why else ""), "name": name}
    s = json.load(open(f"{d}/summary.json"))
    try: s["cpu_s"] = sum(map(float, open(f"{d}/cpu_s").read().split()[-2:]))
    except (OSError, ValueError): s["cpu_s"] = float("nan")
    return s

pc = lambda e, k: f"{100 * e[k]:.1f}" if k in e else "-"
def its(s): return "-" if s.get("ksp_its_mean") is None else f"{s['ksp_its_mean']:.2f} ({s['ksp_its_max']})"
def row(s, label):
    if "failed" in s: return f"| {label} | run failed ({s['failed']}), see {out}/{s['name']}.log |"
    e = s.get("errors", {})
    return (f"| {label} | {s['particles']} | {s['steps']} | {tend / s['steps']:.3e} | {s['wall_s']:.2f} | "
            f"{1e3 * s['wall_s'] / s['steps']:.2f} | {s['cpu_s']:.2f} | {its(s)} | {pc(e, 'front_rel_err_rms')} | {pc(e, 'front_rel_err_max')} | "
            f"{pc(e, 'height_rel_err_rms')} | {pc(e, 'height_rel_err_max')} | {s['mass_rel_drift']:.1e} |")

hdr = ("| run | particles | steps | dt mean (s) | wall (s) | wall/step (ms) | CPU (s) | PPE its/step mean (max) | "
       "front err rms % | front err max % | height err rms % | height err max % | mass drift |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|")
print(f"Dam break (cases/dam_break.opts) to t = {tend} s, {np_} rank(s); errors against Martin & Moyce 1952 (summary.json); "
      "wall = time loop (summary.json wall_s), CPU = user + system seconds of the whole run\n")
print(hdr)
pairs = []
for div in divs:
    w = load(f"wcsph_a{div}")
    print(row(w, f"WCSPH a/{div}"))
    for name, label in [(f"isph_a{div}", f"ISPH a/{div}")] + [(f"isph_a{div}_{n}", f"ISPH a/{div}, {o}") for n, o in variants]:
        i = load(name); print(row(i, label)); pairs.append((div, label, w, i))
print("\n| dx | particles | ISPH run | steps WCSPH/ISPH | wall WCSPH/ISPH | CPU WCSPH/ISPH | wall per step ISPH/WCSPH | front rms err WCSPH / ISPH % |\n|---|---|---|---|---|---|---|---|")
for div, label, w, i in pairs:
    if "failed" in w or "failed" in i: print(f"| a/{div} | | {label} | run failed | | | | |"); continue
    ew, ei = w.get("errors", {}), i.get("errors", {})
    print(f"| a/{div} = {w['dx']:.5g} | {w['particles']} | {label} | {w['steps'] / i['steps']:.1f} | **{w['wall_s'] / i['wall_s']:.2f}** | {w['cpu_s'] / i['cpu_s']:.2f} | "
          f"{(i['wall_s'] / i['steps']) / (w['wall_s'] / w['steps']):.1f} | {pc(ew, 'front_rel_err_rms')} / {pc(ei, 'front_rel_err_rms')} |")
if sdiv:
    print(f"\nISPH particle shifting (-isph_shift A) at a/{sdiv}, to t = {tend} s\n")
    print(hdr)
    print(row(load(f"isph_a{sdiv}"), "ISPH, no shifting"))
    for sa in sas: print(row(load(f"isph_a{sdiv}_shift{sa}"), f"ISPH, -isph_shift {sa}"))
PY
