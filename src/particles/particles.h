/* Particles: structure-of-arrays storage with stable global ids and a kind.
 * Owned particles occupy [0, n); ghosts (copies of neighbours owned elsewhere or periodic images)
 * occupy [n, n + ng).  A field exists only when a module enabled it before ParticlesSetUp. */
#pragma once
#include "base/base.h"

typedef enum { KIND_FLUID = 0, KIND_WALL, KIND_DUMMY, KIND_SOLID, KIND_CLAMP, KIND_COUNT } ParticleKind;
extern const char *const ParticleKindNames[];

static inline PetscBool KindIsFluid(PetscInt k) { return (PetscBool)(k == KIND_FLUID); }
static inline PetscBool KindIsWall(PetscInt k) { return (PetscBool)(k == KIND_WALL || k == KIND_DUMMY); }
static inline PetscBool KindIsSolid(PetscInt k) { return (PetscBool)(k == KIND_SOLID || k == KIND_CLAMP); }

typedef enum {
  FIELD_X = 0, /* position (dim) */
  FIELD_V,     /* velocity (dim) */
  FIELD_RHO,   /* density */
  FIELD_P,     /* pressure */
  FIELD_M,     /* mass */
  FIELD_H,     /* smoothing length */
  FIELD_X0,    /* initial position (dim): displacement probes */
  FIELD_ACC,   /* acceleration (dim) */
  FIELD_DRHO,  /* density rate */
  FIELD_XSPH,  /* XSPH velocity correction (dim), Eq. 44 */
  FIELD_VWALL, /* wall velocity seen by the viscous term (dim) */
  FIELD_VSTAR, /* ISPH: intermediate velocity (dim) */
  FIELD_FS,    /* free-surface flag (0/1) */
  FIELD_S,     /* solid deviatoric stress (2D: xx, xy, yy; 3D: six components) */
  FIELD_NORMAL,  /* interface normal (dim) */
  FIELD_ROW,   /* ISPH: global row of the pressure equation (-1: none) */
  FIELD_KCORR, /* solid: kernel-gradient correction matrix (dim x dim, row-major) */
  FIELD_FVIEW, /* solid next to fluid: the fluid's view of it (3: pressure, density, mass; boundary.h) */
  FIELD_AMEAN, /* solid with ISPH: mean acceleration over the last fluid step (2; ppe.c) */
  FIELD_XREB,  /* scenes with solids: position at the last rebuild (dim); solids move after it, and a
                  restart rebuilds the neighbour lists there to continue exactly (checkpoint.h) */
  FIELD_XLIST,   /* WCSPH's Verlet skin with solids: position when the main list's pairs were last computed (a
                    refresh or a rebuild); the solids move after it, and a restart computes them there (checkpoint.h) */
  FIELD_COUNT
} FieldId;

typedef struct {
  const char *name;
  PetscInt    width;
  PetscBool   on;   /* allocated */
  PetscBool   halo; /* sent to ghosts when the halo is built */
  PetscReal  *a;
} Field;

typedef struct _p_Particles *Particles;
struct _p_Particles {
  MPI_Comm  comm;
  PetscInt  dim;        /* 2 or 3: the width of the vector fields (x, v, ...) and tensors */
  PetscInt  n, ng, cap; /* owned, ghosts, capacity of every array */
  PetscInt *id, *kind;
  Field     f[FIELD_COUNT];
  PetscBool setup;
};

PetscErrorCode ParticlesCreate(MPI_Comm comm, Particles *P);
PetscErrorCode ParticlesDestroy(Particles *P);
/* Before ParticlesSetUp: allocate this field; `halo` says whether ghosts need it. */
PetscErrorCode ParticlesEnableField(Particles P, FieldId f, PetscBool halo);
/* Before ParticlesSetUp: the dimension (2 by default), which sets the widths of the vector fields
 * (dim), the stress (dim (dim + 1) / 2) and the tensors (dim^2). */
PetscErrorCode ParticlesSetDimension(Particles P, PetscInt dim);
PetscErrorCode ParticlesSetUp(Particles P);
/* Make room for at least `cap` particles (owned + ghosts), keeping the contents. */
PetscErrorCode ParticlesReserve(Particles P, PetscInt cap);
/* Append an owned particle at x (dim coordinates; ghosts must be absent); other fields start at zero. */
PetscErrorCode ParticlesAdd(Particles P, PetscInt id, ParticleKind kind, const PetscReal x[], PetscReal m, PetscReal h, PetscReal rho);
/* Remove the owned particles with drop[i] set, keeping the order of the rest; drops ghosts. */
PetscErrorCode ParticlesRemove(Particles P, const PetscBool *drop);
/* Reorder owned particles: new[i] = old[perm[i]]; drops ghosts. */
PetscErrorCode ParticlesPermute(Particles P, const PetscInt *perm);
/* Bytes per particle of all allocated fields (id and kind included). */
PetscInt ParticlesBytesPerParticle(Particles P);
PetscErrorCode ParticlesGlobalCount(Particles P, PetscInt *N);
PetscErrorCode ParticlesView(Particles P, PetscViewer v);

static inline PetscReal *PField(Particles P, FieldId f) { return P->f[f].a; }
