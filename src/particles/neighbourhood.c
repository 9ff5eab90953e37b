#include "particles/neighbourhood.h"
#include "base/dim.h"

PetscErrorCode NeighbourhoodWire(Neighbourhood *nb, MPI_Comm comm, Particles P, const Grid *grid, Decomp decomp, Halo halo, Cells cells, const PetscBool periodic[], PetscBool outflow, PetscLogStage stage_halo, PetscLogStage stage_neighbour)
{
  PetscFunctionBeginUser;
  nb->comm   = comm;
  nb->P      = P;
  nb->grid   = grid;
  nb->decomp = decomp;
  nb->halo   = halo;
  nb->cells  = cells;
  for (PetscInt d = 0; d < 3; d++) nb->periodic[d] = periodic[d];
  nb->outflow         = outflow;
  nb->stage_halo      = stage_halo;
  nb->stage_neighbour = stage_neighbour;
  halo->stage         = stage_halo; /* every ghost refresh, whoever asks for it */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Open boundary: owned fluid particles outside the domain box leave the simulation. */
static PetscErrorCode Outflow(Neighbourhood *nb)
{
  Particles        P = nb->P;
  const PetscInt   D = P->dim;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M);
  PetscBool       *drop = NULL;
  PetscReal        buf[2] = {0, 0}; /* mass and count that left */
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscBool out = PETSC_FALSE;
    if (!KindIsFluid(P->kind[a])) continue;
    for (PetscInt d = 0; d < D; d++)
      if (!nb->periodic[d] && (x[D * a + d] < nb->grid->lo[d] || x[D * a + d] >= nb->grid->hi[d])) out = PETSC_TRUE;
    if (!out) continue;
    if (!drop) PetscCall(PetscCalloc1(P->n, &drop)); /* only in a step where fluid leaves */
    drop[a] = PETSC_TRUE;
    buf[0] += m[a]; buf[1] += 1;
  }
  if (drop) PetscCall(ParticlesRemove(P, drop));
  PetscCall(PetscFree(drop));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, buf, 2, MPIU_REAL, MPI_SUM, nb->comm));
  nb->mass_out += buf[0];
  nb->nparticles -= (PetscInt)buf[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* full: outflow and rebalancing first (every rebuild of a run; a restart repeats one without).
 * Logged in the neighbour stage, the particles' moves between ranks and the ghosts in the halo stage. */
static PetscErrorCode Rebuild(Neighbourhood *nb, PetscBool full, PetscInt step)
{
  PetscBool rep;
  Particles P = nb->P;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(nb->stage_neighbour));
  PetscCall(PetscLogStagePush(nb->stage_halo));
  if (full && nb->outflow) PetscCall(Outflow(nb));
  if (full && nb->inflow) {
    P->ng = 0; /* the ghosts are rebuilt below */
    PetscCall(nb->inflow(nb->inflow_ctx));
  }
  nb->rebuild = PETSC_FALSE;
  PetscCall(DecompMigrate(nb->decomp, P));
  if (full) PetscCall(DecompBalance(nb->decomp, P, step, &rep));
  PetscCall(PetscLogStagePop());
  PetscCall(DecompSortOwned(nb->decomp, P));
  PetscCall(PetscLogStagePush(nb->stage_halo));
  PetscCall(HaloBuild(nb->halo, nb->decomp, P));
  PetscCall(PetscLogStagePop());
  if (nb->decomp->log_stats) PetscCall(DecompLogRebuild(nb->decomp, P, nb->halo->nbr_send, step));
  PetscCall(CellsBuild(nb->cells, P));
  if (full && P->f[FIELD_XREB].on) PetscCall(PetscArraycpy(PField(P, FIELD_XREB), PField(P, FIELD_X), P->dim * P->n)); /* a restart has them */
  if (full && P->f[FIELD_XLIST].on) PetscCall(PetscArraycpy(PField(P, FIELD_XLIST), PField(P, FIELD_X), P->dim * P->n));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourhoodRebuild(Neighbourhood *nb, PetscInt step)
{
  PetscFunctionBeginUser;
  PetscCall(Rebuild(nb, PETSC_TRUE, step));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourhoodRebuildKeepPartition(Neighbourhood *nb, PetscInt step)
{
  PetscFunctionBeginUser;
  PetscCall(Rebuild(nb, PETSC_FALSE, step));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourhoodUpdate(Neighbourhood *nb, PetscInt step)
{
  Particles        P = nb->P;
  const PetscReal *x, *xr;
  const PetscInt   D = P->dim;
  PetscReal        d2 = 0, lim = 0.5 * nb->skin;
  FieldId          all[FIELD_COUNT];
  PetscInt         nf = 0;
  PetscFunctionBeginUser;
  if (nb->skin <= 0) {
    PetscCall(NeighbourhoodRebuild(nb, step));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  x  = PField(P, FIELD_X);
  xr = PField(P, FIELD_XREB);
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal d[3] = {0, 0, 0};
    VSub(x + D * a, xr + D * a, d, D);
    d2 = PetscMax(d2, VDot(d, d, D));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &d2, 1, MPIU_REAL, MPIU_MAX, nb->comm)); /* (in the caller's stage: the wait is the step's) */
  /* the steps that may rebalance rebuild on every number of ranks: the lists, and with them the
   * order of every sum, stay the same on 1 and on 2 ranks */
  if (d2 >= lim * lim || step % nb->decomp->check_every == 0 || nb->rebuild) { /* (rebuild: set on every rank alike) */
    PetscCall(NeighbourhoodRebuild(nb, step));
    nb->nrebuild++;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* the ghosts as a rebuild leaves them: the halo fields their owners', the others zero */
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    if (!P->f[f].on) continue;
    if (P->f[f].halo) all[nf++] = (FieldId)f;
    else PetscCall(PetscArrayzero(P->f[f].a + P->n * P->f[f].width, P->ng * P->f[f].width));
  }
  PetscCall(HaloRefresh(nb->halo, P, nf, all)); /* in the halo stage */
  PetscCall(PetscLogStagePush(nb->stage_neighbour));
  PetscCall(CellsRefreshPairs(nb->cells, P));
  if (P->f[FIELD_XLIST].on) PetscCall(PetscArraycpy(PField(P, FIELD_XLIST), x, D * P->n));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourhoodSubList(Neighbourhood *nb, PetscBool (*keep)(PetscInt), PetscReal skin, Cells sub)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(nb->stage_neighbour));
  PetscCall(CellsBuildSubList(nb->cells, nb->P, keep, skin, sub));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}
