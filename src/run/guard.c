#include "run/guard.h"
#include "base/options_used.h"
#include "io/io.h"
#include "io/io_space.h"
#include <signal.h>
#include <stdarg.h>

/* The program's one global: the signal a handler saw (0: none).  A handler may do no more than set
 * a flag of this type; the time loop reads it at the end of each step and the ranks agree on it in
 * the step's reduction.  A SIGINT once a stop is under way (Ctrl-C again: a user who insists) ends
 * the process at once: the last complete checkpoint stays, as a checkpoint is renamed into place only
 * when whole, and summary.json already says the run was stopped (sim.c writes it first).  A SIGTERM
 * or SIGUSR1 that comes again is ignored: SLURM sends SIGTERM twice at a job's time limit (srun
 * forwards the one it gets, then slurmd signals the step: 10-50 ms apart, tools/slurm_check.sh), and
 * a launcher that will not wait sends SIGKILL. */
static volatile sig_atomic_t caught_signal = 0;

static void OnSignal(int sig)
{
  if (caught_signal) {
    if (sig != SIGINT) return;
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  caught_signal = sig;
}

/* PETSc 3.18 installs its handler for SEGV, FPE, BUS, ILL, HUP, ... and, except under Open MPI
 * (which ends a job with SIGTERM), for SIGTERM; never for SIGINT or SIGUSR1.  These three are ours:
 * SIGTERM is what batch systems send at the time limit, SIGINT is Ctrl-C, SIGUSR1 is the signal
 * Open MPI's mpiexec forwards to the ranks (and SLURM's --signal can send ahead of the limit). */
PetscErrorCode GuardInstallSignals(void)
{
  struct sigaction sa;
  const int        sigs[] = {SIGTERM, SIGINT, SIGUSR1};
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&sa, sizeof(sa)));
  sa.sa_handler = OnSignal;
  sa.sa_flags   = SA_RESTART; /* MPI and file I/O carry on; the flag is read at the step's end */
  sigemptyset(&sa.sa_mask);
  for (size_t k = 0; k < sizeof(sigs) / sizeof(sigs[0]); k++) PetscCheck(!sigaction(sigs[k], &sa, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "sigaction(%d) failed", sigs[k]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static const char *SignalName(int sig)
{
  return sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : sig == SIGUSR1 ? "SIGUSR1" : "a signal";
}

PetscErrorCode GuardCreate(Guard *g)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(g));
  PetscCall(PetscTime(&(*g)->t0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardDestroy(Guard *g)
{
  PetscFunctionBeginUser;
  if (!*g) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(StateDestroy(&(*g)->good));
  PetscCall(PetscFree(*g));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardSetFromOptions(Sim sim)
{
  Guard g = sim->guard;
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim->comm, NULL, "Run control: early stops and faults", "Guard");
  PetscCall(OptReal("-max_wall_time", "Wall seconds since start after which the run writes a checkpoint and stops (exit status 3); 0 = none", "", g->max_wall, &g->max_wall, NULL));
  PetscCall(OptReal("-dt_min", "Floor of the adaptive time step (s): below it the run stops as unstable (exit status 4); 0 = 1e-3 of the first step of each medium", "", g->dt_min, &g->dt_min, NULL));
  PetscOptionsEnd();
  PetscCheck(g->max_wall >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-max_wall_time %g must be >= 0 (seconds; 0 = no limit)", (double)g->max_wall);
  PetscCheck(g->dt_min >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dt_min %g must be >= 0 (0 = 1e-3 of the first step)", (double)g->dt_min);
  PetscCheck(!(g->dt_min > 0 && sim->dt_fixed > 0), sim->comm, PETSC_ERR_ARG_INCOMP, "-dt_min %g and -dt %g conflict: -dt_min is the floor of the adaptive step, and -dt fixes the step", (double)g->dt_min, (double)sim->dt_fixed);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardStepBegin(Sim sim)
{
  Guard g = sim->guard;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&g->step_start));
  if (!g->have_good || sim->phys.step % GUARD_KEEP_EVERY == 0) {
    PetscCall(PetscLogStagePush(sim->stage[STAGE_GUARD]));
    PetscCall(StateCopy(&sim->out, &g->good));
    g->have_good = PETSC_TRUE;
    PetscCall(PetscLogStagePop());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardFault(Sim sim, PetscBool state_ok, const char *fmt, ...)
{
  Guard   g = sim->guard;
  va_list ap;
  size_t  len;
  PetscFunctionBeginUser;
  va_start(ap, fmt);
  PetscCall(PetscVSNPrintf(g->msg, sizeof(g->msg), fmt, &len, ap));
  va_end(ap);
  g->state = GUARD_FAULT;
  if (state_ok) {
    PetscCall(StateCopy(&sim->out, &g->good));
    g->have_good = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The stage current when a step began; an error inside it leaves its stages pushed. */
static PetscErrorCode CurrentStage(int *stage)
{
  PetscStageLog log;
  PetscFunctionBeginUser;
  PetscCall(PetscLogGetStageLog(&log));
  PetscCall(PetscStageLogGetCurrent(log, stage));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardStep(Sim sim, PetscErrorCode (*step)(Sim))
{
  PetscErrorCode ierr;
  int            stage0, stage;
  char          *specific = NULL, msg[1024];

  PetscFunctionBeginUser;
  PetscCall(CurrentStage(&stage0));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = step(sim); /* not PetscCall: a fault raised inside is handled here (all ranks raise it) */
  PetscCall(PetscPopErrorHandler());
  if (!ierr) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscErrorMessage(ierr, NULL, &specific));
  PetscCall(PetscStrncpy(msg, specific ? specific : "(no message)", sizeof(msg)));
  PetscCall(CurrentStage(&stage));
  for (PetscInt k = 0; k < 32 && stage != stage0; k++) {
    PetscCall(PetscLogStagePop());
    PetscCall(CurrentStage(&stage));
  }
  PetscCheck(ierr == PETSC_ERR_NOT_CONVERGED, PETSC_COMM_SELF, ierr, "In step %" PetscInt_FMT " (t = %g): %s", sim->phys.step, (double)sim->phys.t, msg);
  PetscCall(GuardFault(sim, PETSC_FALSE, "in step %" PetscInt_FMT " (from t = %g): %s", sim->phys.step + 1, (double)sim->phys.t, msg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Particle data of the owned particle a, or of none (a < 0), for a collective report. */
typedef struct {
  PetscReal val, id, kind, x[3], field;
} Where;
#define WHERE_REALS 7

/* "(x, y)" or "(x, y, z)" of a report */
static const char *WherePoint(Sim sim, const Where *w, char buf[96]) { return GridFormatPoint(buf, 96, sim->phys.dim, w->x); }

static void WhereOf(Sim sim, PetscInt a, PetscInt field, PetscReal val, Where *w)
{
  const PetscReal *x = PField(sim->P, FIELD_X);
  memset(w, 0, sizeof(*w));
  if (a < 0) { w->id = -1; return; }
  w->val = val; w->id = (PetscReal)sim->P->id[a]; w->kind = (PetscReal)sim->P->kind[a];
  for (PetscInt d = 0; d < sim->phys.dim; d++) w->x[d] = x[sim->phys.dim * a + d];
  w->field = (PetscReal)field;
}

/* The report of the lowest rank that has one (collective; found = no rank had one). */
static PetscErrorCode Gather(Sim sim, const Where *mine, Where *w, PetscBool *found)
{
  Where *all;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(sim->size, &all));
  PetscCallMPI(MPI_Allgather((void *)mine, WHERE_REALS, MPIU_REAL, all, WHERE_REALS, MPIU_REAL, sim->comm));
  *found = PETSC_FALSE;
  for (PetscMPIInt r = 0; r < sim->size && !*found; r++)
    if (all[r].id >= 0) { *w = all[r]; *found = PETSC_TRUE; }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardCheckDt(Sim sim, PetscInt medium, PetscReal dt)
{
  Guard            g = sim->guard;
  Particles        P = sim->P;
  const PetscReal *acc = PField(P, FIELD_ACC), *v = PField(P, FIELD_V);
  PetscReal        floor, amax = -1;
  PetscInt         worst = -1;
  Where            mine, w;
  PetscBool        found;

  PetscFunctionBeginUser;
  if (!g->dt_first[medium]) g->dt_first[medium] = dt;
  floor = g->dt_min > 0 ? g->dt_min : 1e-3 * g->dt_first[medium];
  if (dt >= floor) PetscFunctionReturn(PETSC_SUCCESS);
  if (PetscIsInfOrNanReal(dt)) { /* a state the end-of-step check passed cannot give this: a parameter */
    PetscCall(GuardFault(sim, PETSC_TRUE, "the %s time step is not finite at step %" PetscInt_FMT ", t = %g", medium ? "solid" : "fluid", sim->phys.step, (double)sim->phys.t));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* where: the owned particle of this medium with the largest acceleration */
  for (PetscInt a = 0; a < P->n && acc; a++) {
    PetscReal an = PetscSqrtReal(VDot(acc + sim->phys.dim * a, acc + sim->phys.dim * a, sim->phys.dim));
    if ((medium ? P->kind[a] == KIND_SOLID : KindIsFluid(P->kind[a])) && an > amax) { amax = an; worst = a; }
  }
  {
    PetscReal gmax;
    PetscCall(MPIU_Allreduce(&amax, &gmax, 1, MPIU_REAL, MPIU_MAX, sim->comm));
    WhereOf(sim, amax == gmax ? worst : -1, FIELD_ACC, amax, &mine);
  }
  PetscCall(Gather(sim, &mine, &w, &found));
  if (found) {
    PetscInt  a  = -1;
    PetscReal vn = 0;
    for (PetscInt b = 0; b < P->n; b++)
      if (P->id[b] == (PetscInt)w.id) a = b;
    char      at[96];
    if (a >= 0) vn = PetscSqrtReal(VDot(v + sim->phys.dim * a, v + sim->phys.dim * a, sim->phys.dim));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &vn, 1, MPIU_REAL, MPIU_MAX, sim->comm));
    PetscCall(GuardFault(sim, PETSC_TRUE, "the %s time step %g s fell below its floor %g s (%s) at step %" PetscInt_FMT ", t = %g; largest acceleration %g m/s^2 (speed %g m/s) at particle id %d (%s) at %s: the run is unstable (try a smaller -cfl; -dt_min sets the floor)", medium ? "solid" : "fluid", (double)dt, (double)floor, g->dt_min > 0 ? "-dt_min" : "1e-3 of the first step", sim->phys.step, (double)sim->phys.t, (double)w.val, (double)vn, (int)w.id, ParticleKindNames[(PetscInt)w.kind], WherePoint(sim, &w, at)));
  } else PetscCall(GuardFault(sim, PETSC_TRUE, "the %s time step %g s fell below its floor %g s at step %" PetscInt_FMT ", t = %g: the run is unstable (try a smaller -cfl)", medium ? "solid" : "fluid", (double)dt, (double)floor, sim->phys.step, (double)sim->phys.t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* First owned particle with a non-finite value in any field: one streaming pass per field, and a
 * search only in a field that has one. */
static void FindNonFinite(Particles P, PetscInt *bad, PetscInt *field, PetscReal *val)
{
  *bad = -1;
  for (PetscInt f = 0; f < FIELD_COUNT && *bad < 0; f++) {
    const PetscReal *a = P->f[f].a;
    const PetscInt   w = P->f[f].width, n = P->n * w;
    PetscReal        s[4] = {0, 0, 0, 0}; /* x 0: stays 0 unless a value is NaN or Inf; four sums pipeline */
    PetscInt         k;
    if (!P->f[f].on) continue;
    for (k = 0; k + 4 <= n; k += 4)
      for (PetscInt j = 0; j < 4; j++) s[j] += 0 * a[k + j];
    for (; k < n; k++) s[0] += 0 * a[k];
    if (!PetscIsInfOrNanReal(s[0] + s[1] + s[2] + s[3])) continue;
    for (PetscInt k = 0; k < n; k++)
      if (PetscIsInfOrNanReal(a[k])) { *bad = k / w; *field = f; *val = a[k]; break; }
  }
}

/* The fault of a non-finite value (collective; bad < 0 on ranks without one). */
static PetscErrorCode NonFinite(Sim sim, PetscInt bad, PetscInt field, PetscReal val, PetscBool initial)
{
  Where     mine, w;
  PetscBool found;
  char      when[128], value[32], at[96];
  PetscFunctionBeginUser;
  WhereOf(sim, bad, field, val, &mine);
  PetscCall(Gather(sim, &mine, &w, &found));
  if (initial) PetscCall(PetscSNPrintf(when, sizeof(when), "in the initial state at step %" PetscInt_FMT " (t = %g): check the scene's options or the checkpoint", sim->phys.step, (double)sim->phys.t));
  else PetscCall(PetscSNPrintf(when, sizeof(when), "after step %" PetscInt_FMT " (t = %g): the run is unstable (reduce -dt or -cfl)", sim->phys.step, (double)sim->phys.t));
  snprintf(value, sizeof(value), "%g", (double)w.val); /* "nan", not PETSc's "nan." */
  PetscCall(GuardFault(sim, PETSC_FALSE, "%s = %s at particle id %d (%s) at %s %s", sim->P->f[(PetscInt)w.field].name, value, (int)w.id, ParticleKindNames[(PetscInt)w.kind], WherePoint(sim, &w, at), when));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardCheckInitial(Sim sim)
{
  PetscInt  bad, field = 0, gbad;
  PetscReal val = 0;
  PetscFunctionBeginUser;
  FindNonFinite(sim->P, &bad, &field, &val);
  PetscCall(MPIU_Allreduce(&bad, &gbad, 1, MPIU_INT, MPI_MAX, sim->comm));
  if (gbad >= 0) PetscCall(NonFinite(sim, bad, field, val, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardStepEnd(Sim sim, PetscBool *progress)
{
  Guard          g = sim->guard;
  PetscLogDouble now;
  PetscInt       bad, field = 0;
  PetscReal      val = 0;
  int            flags[4];

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  g->step_max = PetscMax(g->step_max, now - g->step_start);
  PetscCall(PetscLogStagePush(sim->stage[STAGE_GUARD])); /* the scan; the reduction's wait is the step's */
  FindNonFinite(sim->P, &bad, &field, &val);
  PetscCall(PetscLogStagePop());
  flags[0] = bad >= 0;
  flags[1] = (int)caught_signal;
  flags[2] = g->max_wall > 0 && now - g->t0 + 2 * g->step_max >= g->max_wall; /* the next step might end past it */
  flags[3] = !sim->rank && *progress; /* rank 0's clock decides: what follows a progress line is collective */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, flags, 4, MPI_INT, MPI_MAX, sim->comm));
  *progress = (PetscBool)flags[3];
  if (flags[0]) PetscCall(NonFinite(sim, bad, field, val, PETSC_FALSE));
  else if (flags[1]) {
    g->state = GUARD_STOP;
    PetscCall(PetscSNPrintf(g->msg, sizeof(g->msg), "received %s", SignalName(flags[1])));
  } else if (flags[2]) {
    g->state = GUARD_STOP;
    PetscCall(PetscSNPrintf(g->msg, sizeof(g->msg), "-max_wall_time %g s: %.1f s used, and a step takes up to %.2f s", (double)g->max_wall, (double)(now - g->t0), (double)g->step_max));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardCheckIO(Sim sim)
{
  Guard g = sim->guard;
  PetscFunctionBeginUser;
  if (!sim->out.fault.set || g->state == GUARD_IO) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscStrncpy(g->msg, sim->out.fault.msg, sizeof(g->msg)));
  g->state = GUARD_IO;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardCheckSetUp(Sim sim, const char *when)
{
  Guard g = sim->guard;
  int   sig = (int)caught_signal;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, sim->comm));
  if (!sig) PetscFunctionReturn(PETSC_SUCCESS);
  g->state = GUARD_STOP;
  PetscCall(PetscSNPrintf(g->msg, sizeof(g->msg), "received %s during set-up, %s", SignalName(sig), when));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardAnnounceStop(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(sim->comm, "sphfsi: stopped at step %" PetscInt_FMT ", t = %g: %s.\n", sim->phys.step, (double)sim->phys.t, sim->guard->msg));
  if (!sim->rank) fflush(PETSC_STDOUT); /* before a launcher's kill can take it */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GuardFinish(Sim sim)
{
  Guard g = sim->guard;
  char  path[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  PetscCall(GuardCheckIO(sim));
  if (g->state == GUARD_IO) {
    PetscCall(PetscFPrintf(sim->comm, PETSC_STDERR, "sphfsi: error: %s (exit status %d)\n", g->msg, SIM_EXIT_IO));
    sim->exit_status = SIM_EXIT_IO;
  } else if (g->state == GUARD_STOP) { /* SimRun announced the stop and wrote the checkpoint */
    PetscCall(PetscPrintf(sim->comm, "sphfsi: checkpoint written to %s/checkpoint.h5: continue with -restart %s/checkpoint.h5 (its options are taken from it; options given override them) (exit status %d)\n", sim->out.dir, sim->out.dir, SIM_EXIT_STOPPED));
    sim->exit_status = SIM_EXIT_STOPPED;
  } else if (g->state == GUARD_FAULT) {
    PetscCall(PetscPrintf(sim->comm, "sphfsi: FAULT: %s\n", g->msg));
    sim->exit_status = SIM_EXIT_FAULT;
    if (!g->have_good) {
      PetscCall(PetscPrintf(sim->comm, "sphfsi: the run has no good state to write (exit status %d)\n", SIM_EXIT_FAULT));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/last_good.h5", sim->out.dir));
    {
      PetscReal bytes;
      PetscBool ok;
      PetscCall(IOSpaceCheckpoint(&sim->out, &bytes));
      PetscCall(IOSpaceReserve(&sim->out, "last_good.h5", bytes, &ok));
      if (!ok) {
        PetscCall(PetscFPrintf(sim->comm, PETSC_STDERR, "sphfsi: error: %s (exit status %d)\n", g->msg, SIM_EXIT_FAULT));
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    PetscCall(IOSpacePushWrite(path));
    PetscCall(CheckpointWrite(&sim->out, &g->good, path));
    PetscCall(IOSpacePopWrite());
    PetscCall(IOWriteXDMFOne(&sim->out, "last_good.xmf", "last_good.h5", g->good.r[0], g->good.i[1]));
    PetscCall(PetscPrintf(sim->comm, "sphfsi: the last good state, step %" PetscInt_FMT " (t = %g), is in %s: a checkpoint with the datasets of a snapshot, to look at (last_good.xmf in ParaView) or to restart from with -restart %s and a smaller -dt or -cfl.  No NaN was written to any output file (exit status %d)\n", g->good.i[0], (double)g->good.r[0], path, path, SIM_EXIT_FAULT));
    sim->exit_status = SIM_EXIT_FAULT;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
