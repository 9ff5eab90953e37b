#!/bin/bash
# The batch recipe of docs/cluster.md ("A SLURM job that runs until done") under a real SLURM (issue 46).
#
#   tools/slurm_check.sh [WORKDIR]           with a SLURM running (SLURM_CONF, or tools/slurm_local.sh's)
#   tools/slurm_check.sh --setup [WORKDIR]   `make slurm`: as root, install slurm-wlm and munge if missing,
#                                            start tools/slurm_local.sh, check, stop what it started;
#                                            otherwise one line saying why it was skipped, status 0
#
# The recipe is taken from the doc's first bash block after the heading, and the mpirun variant
# from the second; only site values are replaced (ntasks, time, --signal, SPHFSI, OUT, the case
# line), each replacement must match exactly once, so a recipe that changes shape fails the check
# instead of testing something else.  A dam break (dx 8 mm, 2 tasks, checkpoints every 0.02 s):
#   a. an uninterrupted job (srun) to t = 1.5 s: the reference probes.csv;
#   b. the recipe (srun), plain scancel right after its first checkpoint, the stop made 5 s slow:
#      JobState CANCELLED, ExitCode 3:0, "received SIGTERM", a checkpoint after t = 0, not resubmitted;
#      the mpirun variant submitted again into the same directory, scancel --batch --signal=USR1
#      after its first new checkpoint: FAILED 3:0, "received SIGUSR1", resubmitted by itself; the
#      resubmitted job runs to the end: COMPLETED 0:0 and probes.csv equal to a's byte for byte;
#   c. into a new directory with t_end 1000: the recipe with --time=1 and no --signal hits its time
#      limit (stop 5 s slow): TIMEOUT 3:0, "received SIGTERM", resubmitted by itself; that job is
#      cancelled; the recipe with --time=1 --signal=USR1@10 gets SIGUSR1 before the limit: FAILED
#      3:0, "received SIGUSR1", resubmitted by itself; that job is cancelled; the chain's probes.csv
#      equals an uninterrupted job's of as many steps (-max_steps) byte for byte.
# Prints what SLURM recorded for each job, one summary line, and exits 1 on any failure.
set -u
REPO=$(cd "$(dirname "$0")/.." && pwd)
SETUP=0
if [ "${1:-}" = --setup ]; then SETUP=1; shift; fi
W=${1:-$REPO/out/slurm}
BIN=$REPO/bin/sphfsi
DOC=$REPO/docs/cluster.md
say() { echo "slurm_check: $*"; }

if [ $SETUP = 1 ]; then
  if [ "$(id -u)" != 0 ]; then echo "make slurm: skipped: it installs and starts SLURM, which needs root"; exit 0; fi
  if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
    if ! command -v apt-get >/dev/null; then echo "make slurm: skipped: SLURM is not installed and there is no apt-get to install it"; exit 0; fi
    mkdir -p "$REPO/out"
    say "installing slurm-wlm and munge (apt-get; log in out/slurm-apt.log)"
    if ! DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge > "$REPO/out/slurm-apt.log" 2>&1; then
      echo "make slurm: skipped: apt-get install slurm-wlm munge failed (out/slurm-apt.log)"; exit 0
    fi
  fi
  started=0
  if ! bash "$REPO/tools/slurm_local.sh" status 2>/dev/null | grep -q "^slurmctld: running"; then started=1; fi
  bash "$REPO/tools/slurm_local.sh" start || { echo "make slurm: FAIL: the local SLURM did not start"; exit 1; }
  eval "$(bash "$REPO/tools/slurm_local.sh" env)"
  bash "$0" "$W"; rc=$?
  [ $started = 1 ] && bash "$REPO/tools/slurm_local.sh" stop
  exit $rc
fi

[ -n "${SLURM_CONF:-}" ] || [ -f /etc/slurm/slurm.conf ] || eval "$(bash "$REPO/tools/slurm_local.sh" env)"
scontrol ping 2>/dev/null | grep -q "is UP" || { say "FAIL: no SLURM answers (tools/slurm_local.sh start)"; exit 1; }
[ -x "$BIN" ] || { say "FAIL: $BIN not built (make)"; exit 1; }
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi

rm -rf "$W"; mkdir -p "$W"; cd "$W" || exit 1
FAILS=0; PASSES=0
fail() { say "FAIL: $*"; FAILS=$((FAILS + 1)); }
pass() { say "ok: $*"; PASSES=$((PASSES + 1)); }
finish() {
  # every job this check submitted or saw resubmitted, should one still be queued or running
  [ -f "$W/jobs" ] && scancel $(sort -u "$W/jobs") 2>/dev/null
  if [ $FAILS = 0 ]; then echo "slurm: $PASSES checks passed, 0 failed (jobs' output in $W)"; exit 0; fi
  echo "slurm: $PASSES checks passed, $FAILS failed (jobs' output in $W)"; exit 1
}
trap 'say "interrupted"; FAILS=$((FAILS + 1)); finish' INT TERM

# --- the recipe, from the doc --------------------------------------------------------------------
python3 - "$DOC" "$W" <<'PY' || { fail "the recipe's blocks not found in docs/cluster.md"; finish; }
import sys
doc, w = sys.argv[1], sys.argv[2]
s = open(doc).read()
sec = s[s.index('### A SLURM job that runs until done'):]
blocks = []
while len(blocks) < 2:
    a = sec.index('```bash\n') + len('```bash\n'); b = sec.index('```', a)
    blocks.append(sec[a:b]); sec = sec[b + 3:]
open(w + '/recipe.sh', 'w').write(blocks[0])
open(w + '/recipe_mpirun_lines.sh', 'w').write(blocks[1])
PY
# variant NAME [mpirun] [--time=T] [--signal=S|--nosignal] [--case "OPTIONS"] [--out DIR]: a job script
variant() {
  REPO=$REPO python3 - "$W" "$@" <<'PY'
import os, re, sys
w, name, args = sys.argv[1], sys.argv[2], sys.argv[3:]
s = open(w + '/recipe.sh').read()
def once(pat, flags=re.M):
    n = len(re.findall(pat, s, flags))
    if n != 1: sys.exit('the recipe: %r matches %d times, not once' % (pat, n))
def sub(pat, rep, flags=re.M):
    global s
    once(pat, flags)
    s = re.sub(pat, lambda m: rep if isinstance(rep, str) else rep(m), s, flags=flags)
o = {'time': None, 'signal': None, 'case': None, 'out': None}
i = 0
while i < len(args):
    a = args[i]
    if a == 'mpirun': o['mpirun'] = 1
    elif a.startswith('--time='): o['time'] = a[7:]
    elif a.startswith('--signal='): o['signal'] = a
    elif a == '--nosignal': o['signal'] = ''
    elif a == '--case': i += 1; o['case'] = args[i]
    elif a == '--out': i += 1; o['out'] = args[i]
    i += 1
if o.get('mpirun'):
    m = open(w + '/recipe_mpirun_lines.sh').read()
    sig = re.search(r'^#SBATCH --signal=.*$', m, re.M).group(0)
    fn = re.search(r'^run\(\) \{.*?^\}$', m, re.M | re.S).group(0)
    sub(r'^#SBATCH --signal=.*$', sig)
    sub(r'^run\(\) \{.*\}[^\n]*$', fn)
sub(r'^#SBATCH --ntasks=\d+$', '#SBATCH --ntasks=2')
if o['time']: sub(r'^#SBATCH --time=[0-9:]+$', '#SBATCH --time=' + o['time'])
if o['signal'] == '': sub(r'^#SBATCH --signal=.*\n', '')
elif o['signal']:  # keep B: where the variant has it
    sub(r'^(#SBATCH --signal=(?:B:)?)USR1@\d+', lambda m: m.group(1) + o['signal'][len('--signal='):])
sub(r'^SPHFSI=\S+', 'SPHFSI=' + os.environ['REPO'])
sub(r'^OUT=\S+', 'OUT=' + o['out'])
sub(r'-options_file "\$SPHFSI/cases/elastic_gate\.opts"', o['case'])
open(w + '/' + name + '.sh', 'w').write(s)
PY
}

# --- helpers -------------------------------------------------------------------------------------
submit() { local j; j=$(sbatch --parsable "$@") || return 1; j=${j%%;*}; echo "$j" >> "$W/jobs"; echo "$j"; }
field() { scontrol show job "$1" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1; }
wait_running() { # JOB [seconds]
  local i; for i in $(seq 1 $((${2:-600} * 5))); do
    case $(field "$1" JobState) in RUNNING|COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) return 0 ;; esac
    sleep 0.2; done; return 1; }
