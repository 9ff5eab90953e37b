/* Ghost particles: copies of particles owned by other ranks (or periodic images) that lie in cells
 * adjacent to this rank's cells.  Built after migration; individual fields refreshed by PetscSF. */
#pragma once
#include "particles/decomp.h"
#include <petscsf.h>

/* the widest array refreshed: the total-Lagrangian solid's Q in 3D, 3 x 9 (HaloRefreshSlots) */
#define HALO_MAX_WIDTH 27

typedef struct _p_Halo *Halo;
struct _p_Halo {
  MPI_Comm    comm;
  PetscSF     sf;       /* roots: owned particles; leaves: ghost slots n .. n+ng */
  PetscInt   *shift;    /* per ghost: periodic image code 9 (sz+1) + 3 (sy+1) + (sx+1); 13 = none */
  PetscInt    cap_shift;
  MPI_Datatype unit[HALO_MAX_WIDTH + 1]; /* contiguous blocks of 1..HALO_MAX_WIDTH reals */
  PetscInt    nghost_sent;
  PetscInt    nbr_send;  /* other ranks this rank sends ghosts to (the messages of a refresh) */
  PetscReal   period[3]; /* domain lengths, for periodic shifts */
  /* the ghosts of some kinds only (HaloRefreshKinds): rebuilt after each HaloBuild on first use */
  PetscSF     sf_kinds;
  PetscBool (*kinds)(PetscInt);
  PetscInt   *kinds_ghost; /* their ghost offsets (0 .. ng) */
  PetscInt    nkinds;
  PetscLogStage stage; /* pushed around every refresh (NeighbourhoodWire: the halo stage); -1: none */
};

PetscErrorCode HaloCreate(MPI_Comm comm, Halo *h);
PetscErrorCode HaloDestroy(Halo *h);
/* Create ghosts of all fields marked `halo` (plus id, kind) and the SF for later refreshes. */
PetscErrorCode HaloBuild(Halo h, Decomp d, Particles P);
/* Copy the owners' current values of these fields into the ghosts.  The refreshes (this and the two
 * below) log in h->stage, wherever they are called from. */
PetscErrorCode HaloRefresh(Halo h, Particles P, PetscInt nf, const FieldId f[]);
/* The same for the ghosts whose kind `keep` accepts (the solid's sub-steps, between fluid steps,
 * change only the solids: refreshing the fluid's ghosts too costs most of a 3D FSI sub-step). */
PetscErrorCode HaloRefreshKinds(Halo h, Particles P, PetscBool (*keep)(PetscInt), PetscInt nf, const FieldId f[]);
/* Compact arrays that only some particles carry, slot[a] >= 0 (owned slots [0, nown), then the
 * ghosts'): the SF from the owners' slots to their ghosts' (built after each HaloBuild), and the
 * refresh of na such arrays of width[k] reals a slot over it. */
PetscErrorCode HaloSlotSF(Halo h, Particles P, const PetscInt *slot, PetscInt nown, PetscSF *sf);
PetscErrorCode HaloRefreshSlots(Halo h, PetscSF sf, PetscInt nown, PetscInt na, const PetscInt width[], PetscReal *const a[]);
