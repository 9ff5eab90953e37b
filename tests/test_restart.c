/* Checkpoint and restart continue a run exactly.  A short run (default: the dam break of
 * test_rank_agreement, every WCSPH option on) is done three ways and its final states compared
 * particle by particle, every field, by id, and its probe rows:
 *   uninterrupted on all ranks;
 *   stopped after half its steps (checkpoint), restarted on all ranks   (same ranks: -tol_same, 0)
 *   the same checkpoint restarted on rank 0 alone                        (N -> 1: -tol, default 0)
 *   stopped after half its steps on rank 0 alone, restarted on all ranks (1 -> N: -tol)
 * (probe rows across rank counts: max(-tol, 1e-12), see Compare)
 * Neighbour sums do not depend on the decomposition, so WCSPH and solids agree bit for bit even
 * across rank counts; with -fluid isph the solver's parallel preconditioner does not, so use
 * -ppe_ksp_rtol 1e-10 -tol 1e-8 there.  Another scene with -case NAME and its options.  2 ranks. */
#include "run/sim.h"
#include <sphfsi.h>

typedef struct {
  PetscInt   N, w, nrow, ncol, step;
  PetscReal *rec, *rows, t; /* rank 0: per particle (sorted by id) id + every field; probe rows */
} Final;

static PetscErrorCode Run(MPI_Comm comm, const char *outdir, const char *restart, PetscInt max_steps, Sim *sim)
{
  char buf[32];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof(buf), "%" PetscInt_FMT, max_steps));
  PetscCall(PetscOptionsSetValue(NULL, "-max_steps", max_steps > 0 ? buf : "1000000000"));
  if (restart) PetscCall(PetscOptionsSetValue(NULL, "-restart", restart));
  else PetscCall(PetscOptionsClearValue(NULL, "-restart"));
  PetscCall(SimCreate(comm, sim));
  PetscCall(SimSetFromOptions(*sim));
  PetscCall(PetscStrncpy((*sim)->out.dir, outdir, sizeof((*sim)->out.dir)));
  PetscCall(SimSetUp(*sim));
  PetscCall(SimRun(*sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static int ById(const void *a, const void *b, void *ctx)
{
  PetscReal ia = *(const PetscReal *)a, ib = *(const PetscReal *)b;
  return ia < ib ? -1 : ia > ib;
}

/* Everything of a finished run on rank 0 of its communicator (collective there), then destroyed. */
static PetscErrorCode Collect(Sim *psim, Final *F)
{
  Sim          sim = *psim;
  Particles    P   = sim->P;
  PetscReal   *loc;
  PetscMPIInt  n, *cnt = NULL, *disp = NULL;
  PetscInt     w = 1;
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on && f != FIELD_ROW) w += P->f[f].width; /* PPE row numbers depend on the partition */
  PetscCall(PetscMalloc1(w * P->n + 1, &loc));
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal *r = loc + w * a;
    *r++ = P->id[a];
    for (PetscInt f = 0; f < FIELD_COUNT; f++)
      for (PetscInt k = 0; P->f[f].on && f != FIELD_ROW && k < P->f[f].width; k++) *r++ = P->f[f].a[a * P->f[f].width + k];
  }
  n = (PetscMPIInt)(w * P->n);
  F->N = sim->nbhd.nparticles; F->w = w; F->step = sim->phys.step; F->t = sim->phys.t;
  F->ncol = 1 + sim->scene->nprobes; F->nrow = sim->out.nprobe_rows;
  if (!sim->rank) {
    PetscCall(PetscMalloc2(sim->size, &cnt, sim->size + 1, &disp));
    PetscCall(PetscMalloc1(w * F->N, &F->rec));
    PetscCall(PetscMalloc1(F->nrow * F->ncol, &F->rows));
    PetscCall(PetscArraycpy(F->rows, sim->out.probe_rows, F->nrow * F->ncol));
  }
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, sim->comm));
  if (!sim->rank) { disp[0] = 0; for (PetscMPIInt r = 0; r < sim->size; r++) disp[r + 1] = disp[r] + cnt[r]; }
  PetscCallMPI(MPI_Gatherv(loc, n, MPIU_REAL, F->rec, cnt, disp, MPIU_REAL, 0, sim->comm));
  if (!sim->rank) {
    PetscCall(PetscTimSort(F->N, F->rec, w * sizeof(PetscReal), ById, NULL));
    PetscCall(PetscFree2(cnt, disp));
  }
  PetscCall(PetscFree(loc));
  PetscCall(SimDestroy(psim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Largest difference of a against the reference r, relative to each column's largest value (state and
 * probe rows). */
/* Probe rows of runs on different rank counts may differ by round-off even when the states are
 * equal: probes that sum over particles reduce across ranks in another order (ptol). */
static PetscErrorCode Compare(const char *what, const Final *r, const Final *a, PetscReal tol, PetscReal ptol, PetscReal *out)
{
  PetscReal err = 0, perr = 0;
  PetscInt  worst = -1; /* the record column of the largest difference (0 = id, then the fields in order) */
  PetscFunctionBeginUser;
  PetscCheck(a->N == r->N && a->w == r->w && a->step == r->step && a->nrow == r->nrow, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: %d particles, %d steps, %d probe rows; uninterrupted: %d, %d, %d", what, (int)a->N, (int)a->step, (int)a->nrow, (int)r->N, (int)r->step, (int)r->nrow);
  for (PetscInt c = 0; c < r->w; c++) {
    PetscReal scale = 0, d = 0;
    for (PetscInt k = 0; k < r->N; k++) {
      scale = PetscMax(scale, PetscAbsReal(r->rec[k * r->w + c]));
      d     = PetscMax(d, PetscAbsReal(a->rec[k * r->w + c] - r->rec[k * r->w + c]));
    }
    if ((scale > 0 ? d / scale : d) > err) { err = scale > 0 ? d / scale : d; worst = c; }
  }
  for (PetscInt c = 0; c < r->ncol; c++) {
    PetscReal scale = 0, d = 0;
    for (PetscInt k = 0; k < r->nrow; k++) {
      scale = PetscMax(scale, PetscAbsReal(r->rows[k * r->ncol + c]));
      d     = PetscMax(d, PetscAbsReal(a->rows[k * r->ncol + c] - r->rows[k * r->ncol + c]));
    }
    perr = PetscMax(perr, scale > 0 ? d / scale : d);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-34s max relative difference: state %.3e (bound %.0e; record column %" PetscInt_FMT ": 0 id, then the fields in order), probe rows %.3e (bound %.0e)\n", what, (double)err, (double)tol, worst, (double)perr, (double)ptol));
  *out = err;
  PetscCheck(err <= tol && perr <= ptol, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s differs from the uninterrupted run by %g (probes %g) > %g", what, (double)err, (double)perr, (double)tol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FinalDestroy(Final *F)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(F->rec));
  PetscCall(PetscFree(F->rows));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim         sim;
  Final       full = {0}, same = {0}, down = {0}, up = {0};
  PetscMPIInt rank, size;
  PetscReal   tol = 0, tol_same = 0;
  PetscInt    half;
  PetscBool   other;
  const char *ckw = "out/test_restart/world/checkpoint.h5", *cks = "out/test_restart/self/checkpoint.h5";

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol_same", &tol_same, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-case", &other));
  if (!other) {
    PetscCall(PetscOptionsSetValue(NULL, "-case", "dam_break"));
    PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
    PetscCall(PetscOptionsSetValue(NULL, "-t_end", "0.03"));
    PetscCall(PetscOptionsSetValue(NULL, "-wcsph_delta", "0.1"));
    PetscCall(PetscOptionsSetValue(NULL, "-wcsph_alpha", "0.1"));
    PetscCall(PetscOptionsSetValue(NULL, "-fluid_xsph", "0.5"));
  }
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_interval", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-checkpoint_interval", "1e9")); /* only the one at the end */

  PetscCall(Run(PETSC_COMM_WORLD, "out/test_restart/full", NULL, 0, &sim));
  half = sim->phys.step / 2;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "restart (%s %s): %d particles, %d steps, stopped after %d and restarted:\n", sim->scene->name, !sim->phys.has_fluid ? "solid" : sim->phys.isph ? "isph" : "wcsph", (int)sim->nbhd.nparticles, (int)sim->phys.step, (int)half));
  PetscCall(Collect(&sim, &full));
  /* same ranks */
  PetscCall(Run(PETSC_COMM_WORLD, "out/test_restart/world", NULL, half, &sim));
  PetscCall(SimDestroy(&sim));
  PetscCall(Run(PETSC_COMM_WORLD, "out/test_restart/same", ckw, 0, &sim));
  PetscCall(Collect(&sim, &same));
  /* N -> 1, and 1 -> N */
  if (!rank) {
    PetscCall(Run(PETSC_COMM_SELF, "out/test_restart/down", ckw, 0, &sim));
    PetscCall(Collect(&sim, &down));
    PetscCall(Run(PETSC_COMM_SELF, "out/test_restart/self", NULL, half, &sim));
    PetscCall(SimDestroy(&sim));
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD)); /* the 1-rank checkpoint is complete */
  PetscCall(Run(PETSC_COMM_WORLD, "out/test_restart/up", cks, 0, &sim));
  PetscCall(Collect(&sim, &up));
  if (!rank) {
    char      what[64];
    PetscReal e[3];
    PetscCall(PetscSNPrintf(what, sizeof(what), "restart on %d ranks (same):", size));
    PetscCall(Compare(what, &full, &same, tol_same, tol_same, &e[0]));
    PetscCall(PetscSNPrintf(what, sizeof(what), "written on %d ranks, restart on 1:", size));
    PetscCall(Compare(what, &full, &down, tol, PetscMax(tol, 1e-12), &e[1]));
    PetscCall(PetscSNPrintf(what, sizeof(what), "written on 1 rank, restart on %d:", size));
    PetscCall(Compare(what, &full, &up, tol, PetscMax(tol, 1e-12), &e[2]));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "restart: state differences same ranks %.1e, %d to 1 %.1e, 1 to %d %.1e (bounds %.0e, %.0e)\n", (double)e[0], size, (double)e[1], size, (double)e[2], (double)tol_same, (double)tol));
  }
  PetscCall(FinalDestroy(&full));
  PetscCall(FinalDestroy(&same));
  PetscCall(FinalDestroy(&down));
  PetscCall(FinalDestroy(&up));
  PetscCall(PetscFinalize());
  return 0;
}
