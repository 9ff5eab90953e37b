#include "particles/decomp.h"
#include "base/options_used.h"
#include "particles/exchange.h"
#include <metis.h>
#include <signal.h>

/* Relative work of a particle by kind: fluid and solid particles run every neighbour pass, wall
 * and dummy particles only the light wall-state pass. Used to weight cells and measure balance. */
static const PetscInt KindCost[KIND_COUNT] = {4, 1, 1, 4, 1};

static PetscInt Work(Particles P)
{
  PetscInt w = 0;
  for (PetscInt a = 0; a < P->n; a++) w += KindCost[P->kind[a]];
  return w;
}

static PetscInt SolidCount(Particles P)
{
  PetscInt n = 0;
  for (PetscInt a = 0; a < P->n; a++) n += KindIsSolid(P->kind[a]);
  return n;
}

PetscErrorCode DecompCreate(MPI_Comm comm, Decomp *d)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(d));
  (*d)->comm        = comm;
  (*d)->threshold   = 1.1;
  (*d)->check_every = 20;
  (*d)->split_solids = PETSC_TRUE;
  PetscCallMPI(MPI_Comm_rank(comm, &(*d)->rank));
  PetscCallMPI(MPI_Comm_size(comm, &(*d)->size));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompSetFromOptions(Decomp d)
{
  PetscInt sparse_ranks = 9; /* dense below: one round fewer (2 ranks: +6 % halo stage sparse) */
  PetscFunctionBeginUser;
  PetscOptionsBegin(d->comm, NULL, "Domain decomposition", "Decomp");
  PetscCall(OptReal("-rebalance_threshold", "Repartition when max/mean work per rank exceeds this (>= 1)", "", d->threshold, &d->threshold, NULL));
  PetscCall(OptInt("-rebalance_every", "Steps between load-imbalance checks (> 0)", "", d->check_every, &d->check_every, NULL));
  PetscCall(OptInt("-decomp_sparse_ranks", "From this many ranks on, migration and ghosts go to the ranks concerned only (a two-sided set-up, see -build_twosided) instead of MPI_Alltoallv, whose cost grows with the ranks", "", sparse_ranks, &sparse_ranks, NULL));
  PetscCall(OptBool("-decomp_log_stats", "Record each rank's ghosts, owned particles, work and neighbour ranks after every rebuild (and ISPH's PPE rows per step) and write their max and sum over the ranks to OUTDIR/partition_stats.csv at the end (tools/count_traffic.sh); the results do not change", "", d->log_stats, &d->log_stats, NULL));
  PetscCall(OptBool("-decomp_split_solids", "With fluid and solids: balance the solid particles over the ranks as a second METIS constraint (the solid sub-steps are a phase of their own)", "", d->split_solids, &d->split_solids, NULL));
  PetscOptionsEnd();
  PetscCheck(d->threshold >= 1.0, d->comm, PETSC_ERR_ARG_OUTOFRANGE, "-rebalance_threshold %g must be >= 1", (double)d->threshold);
  PetscCheck(sparse_ranks > 0, d->comm, PETSC_ERR_ARG_OUTOFRANGE, "-decomp_sparse_ranks %" PetscInt_FMT " must be > 0", sparse_ranks);
  d->sparse = (PetscBool)(d->size >= sparse_ranks);
  PetscCheck(d->check_every > 0, d->comm, PETSC_ERR_ARG_OUTOFRANGE, "-rebalance_every %" PetscInt_FMT " must be > 0", d->check_every);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompSetUp(Decomp d, const Grid *g)
{
  PetscFunctionBeginUser;
  d->grid = g;
  PetscCall(PetscFree3(d->owner, d->wcount, d->scount));
  PetscCall(PetscCalloc3(GridNumCells(g), &d->owner, GridNumCells(g), &d->wcount, GridNumCells(g), &d->scount));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompDestroy(Decomp *d)
{
  PetscFunctionBeginUser;
  if (!*d) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree3((*d)->owner, (*d)->wcount, (*d)->scount));
  PetscCall(PetscFree((*d)->log[0]));
  PetscCall(PetscFree((*d)->log[1]));
  PetscCall(PetscFree(*d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Owner of every empty cell: that of the nearest occupied cell (breadth-first over the 8 (3D: 26)
 * neighbours, periodic wrap; ties go to the cell reached first, so the result is deterministic). */
static PetscErrorCode OwnEmptyCells(const Grid *g, const PetscInt *count, PetscMPIInt *owner)
{
  PetscInt nc = GridNumCells(g), *queue, head = 0, tail = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nc, &queue));
  for (PetscInt c = 0; c < nc; c++)
    if (count[c]) queue[tail++] = c;
    else owner[c] = -1;
  while (head < tail) {
    PetscInt c = queue[head++], nb[26], nn = GridCellNeighbours(g, c, nb);
    for (PetscInt k = 0; k < nn; k++) {
      if (owner[nb[k]] >= 0) continue;
      owner[nb[k]]  = owner[c];
      queue[tail++] = nb[k];
    }
  }
  PetscCall(PetscFree(queue));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* k-way partition of the cell graph (8 neighbours, 26 in 3D, periodic wrap), serial (rank 0).  Only the
 * occupied cells are vertices: the dam break's tall tank is mostly empty (410k particles: 64k of
 * 900k cells occupied), and METIS on the whole grid took more memory on rank 0 than its share of the
 * particles; empty cells then go to the owner of the nearest occupied cell (OwnEmptyCells).
 * Vertex weight 32 work + 1; edge weight work_i + work_j + 1, a proxy for the ghosts a cut edge
 * creates.  Second constraint (scount): the solid particles. */
PetscErrorCode DecompPartitionCells(const Grid *g, const PetscInt *count, const PetscInt *scount, PetscInt nranks, PetscMPIInt *owner)
{
  idx_t nc = GridNumCells(g), nv = 0, ncon = scount ? 2 : 1, nparts = nranks, objval, *xadj, *adj, *vw, *ew, *part, *vert, ne = 0, wscale;
  idx_t opts[METIS_NOPTIONS];
  int   status;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nc, &vert)); /* vertex of an occupied cell, -1 for an empty one */
  for (PetscInt c = 0; c < nc; c++) vert[c] = count[c] ? nv++ : -1;
  if (nv < nranks) PetscCall(PetscFree(vert));
  PetscCheck(nv >= nranks, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Only %d occupied cells for %d ranks: use fewer ranks or a smaller -dx", (int)nv, (int)nranks);
  { /* the weight scale, kept small enough for METIS's 32-bit sums */
    PetscInt64 wsum = 0;
    for (PetscInt c = 0; c < nc; c++) wsum += count[c];
    wscale = (idx_t)PetscMax(1, PetscMin(32, (PetscInt64)PETSC_MAX_INT / 4 / (wsum + nv)));
  }
  {
    const idx_t maxdeg = g->dim == 3 ? 26 : 8;
    PetscCall(PetscMalloc5(nv + 1, &xadj, maxdeg * nv, &adj, ncon * nv, &vw, maxdeg * nv, &ew, nv, &part));
  }
  for (PetscInt c = 0; c < nc; c++) {
    PetscInt v = vert[c], nb[26], nn;
    if (v < 0) continue;
    xadj[v]      = ne;
    vw[ncon * v] = wscale * count[c] + 1;
    if (scount) vw[2 * v + 1] = scount[c];
    nn = GridCellNeighbours(g, c, nb);
    for (PetscInt k = 0; k < nn; k++) {
      PetscInt n = nb[k];
      if (vert[n] < 0) continue;
      adj[ne] = vert[n];
      ew[ne]  = count[c] + count[n] + 1;
      ne++;
    }
  }
  xadj[nv] = ne;
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_SEED]      = 1;
  opts[METIS_OPTION_NUMBERING] = 0;
  { /* METIS (its GKlib) sets its own SIGTERM and SIGABRT handlers for the call and puts the old ones
     back with System V signal(): one-shot.  After a partition rank 0's stop handler then reset itself
     at the first SIGTERM, and the second SIGTERM that SLURM sends at a time limit killed the stop
     (tools/slurm_check.sh).  The dispositions are restored whole, and SIGTERM waits in this thread
     until they are (METIS's handler would end the call with METIS_ERROR). */
    struct sigaction term, abrt;
    sigset_t         block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGTERM);
    PetscCheck(!pthread_sigmask(SIG_BLOCK, &block, &old), PETSC_COMM_SELF, PETSC_ERR_SYS, "pthread_sigmask failed");
    PetscCheck(!sigaction(SIGTERM, NULL, &term) && !sigaction(SIGABRT, NULL, &abrt), PETSC_COMM_SELF, PETSC_ERR_SYS, "sigaction failed");
    status = METIS_PartGraphKway(&nv, &ncon, xadj, adj, vw, NULL, ew, &nparts, NULL, NULL, opts, &objval, part);
    PetscCheck(!sigaction(SIGTERM, &term, NULL) && !sigaction(SIGABRT, &abrt, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "sigaction failed");
    PetscCheck(!pthread_sigmask(SIG_SETMASK, &old, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "pthread_sigmask failed");
  }
  for (PetscInt c = 0; c < nc; c++)
    if (vert[c] >= 0) owner[c] = (PetscMPIInt)part[vert[c]]; /* the empty ones: OwnEmptyCells */
  PetscCall(PetscFree5(xadj, adj, vw, ew, part));
  PetscCall(PetscFree(vert));
  PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway failed with status %d", status);
  PetscCall(OwnEmptyCells(g, count, owner));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void DecompCellWork(const Grid *g, Particles P, PetscInt *wcount, PetscInt *scount)
{
  const PetscReal *x = PField(P, FIELD_X);
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal xa[3] = {x[P->dim * a], x[P->dim * a + 1], P->dim == 3 ? x[P->dim * a + 2] : 0};
    PetscInt  c;
    GridWrap(g, xa);
    c = GridCellOf(g, xa);
    if (c < 0) continue;
    wcount[c] += KindCost[P->kind[a]];
    if (scount && KindIsSolid(P->kind[a])) scount[c]++;
  }
}

PetscInt DecompKindCost(PetscInt kind) { return KindCost[kind]; }

/* A new partition from the current particles.  METIS needs an occupied cell per rank: at set-up
 * (setup) fewer are an input error on every rank, naming the most ranks that can run; later (a
 * rebalance) the current partition is kept (*done false), since particles that gather in fewer cells
 * than ranks are no reason to stop a run. */
static PetscErrorCode Partition(Decomp d, Particles P, PetscBool setup, PetscBool *done)
{
  const Grid *g  = d->grid;
  PetscInt    nc = GridNumCells(g), *gcount = NULL, *gscount = NULL, nsolid = 0;
  PetscInt    res[2] = {PETSC_SUCCESS, 0}; /* rank 0's METIS status, occupied cells */

  PetscFunctionBeginUser;
  *done = PETSC_TRUE;
  PetscCall(PetscArrayzero(d->wcount, nc));
  PetscCall(PetscArrayzero(d->scount, nc));
  DecompCellWork(g, P, d->wcount, d->split_solids ? d->scount : NULL);
  if (d->size == 1) {
    PetscCall(PetscArrayzero(d->owner, nc));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (d->split_solids) {
    nsolid = SolidCount(P);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nsolid, 1, MPIU_INT, MPI_SUM, d->comm));
  }
  if (!d->rank) PetscCall(PetscMalloc2(nc, &gcount, nsolid ? nc : 0, &gscount));
  PetscCallMPI(MPI_Reduce(d->wcount, gcount, (PetscMPIInt)nc, MPIU_INT, MPI_SUM, 0, d->comm));
  if (nsolid) PetscCallMPI(MPI_Reduce(d->scount, gscount, (PetscMPIInt)nc, MPIU_INT, MPI_SUM, 0, d->comm));
  if (!d->rank) {
    for (PetscInt c = 0; c < nc; c++) res[1] += gcount[c] > 0;
    if (res[1] >= d->size) res[0] = DecompPartitionCells(g, gcount, nsolid ? gscount : NULL, d->size, d->owner);
    PetscCall(PetscFree2(gcount, gscount));
  }
  PetscCallMPI(MPI_Bcast(res, 2, MPIU_INT, 0, d->comm));
  if (res[1] < d->size) {
    PetscCheck(!setup, d->comm, PETSC_ERR_ARG_OUTOFRANGE, "%d ranks for %" PetscInt_FMT " cells that hold particles (of %" PetscInt_FMT " cells of %g m; each rank needs one): run on at most %" PetscInt_FMT " ranks, or with a smaller -dx", d->size, res[1], nc, (double)g->cs, res[1]);
    PetscCall(PetscInfo(NULL, "%" PetscInt_FMT " occupied cells for %d ranks: the partition is kept\n", res[1], d->size));
    *done = PETSC_FALSE;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(!res[0], d->comm, PETSC_ERR_LIB, "Partitioning the cell graph failed (see the message from rank 0)");
  PetscCallMPI(MPI_Bcast(d->owner, (PetscMPIInt)nc, MPI_INT, 0, d->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompPartition(Decomp d, Particles P)
{
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(Partition(d, P, PETSC_TRUE, &done));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Pack the owned particle a as a record of reals: id, kind, then every allocated field. */
static PetscInt RecordSize(Particles P)
{
  PetscInt s = 2;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on) s += P->f[f].width;
  return s;
}

static void PackRecord(Particles P, PetscInt a, PetscReal *r)
{
  PetscInt k = 0;
  r[k++] = (PetscReal)P->id[a];
  r[k++] = (PetscReal)P->kind[a];
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    if (!P->f[f].on) continue;
    for (PetscInt w = 0; w < P->f[f].width; w++) r[k++] = P->f[f].a[a * P->f[f].width + w];
  }
}

static void UnpackRecord(Particles P, PetscInt a, const PetscReal *r)
{
  PetscInt k = 0;
  P->id[a]   = (PetscInt)r[k++];
  P->kind[a] = (PetscInt)r[k++];
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    if (!P->f[f].on) continue;
    for (PetscInt w = 0; w < P->f[f].width; w++) P->f[f].a[a * P->f[f].width + w] = r[k++];
  }
}

static void CopyParticle(Particles P, PetscInt to, PetscInt from)
{
  P->id[to] = P->id[from]; P->kind[to] = P->kind[from];
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    PetscInt w = P->f[f].width;
    if (!P->f[f].on) continue;
    for (PetscInt k = 0; k < w; k++) P->f[f].a[to * w + k] = P->f[f].a[from * w + k];
  }
}

/* The grid's box "[x0, x1] x [y0, y1]" (x [z0, z1]) */
static void FormatBox(char *buf, size_t len, const Grid *g)
{
  if (g->dim == 3) snprintf(buf, len, "[%g, %g] x [%g, %g] x [%g, %g]", (double)g->lo[0], (double)g->hi[0], (double)g->lo[1], (double)g->hi[1], (double)g->lo[2], (double)g->hi[2]);
  else snprintf(buf, len, "[%g, %g] x [%g, %g]", (double)g->lo[0], (double)g->hi[0], (double)g->lo[1], (double)g->hi[1]);
}

PetscErrorCode DecompMigrate(Decomp d, Particles P)
{
  const Grid  *g = d->grid;
  PetscMPIInt  size = d->size, *scnt, *rcnt, *sdisp, *rdisp;
  PetscInt     rs = RecordSize(P), nsend = 0, nrecv = 0, nkeep = 0, nbad = 0, gbad;
  PetscInt    *dest;
  PetscReal   *sbuf, *rbuf, *x = PField(P, FIELD_X);
  const PetscInt D = P->dim;

  PetscFunctionBeginUser;
  P->ng = 0;
  PetscCall(PetscMalloc1(P->n, &dest));
  PetscCall(PetscCalloc4(size, &scnt, size, &rcnt, size + 1, &sdisp, size + 1, &rdisp));
  for (PetscInt a = 0; a < P->n; a++) {
    PetscInt c;
    GridWrap(g, x + D * a);
    c = GridCellOf(g, x + D * a);
    if (c < 0) {
      char at[96], box[160];
      GridFormatPoint(at, sizeof(at), D, x + D * a);
      FormatBox(box, sizeof(box), g);
      if (!nbad) PetscCall(PetscPrintf(PETSC_COMM_SELF, "[%d] particle id %" PetscInt_FMT " (%s) at %s is outside the domain %s\n", d->rank, P->id[a], ParticleKindNames[P->kind[a]], at, box));
      nbad++;
      dest[a] = d->rank;
      continue;
    }
    dest[a] = d->owner[c];
    if (dest[a] != d->rank) { scnt[dest[a]]++; nsend++; }
  }
  PetscCall(MPIU_Allreduce(&nbad, &gbad, 1, MPIU_INT, MPI_SUM, d->comm));
  if (gbad) { /* name one of them in the message every rank raises */
    PetscReal mine[5] = {-1, 0, 0, 0, 0}, *all;
    PetscInt  r = 0;
    char      at[96], box[160];
    for (PetscInt a = 0; a < P->n && nbad; a++)
      if (GridCellOf(g, x + D * a) < 0) {
        mine[0] = P->id[a]; mine[1] = P->kind[a];
        for (PetscInt k = 0; k < D; k++) mine[2 + k] = x[D * a + k];
        break;
      }
    PetscCall(PetscMalloc1(5 * size, &all));
    PetscCallMPI(MPI_Allgather(mine, 5, MPIU_REAL, all, 5, MPIU_REAL, d->comm));
    while (all[5 * r] < 0) r++;
    GridFormatPoint(at, sizeof(at), D, all + 5 * r + 2);
    FormatBox(box, sizeof(box), g);
    PetscCall(PetscFree(dest));
    PetscCall(PetscFree4(scnt, rcnt, sdisp, rdisp));
    SETERRQ(d->comm, PETSC_ERR_NOT_CONVERGED, "%" PetscInt_FMT " particle(s) left the domain %s, e.g. id %d (%s) at %s: the run is unstable (try a smaller -dt or -cfl) or the geometry lets particles escape", gbad, box, (int)all[5 * r], ParticleKindNames[(PetscInt)all[5 * r + 1]], at);
  }
  if (size == 1) { PetscCall(PetscFree(dest)); PetscCall(PetscFree4(scnt, rcnt, sdisp, rdisp)); PetscFunctionReturn(PETSC_SUCCESS); }
  for (PetscMPIInt r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scnt[r];
  PetscCall(PetscMalloc1(nsend * rs + 1, &sbuf));
  {
    PetscMPIInt *fill;
    PetscCall(PetscMalloc1(size, &fill));
    for (PetscMPIInt r = 0; r < size; r++) fill[r] = sdisp[r];
    for (PetscInt a = 0; a < P->n; a++) {
      if (dest[a] == d->rank) { if (nkeep != a) CopyParticle(P, nkeep, a); nkeep++; continue; }
      PackRecord(P, a, sbuf + (fill[dest[a]]++) * rs);
    }
    PetscCall(PetscFree(fill));
  }
  PetscCall(ExchangeRecords(d->comm, d->sparse, rs, scnt, sdisp, sbuf, rcnt, rdisp, &rbuf, &nrecv));
  P->n = nkeep;
  PetscCall(ParticlesReserve(P, nkeep + nrecv));
  for (PetscInt k = 0; k < nrecv; k++) UnpackRecord(P, nkeep + k, rbuf + k * rs);
  P->n = nkeep + nrecv;
  PetscCall(PetscFree(sbuf));
  PetscCall(PetscFree(rbuf));
  PetscCall(PetscFree(dest));
  PetscCall(PetscFree4(scnt, rcnt, sdisp, rdisp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static int CompareKeys(const void *a, const void *b, void *ctx)
{
  PetscInt64 ka = *(const PetscInt64 *)a, kb = *(const PetscInt64 *)b;
  return ka < kb ? -1 : (ka > kb ? 1 : 0);
}

PetscErrorCode DecompSortOwned(Decomp d, Particles P)
{
  PetscInt64 *key, stride;
  PetscInt   *perm, maxid = 0, n = P->n;
  PetscBool   sorted = PETSC_TRUE;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < n; a++) maxid = PetscMax(maxid, P->id[a]);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &maxid, 1, MPIU_INT, MPI_MAX, d->comm));
  stride = (PetscInt64)maxid + 1;
  PetscCall(PetscMalloc2(n, &key, n, &perm));
  for (PetscInt a = 0; a < n; a++) {
    key[a]  = (PetscInt64)GridCellOf(d->grid, PField(P, FIELD_X) + P->dim * a) * stride + P->id[a];
    perm[a] = a;
    if (a && key[a] < key[a - 1]) sorted = PETSC_FALSE;
  }
  if (!sorted) {
    /* timsort: nearly sorted input (the usual case between steps) costs O(n) */
    PetscCall(PetscTimSortWithArray(n, key, sizeof(PetscInt64), perm, sizeof(PetscInt), CompareKeys, NULL));
    PetscCall(ParticlesPermute(P, perm));
  }
  PetscCall(PetscFree2(key, perm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompBalance(Decomp d, Particles P, PetscInt step, PetscBool *repartitioned)
{
  PetscInt w[4], wmax[4], wsum[4], nfluid = 0;

  PetscFunctionBeginUser;
  *repartitioned = PETSC_FALSE;
  if (d->size == 1 || step % d->check_every) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt a = 0; a < P->n; a++) nfluid += KindIsFluid(P->kind[a]);
  w[0] = Work(P);
  w[1] = d->split_solids ? SolidCount(P) : 0;
  /* ranks left without particles or without fluid (counted in the same reduction, no extra message):
   * summary.json reports the most at one check, so a test can tell that such ranks did occur */
  w[2] = P->n == 0;
  w[3] = nfluid == 0;
  PetscCall(MPIU_Allreduce(w, wmax, 4, MPIU_INT, MPI_MAX, d->comm));
  PetscCall(MPIU_Allreduce(w, wsum, 4, MPIU_INT, MPI_SUM, d->comm));
  d->empty_max   = PetscMax(d->empty_max, wsum[2]);
  d->nofluid_max = PetscMax(d->nofluid_max, wsum[3]);
  d->imbalance       = wsum[0] ? (PetscReal)wmax[0] * d->size / wsum[0] : 1.0;
  d->imbalance_solid = wsum[1] ? (PetscReal)wmax[1] * d->size / wsum[1] : 1.0;
  if (d->imbalance <= d->threshold && d->imbalance_solid <= d->threshold) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscInfo(NULL, "Step %" PetscInt_FMT ": imbalance %.3f (solids %.3f) > %.3f, repartitioning\n", step, (double)d->imbalance, (double)d->imbalance_solid, (double)d->threshold));
  PetscCall(Partition(d, P, PETSC_FALSE, repartitioned));
  if (!*repartitioned) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DecompMigrate(d, P));
  d->nrepartition++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompView(Decomp d, PetscViewer v)
{
  char cells[64];
  PetscFunctionBeginUser;
  if (d->grid->dim == 3) PetscCall(PetscSNPrintf(cells, sizeof(cells), "%" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT, d->grid->n[0], d->grid->n[1], d->grid->n[2]));
  else PetscCall(PetscSNPrintf(cells, sizeof(cells), "%" PetscInt_FMT " x %" PetscInt_FMT, d->grid->n[0], d->grid->n[1]));
  PetscCall(PetscViewerASCIIPrintf(v, "Decomposition: %d rank(s), %s cells of %g m, rebalance past %.2f (checked every %" PetscInt_FMT " steps), %" PetscInt_FMT " repartition(s), %s exchanges\n", d->size, cells, (double)d->grid->cs, (double)d->threshold, d->check_every, d->nrepartition, d->sparse ? "sparse" : "all-to-all"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Append one record of LogWidth[which] reals (the step first) to the log `which` (0: rebuilds, 1: PPE rows). */
static const PetscInt LogWidth[2] = {6, 2};

static PetscErrorCode LogAppend(Decomp d, PetscInt which, const PetscReal *rec)
{
  const PetscInt w = LogWidth[which];
  PetscFunctionBeginUser;
  if (d->nlog[which] == d->caplog[which]) {
    PetscReal *a;
    d->caplog[which] = 2 * d->caplog[which] + 64;
    PetscCall(PetscMalloc1(w * d->caplog[which], &a));
    if (d->nlog[which]) PetscCall(PetscArraycpy(a, d->log[which], w * d->nlog[which]));
    PetscCall(PetscFree(d->log[which]));
    d->log[which] = a;
  }
  PetscCall(PetscArraycpy(d->log[which] + w * d->nlog[which]++, rec, w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompLogRebuild(Decomp d, Particles P, PetscInt nbr, PetscInt step)
{
  PetscReal rec[6] = {(PetscReal)step, (PetscReal)P->ng, (PetscReal)P->n, (PetscReal)Work(P), (PetscReal)nbr, P->n ? (PetscReal)P->ng / P->n : 0};
  PetscFunctionBeginUser;
  PetscCall(LogAppend(d, 0, rec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompLogRows(Decomp d, PetscInt nrow, PetscInt step)
{
  PetscReal rec[2] = {(PetscReal)step, (PetscReal)nrow};
  PetscFunctionBeginUser;
  PetscCall(LogAppend(d, 1, rec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DecompWriteStats(Decomp d, const char *outdir)
{
  const char *file[2] = {"partition_stats.csv", "ppe_rows.csv"}, *names[2][6] = {{"step", "ghosts", "owned", "work", "nbr_ranks", "ghosts_per_owned"}, {"step", "ppe_rows"}};
  PetscFunctionBeginUser;
  for (PetscInt which = 0; which < 2; which++) {
    const PetscInt w = LogWidth[which], n = d->nlog[which];
    PetscReal     *mx = NULL, *sum = NULL;
    char           path[PETSC_MAX_PATH_LEN];
    FILE          *f = NULL;
    if (!n) continue; /* the same on every rank: records are made collectively */
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", outdir, file[which]));
    PetscCall(PetscFOpen(d->comm, path, "w", &f));
    PetscCall(PetscFPrintf(d->comm, f, "# %s: max and sum over %d rank(s) of each value, one row %s\nstep", file[which], d->size, which ? "per PPE numbering" : "per rebuild (ghosts, migration)"));
    for (PetscInt k = 1; k < w; k++) PetscCall(PetscFPrintf(d->comm, f, ",%s_max,%s_sum", names[which][k], names[which][k]));
    PetscCall(PetscFPrintf(d->comm, f, "\n"));
    if (!d->rank) PetscCall(PetscMalloc2(w * n, &mx, w * n, &sum));
    PetscCallMPI(MPI_Reduce(d->log[which], mx, (PetscMPIInt)(w * n), MPIU_REAL, MPI_MAX, 0, d->comm));
    PetscCallMPI(MPI_Reduce(d->log[which], sum, (PetscMPIInt)(w * n), MPIU_REAL, MPI_SUM, 0, d->comm));
    for (PetscInt r = 0; r < n && !d->rank; r++) {
      PetscCall(PetscFPrintf(PETSC_COMM_SELF, f, "%.0f", (double)mx[w * r]));
      for (PetscInt k = 1; k < w; k++) PetscCall(PetscFPrintf(PETSC_COMM_SELF, f, ",%.10g,%.10g", (double)mx[w * r + k], (double)sum[w * r + k]));
      PetscCall(PetscFPrintf(PETSC_COMM_SELF, f, "\n"));
    }
    PetscCall(PetscFree2(mx, sum));
    PetscCall(PetscFClose(d->comm, f));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
