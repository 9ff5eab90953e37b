/* Partition statistics of a scene's real cell graph for many ranks, without running them.
 * Builds the scene's initial particles on one process, bins them into the simulation's cells and
 * partitions the cell graph with the code's own METIS call (DecompPartitionCells: the same vertex
 * and edge weights as a run) for P = 2, 4, ..., -nparts_max.  For each P it prints one CSV row:
 *   owned particles and work (fluid/solid 4, wall 1) per rank (max, mean), imbalance max/mean,
 *   PPE rows per rank (fluid + boundary particles within reach of a fluid cell; max, mean),
 *   halo (ghost) particles per rank (max, mean), cut cell-graph edges, neighbour ranks (max, mean),
 *   solid particles per rank (max, mean), METIS time.
 * -solid_weight W: weight solid and clamp particles by W instead of the code's 4 (e.g. to count
 * the solid sub-steps of an FSI scene); -solid_cost S: the cost columns count fluid 4, wall 1 and
 * solid S (the time a solid particle takes per fluid step, in units of a wall particle's);
 * -split_solids: the solid particles balanced as a second constraint (-decomp_split_solids of a run).
 * Usage: bin/partition_model -options_file cases/dam_break.opts -dx 8.2e-5 [-nparts_max 1024] */
#include "run/sim.h"
#include <sphfsi.h>
#include "solid/solid.h"
#include "base/kernel.h"
#include <petscbt.h>

typedef struct {
  PetscInt  nc;
  PetscInt  *all, *fluid, *bnd, *solid, *work, *ppe; /* per cell */
  PetscReal *cost;                                  /* per cell: -solid_cost weighting */
} CellCounts;