wait_end() { # JOB [seconds]: until SLURM has ended it (the batch script has exited)
  local i; for i in $(seq 1 $((${2:-900} * 5))); do
    case $(field "$1" JobState) in COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|PREEMPTED|BOOT_FAIL|DEADLINE) return 0 ;; esac
    sleep 0.2; done; return 1; }
ckpt_id() { stat -c %i "$1/checkpoint.h5" 2>/dev/null || echo none; }
wait_new_ckpt() { # DIR OLD_INODE JOB: a checkpoint renamed into place since (while JOB runs)
  local i; for i in $(seq 1 12000); do
    [ "$(ckpt_id "$1")" != "$2" ] && [ "$(ckpt_id "$1")" != none ] && return 0
    case $(field "$3" JobState) in RUNNING|PENDING|CONFIGURING) ;; *) return 1 ;; esac
    sleep 0.05; done; return 1; }
ckpt_step() { python3 -c "import h5py,sys; print(int(h5py.File(sys.argv[1],'r').attrs['step']))" "$1/checkpoint.h5" 2>/dev/null || echo -1; }
resubmitted() { sed -n 's/^Submitted batch job \([0-9]*\).*/\1/p' "slurm-$1.out" 2>/dev/null | tail -n 1; }
# expect JOB LABEL STATE EXITCODE SIGNAL(-: none) RESUB(yes|no): what SLURM recorded and the output says
expect() {
  local j=$1 label=$2 st ec r
  wait_end "$j" || { fail "$label: job $j did not end"; return 1; }
  st=$(field "$j" JobState); ec=$(field "$j" ExitCode); r=$(resubmitted "$j")
  say "$label: job $j: JobState=$st ExitCode=$ec Reason=$(field "$j" Reason)${r:+, resubmitted as job $r}"
  local ok=1
  [ "$st" = "$3" ] || { fail "$label: JobState $st, expected $3"; ok=0; }
  [ "$ec" = "$4" ] || { fail "$label: ExitCode $ec, expected $4"; ok=0; }
  if [ "$5" != - ]; then
    grep -q "^sphfsi: stopped at step .*received $5\." "slurm-$j.out" || { fail "$label: no 'stopped at step ... received $5' in slurm-$j.out"; ok=0; }
    grep -q "^sphfsi: checkpoint written to" "slurm-$j.out" || { fail "$label: no 'checkpoint written' in slurm-$j.out"; ok=0; }
  fi
  if [ "$6" = yes ]; then [ -n "$r" ] || { fail "$label: not resubmitted"; ok=0; }
  else [ -z "$r" ] || { fail "$label: resubmitted (job $r), expected not"; ok=0; }; fi
  [ $ok = 1 ] && pass "$label"
  [ $ok = 1 ]
}

CASE_A="-case dam_break -dx 0.008 -probe_interval 0.002 -output_interval 0.05 -t_end 1.5"
CASE_C="-case dam_break -dx 0.008 -probe_interval 0.002 -output_interval 0.05 -t_end 1000"

variant b_srun --case "$CASE_A" --out "$W/b" || { fail "the recipe could not be adapted"; finish; }
variant b_mpirun mpirun --case "$CASE_A" --out "$W/b" || { fail "the mpirun variant could not be adapted"; finish; }
variant c_limit --time=00:01:00 --nosignal --case "$CASE_C" --out "$W/c" || { fail "the recipe could not be adapted"; finish; }
variant c_signal --time=00:01:00 --signal=USR1@10 --case "$CASE_C" --out "$W/c" || { fail "the recipe could not be adapted"; finish; }
say "SLURM $(sinfo -V 2>/dev/null | awk '{print $2}'), srun MPI types: $(srun --mpi=list 2>&1 | sed -n 's/^\s\+//p' | grep -v '^specific' | tr '\n' ' ')"

# --- a. the uninterrupted reference --------------------------------------------------------------
j=$(submit -J ref -n 2 --wrap "srun --mpi=pmix $BIN $CASE_A -checkpoint_interval 0.02 -progress_every 0 -output_dir $W/ref")
expect "$j" "a. uninterrupted job" COMPLETED 0:0 - no || finish
[ -s ref/probes.csv ] || { fail "a. no ref/probes.csv"; finish; }

