/* The neighbourhood: after the particles moved, brings the parallel machinery and the neighbour
 * lists up to date (the fluid leaving an open boundary, migration, rebalancing, ghosts, cells, the
 * Verlet skin).  It owns none of the particles or machinery it works on: the driver creates those
 * and wires them in (NeighbourhoodWire); physics asks it for an update, never the driver. */
#pragma once
#include "particles/particles.h"
#include "particles/grid.h"
#include "particles/cells.h"
#include "particles/decomp.h"
#include "particles/halo.h"

typedef struct {
  MPI_Comm    comm;
  Particles   P;
  const Grid *grid;
  Decomp      decomp;
  Halo        halo;
  Cells       cells;
  PetscBool   periodic[3];
  PetscBool   outflow;    /* fluid leaving the domain box is removed (open boundary) */
  PetscReal   skin;       /* Verlet skin of the main list (m; -wcsph_skin): 0 rebuilds at every update */
  PetscInt    nrebuild;   /* rebuilds of the main list by NeighbourhoodUpdate */
  PetscInt    nparticles; /* particles in the run (the outflow removes some) */
  PetscReal   mass_out;   /* fluid mass removed by the outflow */
  PetscBool   rebuild;    /* the next update rebuilds (particles are to be created: the inflow) */
  /* particles the physics creates (an inflow) are added here, in every full rebuild after the
   * outflow and before migration, while no ghosts exist (NULL: none) */
  PetscErrorCode (*inflow)(void *ctx);
  void *inflow_ctx;
  PetscLogStage stage_halo, stage_neighbour;
} Neighbourhood;

/* The particles and machinery to work on, the boundary's kind and the log stages to push: the
 * neighbourhood's work logs in stage_neighbour, its moves of particles between ranks and every ghost
 * refresh of the halo (whoever asks for it) in stage_halo. */
PetscErrorCode NeighbourhoodWire(Neighbourhood *nb, MPI_Comm comm, Particles P, const Grid *grid, Decomp decomp, Halo halo, Cells cells, const PetscBool periodic[], PetscBool outflow, PetscLogStage stage_halo, PetscLogStage stage_neighbour);
/* Outflow, migration, rebalancing (on the steps that may: DecompBalance), sort, ghosts, cells and
 * lists: after particles moved. */
PetscErrorCode NeighbourhoodRebuild(Neighbourhood *nb, PetscInt step);
/* After the particles moved: NeighbourhoodRebuild, or with a skin, while no particle has moved
 * skin / 2 since the last rebuild (and the step is not one that may rebalance), the ghosts take their
 * owners' new state and the list its pairs at the new positions (CellsRefreshPairs). */
PetscErrorCode NeighbourhoodUpdate(Neighbourhood *nb, PetscInt step);
/* The rebuild without outflow or rebalancing (a restart repeats the last rebuild of the run). */
PetscErrorCode NeighbourhoodRebuildKeepPartition(Neighbourhood *nb, PetscInt step);
/* A neighbour list of some kinds over the current cells (CellsBuildSubList: the solid's), logged as
 * the neighbourhood's. */
PetscErrorCode NeighbourhoodSubList(Neighbourhood *nb, PetscBool (*keep)(PetscInt), PetscReal skin, Cells sub);
