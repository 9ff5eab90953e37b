/* The same short dam break on all ranks of the world and on rank 0 alone agrees particle by particle
 * (by id; with open boundaries, which make and remove particles, the same ids). Neighbour sums run in an order independent of the decomposition, so with WCSPH the
 * agreement is expected to be exact; the test allows round-off (-tol, default 1e-12 relative).
 * With -fluid isph the pressure comes from an iterative solve whose parallel preconditioner differs
 * between 1 and 2 ranks, so the runs agree to the solver tolerance: run with -ppe_ksp_rtol 1e-10 and
 * -tol 1e-6.  Another scene with -case NAME and its options.  Run on 2 ranks or more (tests/run_tests.sh:
 * 2 and 8), where some ranks may own no fluid or no particle at all. */
#include "run/sim.h"
#include <sphfsi.h>
#include "run/guard.h"

static PetscErrorCode RunCase(MPI_Comm comm, const char *outdir, Sim *sim)
{
  PetscFunctionBeginUser;
  PetscCall(SimCreate(comm, sim));
  PetscCall(SimSetFromOptions(*sim));
  PetscCall(PetscStrncpy((*sim)->out.dir, outdir, sizeof((*sim)->out.dir)));
  PetscCall(SimSetUp(*sim));
  PetscCall(SimRun(*sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* kind of the particle with global id `id` (a 1-rank run holds them all) */
static PetscInt KindOf(Particles P, PetscInt id)
{
  for (PetscInt a = 0; a < P->n; a++)
    if (P->id[a] == id) return P->kind[a];
  return 0;
}

int main(int argc, char **argv)
{
  Sim         world, self = NULL;
  PetscMPIInt rank, size;
  PetscInt    N;
  PetscReal  *ref = NULL, err = 0, scale = 0, tol = 1e-12, vmin = 0.5;
  PetscInt    worst = -1, wcomp = 0; /* particle id and component (x, y, vx, vy, rho) of the largest difference */
  PetscBool   other;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-min_speed", &vmin, NULL)); /* the run must reach this speed (m/s) */
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-case", &other));
  if (!other) { /* the default: a short dam break with every WCSPH option on */
    PetscCall(PetscOptionsSetValue(NULL, "-case", "dam_break"));
    PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
    PetscCall(PetscOptionsSetValue(NULL, "-t_end", "0.05"));
    PetscCall(PetscOptionsSetValue(NULL, "-wcsph_delta", "0.1"));
    PetscCall(PetscOptionsSetValue(NULL, "-wcsph_alpha", "0.1"));
    PetscCall(PetscOptionsSetValue(NULL, "-wcsph_riemann", "3")); /* and its pass against the walls, through the halo */
    PetscCall(PetscOptionsSetValue(NULL, "-fluid_xsph", "0.5"));
  }
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(RunCase(PETSC_COMM_WORLD, "out/test_rank_agreement/world", &world));
  if (!rank) PetscCall(RunCase(PETSC_COMM_SELF, "out/test_rank_agreement/self", &self));
  N = world->nbhd.nparticles;
  /* agreement of two blown-up runs proves nothing: both must complete */
  PetscCheck(world->guard->state != GUARD_FAULT, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The %d-rank run faulted: %s", size, world->guard->msg);
  PetscCheck(rank || self->guard->state != GUARD_FAULT, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The 1-rank run faulted: %s", self->guard->msg);
  /* every world particle's (x, v, rho) sent to rank 0, compared there by id with the 1-rank run */
  {
    Particles    P = world->P;
    PetscReal   *loc, *buf = NULL;
    PetscMPIInt *cnt = NULL, *disp = NULL, n = (PetscMPIInt)(6 * P->n);
    PetscCall(PetscMalloc1(6 * P->n + 1, &loc));
    for (PetscInt a = 0; a < P->n; a++) {
      PetscReal *r = loc + 6 * a;
      r[0] = P->id[a]; r[1] = PField(P, FIELD_X)[2 * a]; r[2] = PField(P, FIELD_X)[2 * a + 1];
      r[3] = PField(P, FIELD_V)[2 * a]; r[4] = PField(P, FIELD_V)[2 * a + 1]; r[5] = PField(P, FIELD_RHO)[a];
    }
    if (!rank) PetscCall(PetscMalloc3(size, &cnt, size + 1, &disp, 6 * N, &buf));
    PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, PETSC_COMM_WORLD));
    if (!rank) { disp[0] = 0; for (PetscMPIInt r = 0; r < size; r++) disp[r + 1] = disp[r] + cnt[r]; }
    PetscCallMPI(MPI_Gatherv(loc, n, MPIU_REAL, buf, cnt, disp, MPIU_REAL, 0, PETSC_COMM_WORLD));
    if (!rank) {
      Particles Q = self->P;
      PetscCheck(Q->n == N && world->phys.step == self->phys.step, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Runs differ: %d vs %d particles, %d vs %d steps", (int)N, (int)Q->n, (int)world->phys.step, (int)self->phys.step);
      PetscCall(PetscMalloc1(6 * self->next_id, &ref)); /* by id: ids need not be 0..N-1 (open boundaries make and remove particles) */
      for (PetscInt a = 0; a < Q->n; a++) {
        PetscReal *r = ref + 6 * Q->id[a];
        r[0] = Q->id[a]; r[1] = PField(Q, FIELD_X)[2 * a]; r[2] = PField(Q, FIELD_X)[2 * a + 1];
        r[3] = PField(Q, FIELD_V)[2 * a]; r[4] = PField(Q, FIELD_V)[2 * a + 1]; r[5] = PField(Q, FIELD_RHO)[a];
      }
      for (PetscInt k = 0; k < N; k++) {
        const PetscReal *w = buf + 6 * k, *s = ref + 6 * (PetscInt)w[0];
        for (PetscInt c = 1; c < 6; c++) {
          PetscReal e = PetscAbsReal(w[c] - s[c]) / (c == 5 ? 1000.0 : c >= 3 ? 1.0 : 0.1);
          if (e > err) { err = e; worst = (PetscInt)w[0]; wcomp = c; }
        }
        scale = PetscMax(scale, PetscAbsReal(s[3]) + PetscAbsReal(s[4]));
      }
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "rank agreement (%s %s): %d particles after %d steps, max scaled difference %.3e (bound %.0e; max speed %.3f m/s)\n", world->scene->name, !world->phys.has_fluid ? "solid" : world->phys.isph ? "isph" : "wcsph", (int)N, (int)world->phys.step, (double)err, (double)tol, (double)scale));
      if (err > tol) PetscCall(PetscPrintf(PETSC_COMM_SELF, "largest difference: particle %d (%s) at (%g, %g), %s\n", (int)worst, ParticleKindNames[KindOf(self->P, worst)], (double)ref[6 * worst + 1], (double)ref[6 * worst + 2], (const char *[]){"", "x", "y", "vx", "vy", "rho"}[wcomp]));
      PetscCheck(err <= tol, PETSC_COMM_SELF, PETSC_ERR_PLIB, "1-rank and %d-rank runs differ by %g", size, (double)err);
      PetscCheck(scale > vmin, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The run did not move: max speed %g <= -min_speed %g", (double)scale, (double)vmin);
      PetscCall(PetscFree(ref));
      PetscCall(PetscFree3(cnt, disp, buf));
    }
    PetscCall(PetscFree(loc));
  }
  PetscCall(SimDestroy(&self));
  PetscCall(SimDestroy(&world));
  PetscCall(PetscFinalize());
  return 0;
}