# --- b. scancel, then scancel --batch --signal=USR1 on the mpirun variant, then to the end --------
j=$(submit --export=ALL,SPHFSI_TEST_STOP_DELAY=5 b_srun.sh)
wait_running "$j" && wait_new_ckpt "$W/b" none "$j" || { fail "b. no first checkpoint"; finish; }
scancel "$j"
expect "$j" "b1. recipe (srun), scancel after the first checkpoint" CANCELLED 3:0 SIGTERM no
s1=$(ckpt_step "$W/b"); [ "$s1" -gt 0 ] && pass "b1. checkpoint at step $s1" || fail "b1. no checkpoint (step $s1)"
grep -q "^cancelled: sbatch this script again" "slurm-$j.out" || fail "b1. the recipe did not say it was cancelled"
old=$(ckpt_id "$W/b")
j=$(submit b_mpirun.sh)
wait_running "$j" && wait_new_ckpt "$W/b" "$old" "$j" || { fail "b2. no new checkpoint after the restart"; finish; }
scancel --batch --signal=USR1 "$j"
expect "$j" "b2. resubmitted by hand (mpirun), scancel --batch --signal=USR1" FAILED 3:0 SIGUSR1 yes || finish
s2=$(ckpt_step "$W/b"); [ "$s2" -gt "$s1" ] && pass "b2. checkpoint at step $s2 > $s1" || fail "b2. checkpoint step $s2, not past $s1"
j=$(resubmitted "$j"); echo "$j" >> "$W/jobs"
expect "$j" "b3. resubmitted by the recipe (mpirun), to the end" COMPLETED 0:0 - no
if cmp -s ref/probes.csv b/probes.csv; then pass "b. the chain's probes.csv equals the uninterrupted job's byte for byte ($(($(wc -l < b/probes.csv) - 1)) rows)"
else fail "b. the chain's probes.csv differs from the uninterrupted job's: $(cmp ref/probes.csv b/probes.csv 2>&1 | head -n 1)"; fi

# --- c. the time limit, then --signal=USR1@10 ---------------------------------------------------
j=$(submit --export=ALL,SPHFSI_TEST_STOP_DELAY=5 c_limit.sh)
expect "$j" "c1. recipe, --time=1 without --signal: the time limit" TIMEOUT 3:0 SIGTERM yes
s1=$(ckpt_step "$W/c"); [ "$s1" -gt 0 ] && pass "c1. checkpoint at step $s1" || fail "c1. no checkpoint (step $s1)"
j2=$(resubmitted "$j")
if [ -n "$j2" ]; then echo "$j2" >> "$W/jobs"; scancel "$j2"; wait_end "$j2"
  say "c1. its resubmission, job $j2, cancelled: JobState=$(field "$j2" JobState) ExitCode=$(field "$j2" ExitCode)"; fi
j=$(submit c_signal.sh)
expect "$j" "c2. recipe, --time=1 --signal=USR1@10: the signal before the limit" FAILED 3:0 SIGUSR1 yes
j2=$(resubmitted "$j")
if [ -n "$j2" ]; then echo "$j2" >> "$W/jobs"; scancel "$j2"; wait_end "$j2"
  say "c2. its resubmission, job $j2, cancelled: JobState=$(field "$j2" JobState) ExitCode=$(field "$j2" ExitCode)"; fi
n=$(ckpt_step "$W/c")
[ "$n" -gt "$s1" ] && pass "c2. checkpoint at step $n > $s1" || fail "c2. checkpoint step $n, not past $s1"
j=$(submit -J ref_c -n 2 --wrap "srun --mpi=pmix $BIN $CASE_C -checkpoint_interval 0.02 -progress_every 0 -max_steps $n -output_dir $W/ref_c")
expect "$j" "c3. uninterrupted job of $n steps" COMPLETED 0:0 - no
if cmp -s ref_c/probes.csv c/probes.csv; then pass "c. the chain's probes.csv equals the uninterrupted job's byte for byte ($(($(wc -l < c/probes.csv) - 1)) rows)"
else fail "c. the chain's probes.csv differs from the uninterrupted job's: $(cmp ref_c/probes.csv c/probes.csv 2>&1 | head -n 1)"; fi
finish
