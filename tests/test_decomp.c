/* Decomposition and halo: through migration and forced repartitioning, every id exists exactly once
 * across ranks, and every ghost holds its owner's current values (x, rho, p after the step, v after
 * its refresh). Run on 2 ranks. */
#include "run/sim.h"
#include <sphfsi.h>
#include "fluid/wcsph.h"

/* Gather (id, x, y, vx, vy, rho, p) of all owned particles to every rank, indexed by id. */
static PetscErrorCode GatherById(Sim sim, PetscInt N, PetscReal *all, PetscInt *count)
{
  Particles    P = sim->P;
  PetscReal   *loc, *buf;
  PetscMPIInt *cnt, *disp, n = (PetscMPIInt)(7 * P->n), tot = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(7 * P->n + 1, &loc));
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal *r = loc + 7 * a;
    r[0] = P->id[a]; r[1] = PField(P, FIELD_X)[2 * a]; r[2] = PField(P, FIELD_X)[2 * a + 1];
    r[3] = PField(P, FIELD_V)[2 * a]; r[4] = PField(P, FIELD_V)[2 * a + 1]; r[5] = PField(P, FIELD_RHO)[a]; r[6] = PField(P, FIELD_P)[a];
  }
  PetscCall(PetscMalloc2(sim->size, &cnt, sim->size + 1, &disp));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, cnt, 1, MPI_INT, sim->comm));
  disp[0] = 0;
  for (PetscMPIInt r = 0; r < sim->size; r++) disp[r + 1] = disp[r] + cnt[r];
  tot = disp[sim->size];
  PetscCall(PetscMalloc1(tot + 1, &buf));
  PetscCallMPI(MPI_Allgatherv(loc, n, MPIU_REAL, buf, cnt, disp, MPIU_REAL, sim->comm));
  PetscCall(PetscArrayzero(count, N));
  for (PetscInt k = 0; k < tot / 7; k++) {
    PetscInt id = (PetscInt)buf[7 * k];
    PetscCheck(id >= 0 && id < N, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Bad id %" PetscInt_FMT, id);
    count[id]++;
    PetscCall(PetscArraycpy(all + 7 * id, buf + 7 * k, 7));
  }
  PetscCall(PetscFree(buf));
  PetscCall(PetscFree2(cnt, disp));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Check(Sim sim, PetscInt step)
{
  Particles  P = sim->P;
  PetscInt   N = sim->nbhd.nparticles, *count, bad = 0, nghost;
  PetscReal *all;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(7 * N, &all, N, &count));
  PetscCall(GatherById(sim, N, all, count));
  for (PetscInt id = 0; id < N; id++) PetscCheck(count[id] == 1, sim->comm, PETSC_ERR_PLIB, "Step %" PetscInt_FMT ": id %" PetscInt_FMT " owned %" PetscInt_FMT " times", step, id, count[id]);
  for (PetscInt g = P->n; g < P->n + P->ng; g++) {
    const PetscReal *o = all + 7 * P->id[g];
    PetscReal v[7] = {0, PField(P, FIELD_X)[2 * g], PField(P, FIELD_X)[2 * g + 1], PField(P, FIELD_V)[2 * g], PField(P, FIELD_V)[2 * g + 1], PField(P, FIELD_RHO)[g], PField(P, FIELD_P)[g]};
    for (PetscInt k = 1; k < 7; k++) if (v[k] != o[k]) { if (bad < 5) PetscCall(PetscPrintf(PETSC_COMM_SELF, "ghost id %d kind %d field %d: %g vs owner %g\n", (int)P->id[g], (int)P->kind[g], (int)k, (double)v[k], (double)o[k])); bad++; }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, sim->comm));
  PetscCall(MPIU_Allreduce(&P->ng, &nghost, 1, MPIU_INT, MPI_SUM, sim->comm));
  PetscCheck(!bad, sim->comm, PETSC_ERR_PLIB, "Step %" PetscInt_FMT ": %" PetscInt_FMT " ghost values differ from their owners'", step, bad);
  PetscCheck(sim->size == 1 || nghost > 0, sim->comm, PETSC_ERR_PLIB, "No ghosts on %d ranks", sim->size);
  PetscCall(PetscFree2(all, count));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The partition of the cell graph: every occupied cell to a rank, every empty cell to the rank of
 * an occupied cell at the smallest Chebyshev distance (decomp.c partitions only the occupied ones). */
static PetscErrorCode CheckEmptyCells(Sim sim)
{
  const Grid  *g  = &sim->grid;
  PetscInt     nc = GridNumCells(g), *work, bad = 0, nempty = 0;
  PetscMPIInt *owner = sim->decomp->owner;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nc, &work));
  DecompCellWork(g, sim->P, work, NULL);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, work, (PetscMPIInt)nc, MPIU_INT, MPI_SUM, sim->comm));
  for (PetscInt e = 0; e < nc; e++) {
    PetscInt  dmin = PETSC_MAX_INT, ie = e % g->n[0], je = e / g->n[0];
    PetscBool match = PETSC_FALSE;
    if (owner[e] < 0 || owner[e] >= sim->size) bad++;
    if (work[e]) continue;
    nempty++;
    for (PetscInt c = 0; c < nc; c++) {
      PetscInt d = PetscMax(PetscAbsInt(c % g->n[0] - ie), PetscAbsInt(c / g->n[0] - je));
      if (!work[c] || d > dmin) continue;
      if (d < dmin) { dmin = d; match = PETSC_FALSE; }
      match = (PetscBool)(match || owner[c] == owner[e]);
    }
    bad += !match;
  }
  PetscCheck(!bad, sim->comm, PETSC_ERR_PLIB, "%" PetscInt_FMT " of %" PetscInt_FMT " cells with an owner out of range or, if empty, not that of a nearest occupied cell", bad, nc);
  PetscCheck(nempty > 0, sim->comm, PETSC_ERR_PLIB, "No empty cell: the check tested nothing");
  PetscCall(PetscFree(work));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim      sim;
  PetscInt nsteps = 60, nrep;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsSetValue(NULL, "-case", "dam_break"));
  PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.005"));
  PetscCall(PetscOptionsSetValue(NULL, "-rebalance_threshold", "1.0"));
  PetscCall(PetscOptionsSetValue(NULL, "-rebalance_every", "7"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_decomp"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(Check(sim, 0));
  PetscCall(CheckEmptyCells(sim));
  for (PetscInt s = 1; s <= nsteps; s++) {
    PetscCall(WCSPHTimeStep(&sim->phys, &sim->phys.dt));
    sim->phys.dt *= 4; /* larger steps: more particles change cells and owners (still stable for 60 steps) */
    PetscCall(WCSPHStep(&sim->phys));
    sim->phys.step++;
    /* x, rho, p of ghosts are current after a step; v is refreshed where it is read (start of the
     * next step), so refresh it here as the step would */
    PetscCall(HaloRefresh(sim->halo, sim->P, 1, (FieldId[]){FIELD_V}));
    PetscCall(Check(sim, s));
  }
  nrep = sim->decomp->nrepartition;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "decomp: %" PetscInt_FMT " particles, %d ranks, %" PetscInt_FMT " steps, %" PetscInt_FMT " repartitions: ids unique, ghosts equal owners\n", sim->nbhd.nparticles, sim->size, nsteps, nrep));
  PetscCheck(sim->size == 1 || nrep > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Forced rebalancing never repartitioned");
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
