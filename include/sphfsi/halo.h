/* Ghost particles: copies of particles owned by other ranks (or periodic images) that lie in cells
 * adjacent to this rank's cells.  Built after migration; individual fields refreshed by PetscSF. */
#pragma once
#include <sphfsi/decomp.h>
#include <petscsf.h>

typedef struct _p_Halo *Halo;
struct _p_Halo {
  MPI_Comm    comm;
  PetscSF     sf;       /* roots: owned particles; leaves: ghost slots n .. n+ng */
  PetscInt   *shift;    /* per ghost: periodic image code 9 (sz+1) + 3 (sy+1) + (sx+1); 13 = none */
  PetscInt    cap_shift;
  MPI_Datatype unit[26]; /* contiguous blocks of 1..25 reals (the widest field, FIELD_GRAD0) */
  PetscInt    nghost_sent;
  PetscReal   period[3]; /* domain lengths, for periodic shifts */
};

PetscErrorCode HaloCreate(MPI_Comm comm, Halo *h);
PetscErrorCode HaloDestroy(Halo *h);
/* Create ghosts of all fields marked `halo` (plus id, kind) and the SF for later refreshes. */
PetscErrorCode HaloBuild(Halo h, Decomp d, Particles P);
/* Copy the owners' current values of these fields into the ghosts. */
PetscErrorCode HaloRefresh(Halo h, Particles P, PetscInt nf, const FieldId f[]);