/* Scene particles on this process only: the part of SimSetUp that creates them. */
static PetscErrorCode BuildScene(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(sim->scene->create(sim));
  if (sim->phys.fl.c0 <= 0) sim->phys.fl.c0 = 10.0 * sim->phys.v_ref; /* as SimSetUp: the EOS of the initial density */
  KernelInit(&sim->phys.kernel, sim->phys.kernel.type, sim->phys.dim, sim->phys.kernel.h_factor);
  PetscCall(ParticlesSetDimension(sim->P, sim->phys.dim));
  if (sim->phys.has_solid) PetscCall(SolidSetUp(&sim->phys));
  PetscCall(ParticlesSetUp(sim->P));
  sim->phys.h_max = sim->phys.kernel.h_factor * sim->phys.dx;
  PetscCall(sim->scene->populate(sim));
  PetscCall(GridSetUp(&sim->grid, sim->phys.dim, sim->dom_lo, sim->dom_hi, 2.0 * sim->phys.h_max + (sim->phys.solid ? sim->phys.solid->skin * sim->phys.dx : 0), sim->periodic));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CountCells(Sim sim, PetscInt solid_weight, PetscReal solid_cost, CellCounts *cc)
{
  const Grid      *g = &sim->grid;
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X);
  PetscFunctionBeginUser;
  cc->nc = GridNumCells(g);
  PetscCall(PetscCalloc6(cc->nc, &cc->all, cc->nc, &cc->fluid, cc->nc, &cc->bnd, cc->nc, &cc->solid, cc->nc, &cc->work, cc->nc, &cc->ppe));
  DecompCellWork(g, P, cc->work, NULL);
  for (PetscInt a = 0; a < P->n; a++) {
    PetscInt c = GridCellOf(g, x + P->dim * a);
    if (c < 0) continue;
    cc->all[c]++;
    if (KindIsFluid(P->kind[a])) cc->fluid[c]++;
    else cc->bnd[c]++;
    if (KindIsSolid(P->kind[a])) cc->solid[c]++;
  }
  if (solid_weight > 0) /* solids re-weighted: fluid 4, wall/dummy 1, solid/clamp solid_weight */
    for (PetscInt c = 0; c < cc->nc; c++) cc->work[c] = DecompKindCost(KIND_FLUID) * cc->fluid[c] + DecompKindCost(KIND_WALL) * (cc->bnd[c] - cc->solid[c]) + solid_weight * cc->solid[c];
  PetscCall(PetscMalloc1(cc->nc, &cc->cost));
  for (PetscInt c = 0; c < cc->nc; c++) cc->cost[c] = DecompKindCost(KIND_FLUID) * cc->fluid[c] + DecompKindCost(KIND_WALL) * (cc->bnd[c] - cc->solid[c]) + solid_cost * cc->solid[c];
  /* PPE rows: fluid, and boundary particles of cells next to a fluid cell */
  for (PetscInt c = 0; c < cc->nc; c++) {
    PetscInt  nb[26], nn = GridCellNeighbours(g, c, nb);
    PetscBool near = (PetscBool)(cc->fluid[c] > 0);
    for (PetscInt k = 0; k < nn && !near; k++)
      if (cc->fluid[nb[k]] > 0) near = PETSC_TRUE;
    cc->ppe[c] = cc->fluid[c] + (near ? cc->bnd[c] : 0);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void MaxMean(const PetscInt *v, PetscInt n, PetscInt *max, PetscReal *mean)
{
  PetscReal s = 0;
  *max = 0;
  for (PetscInt r = 0; r < n; r++) { *max = PetscMax(*max, v[r]); s += v[r]; }
  *mean = s / n;
}

/* Statistics of one partition; `seen` (np x np bits) marks neighbouring rank pairs. */
static PetscErrorCode PartitionStats(Sim sim, const CellCounts *cc, PetscInt np, const PetscMPIInt *owner, double metis_s)
{
  const Grid    *g = &sim->grid;
  PetscInt      *owned, *work, *ppe, *halo, *nbrs, *solid, cut = 0, mx[6];
  PetscReal      mean[6], *cost, cmax = 0, csum = 0;
  PetscBT        seen;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc6(np, &owned, np, &work, np, &ppe, np, &halo, np, &nbrs, np, &solid));
  PetscCall(PetscBTCreate(np * np, &seen));
  PetscCall(PetscCalloc1(np, &cost));
  for (PetscInt c = 0; c < cc->nc; c++) {
    PetscInt    got[26], ngot = 0, nb[26], nn = GridCellNeighbours(g, c, nb);
    PetscMPIInt r = owner[c];
    owned[r] += cc->all[c]; work[r] += cc->work[c]; ppe[r] += cc->ppe[c]; solid[r] += cc->solid[c]; cost[r] += cc->cost[c];
    for (PetscInt k = 0; k < nn; k++) {
      PetscInt    cn = nb[k], dup = 0;
      PetscMPIInt q;
      if ((q = owner[cn]) == r) continue;
      if (cn > c) cut++; /* each cut edge once (both ends different cells) */
      for (PetscInt l = 0; l < ngot; l++) dup |= got[l] == q;
      if (dup) continue;
      got[ngot++] = q;
      halo[q] += cc->all[c]; /* rank q needs this cell's particles as ghosts */
      /* a message from r to q only if there is something to send: cells of two ranks that meet
       * in empty space exchange nothing (HaloBuild loops over particles) */
      if (cc->all[c] && !PetscBTLookupSet(seen, (PetscInt)q * np + r)) nbrs[q]++;
    }
  }
  MaxMean(owned, np, &mx[0], &mean[0]);
  MaxMean(work, np, &mx[1], &mean[1]);
  MaxMean(ppe, np, &mx[2], &mean[2]);
  MaxMean(halo, np, &mx[3], &mean[3]);
  MaxMean(nbrs, np, &mx[4], &mean[4]);
  MaxMean(solid, np, &mx[5], &mean[5]);
  for (PetscInt r = 0; r < np; r++) { cmax = PetscMax(cmax, cost[r]); csum += cost[r]; }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s,%d,%d,%d,", sim->scene->name, (int)sim->nbhd.nparticles, (int)cc->nc, (int)np));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%d,%.1f,%d,%.1f,%.4f,", (int)mx[0], (double)mean[0], (int)mx[1], (double)mean[1], (double)(mx[1] / mean[1])));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%d,%.1f,%.4f,%d,%.1f,%d,", (int)mx[2], (double)mean[2], (double)(mx[2] / mean[2]), (int)mx[3], (double)mean[3], (int)cut));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%d,%.2f,%d,%.2f,%.1f,%.1f,%.2f\n", (int)mx[4], (double)mean[4], (int)mx[5], (double)mean[5], (double)cmax, (double)(csum / np), metis_s));
  PetscCall(PetscBTDestroy(&seen));
  PetscCall(PetscFree(cost));
  PetscCall(PetscFree6(owned, work, ppe, halo, nbrs, solid));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim          sim;
  CellCounts   cc;
  PetscMPIInt  size, *owner;
  PetscInt     npmax = 1024, solid_weight = 0;
  PetscBool    split = PETSC_FALSE;
  PetscReal    solid_cost = -1;
  PetscBool    header = PETSC_TRUE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Partition statistics of a scene's cell graph for 2..nparts_max ranks (CSV)\n"));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCheck(size == 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "Run partition_model on one process");
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-nparts_max", &npmax, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-header", &header, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-solid_weight", &solid_weight, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-split_solids", &split, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-solid_cost", &solid_cost, NULL));
  if (solid_cost < 0) solid_cost = solid_weight > 0 ? solid_weight : DecompKindCost(KIND_SOLID);
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(BuildScene(sim));
  sim->nbhd.nparticles = sim->P->n;
  PetscCall(CountCells(sim, solid_weight, solid_cost, &cc));
  PetscCall(PetscMalloc1(cc.nc, &owner));
  if (header) PetscCall(PetscPrintf(PETSC_COMM_SELF, "case,particles,cells,ranks,owned_max,owned_mean,work_max,work_mean,work_imbalance,ppe_rows_max,ppe_rows_mean,ppe_imbalance,halo_max,halo_mean,cut_edges,nbr_ranks_max,nbr_ranks_mean,solid_max,solid_mean,cost_max,cost_mean,metis_s\n"));
  for (PetscInt np = 2; np <= npmax; np *= 2) {
    PetscLogDouble t0, t1;
    PetscCall(PetscTime(&t0));
    PetscCall(DecompPartitionCells(&sim->grid, cc.work, split ? cc.solid : NULL, np, owner));
    PetscCall(PetscTime(&t1));
    PetscCall(PartitionStats(sim, &cc, np, owner, t1 - t0));
  }
  PetscCall(PetscFree(owner));
  PetscCall(PetscFree6(cc.all, cc.fluid, cc.bnd, cc.solid, cc.work, cc.ppe));
  PetscCall(PetscFree(cc.cost));
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
