/* Domain decomposition by cells: METIS k-way partition of the cell graph weighted by particle
 * counts; migration of particles whose cell changed owner; rebalancing past a threshold. */
#pragma once
#include "particles/grid.h"
#include "particles/particles.h"
#include <petscviewer.h>

typedef struct _p_Decomp *Decomp;
struct _p_Decomp {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  const Grid *grid;
  PetscMPIInt *owner;       /* owner rank of each global cell */
  PetscReal   threshold;    /* repartition when max/mean work per rank exceeds it */
  PetscInt    check_every;  /* steps between imbalance checks */
  PetscInt    nrepartition; /* repartitions after the first */
  PetscReal   imbalance;    /* at the last check */
  PetscInt    *wcount;      /* per-cell work (particles weighted by kind) */
  PetscBool   split_solids; /* balance the solid particles as a second constraint (FSI: the solid
                               sub-steps are a phase of their own, every rank should hold a share) */
  PetscInt    *scount;      /* per-cell solid + clamp particles, with split_solids */
  PetscReal   imbalance_solid;
  PetscBool   sparse;       /* exchange particles with the ranks concerned only (exchange.h) */
  PetscInt    empty_max;    /* most ranks that owned no particle at one imbalance check (this run) */
  PetscInt    nofluid_max;  /* most ranks that owned no fluid particle at one imbalance check */
  /* -decomp_log_stats: this rank's ghosts, owned particles, work and neighbour ranks after each
   * rebuild, and its PPE rows at each numbering, kept until the end (no communication before) */
  PetscBool   log_stats;
  PetscInt    nlog[2], caplog[2];
  PetscReal  *log[2];
};

PetscErrorCode DecompCreate(MPI_Comm comm, Decomp *d);
PetscErrorCode DecompSetFromOptions(Decomp d);
PetscErrorCode DecompSetUp(Decomp d, const Grid *g);
PetscErrorCode DecompDestroy(Decomp *d);
/* Serial METIS k-way partition of the graph of occupied cells (count > 0) into nranks parts for
 * per-cell work `count` and, when scount is not NULL, per-cell solid particles balanced as a second
 * constraint; an empty cell goes to the rank of a nearest occupied cell (what DecompPartition runs
 * on rank 0; also used by tools/partition_model.c). */
PetscErrorCode DecompPartitionCells(const Grid *g, const PetscInt *count, const PetscInt *scount, PetscInt nranks, PetscMPIInt *owner);
/* Add the kind-weighted work of the owned particles to wcount[cell] and, when scount is not NULL,
 * their solid and clamp particles to scount[cell]; the weight of one kind. */
void     DecompCellWork(const Grid *g, Particles P, PetscInt *wcount, PetscInt *scount);
PetscInt DecompKindCost(PetscInt kind);
/* New cell ownership from the current particle distribution (collective); at set-up: fewer occupied
 * cells than ranks are an input error (PETSC_ERR_ARG_OUTOFRANGE) naming the most ranks that can run. */
PetscErrorCode DecompPartition(Decomp d, Particles P);
/* Send every owned particle to the owner of its cell; positions are wrapped in periodic directions.
 * A particle outside the domain is an error naming it. Drops ghosts. */
PetscErrorCode DecompMigrate(Decomp d, Particles P);
/* Reorder owned particles by (cell, id): neighbours close in memory, order independent of ranks. */
PetscErrorCode DecompSortOwned(Decomp d, Particles P);
/* Every check_every steps: measure the imbalance of work (particles weighted by kind, fluid and
 * solid 4, walls 1) and, with split_solids, of the solid particles; repartition + migrate when
 * either is past the threshold (unless fewer cells than ranks are occupied: then the partition stays). */
PetscErrorCode DecompBalance(Decomp d, Particles P, PetscInt step, PetscBool *repartitioned);
PetscErrorCode DecompView(Decomp d, PetscViewer v);
/* With -decomp_log_stats (tools/count_traffic.sh): record the state after a rebuild (ghosts P->ng,
 * owned particles, work, ranks this rank sends ghosts to) or the PPE rows of this rank at a step;
 * at the end, DecompWriteStats reduces the records over the ranks (max and sum of each) and rank 0
 * writes OUTDIR/partition_stats.csv.  Off: nothing recorded, nothing written. */
PetscErrorCode DecompLogRebuild(Decomp d, Particles P, PetscInt nbr, PetscInt step);
PetscErrorCode DecompLogRows(Decomp d, PetscInt nrow, PetscInt step);
PetscErrorCode DecompWriteStats(Decomp d, const char *outdir);
