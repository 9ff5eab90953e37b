/* Particles: structure-of-arrays storage with stable global ids and a kind.
 * Owned particles occupy [0, n); ghosts (copies of neighbours owned elsewhere or periodic images)
 * occupy [n, n + ng).  A field exists only when a module enabled it before ParticlesSetUp. */
#pragma once
#include "base/base.h"

#include <sphfsi/particles.h> /* ParticleKind, KindIsFluid/Wall/Solid; a scene's view of the fields */
extern const char *const ParticleKindNames[];

/* A field's width: a fixed number of reals (1: a scalar), or one that follows the dimension d. */
enum { WIDTH_VECTOR = -1 /* d */, WIDTH_SYM = -2 /* d (d + 1) / 2: a symmetric tensor's xx, xy, yy (3D: six) */, WIDTH_TENSOR = -3 /* d x d, row-major */ };
/* How particles.xmf describes a snapshot field (io.c): an attribute of type Scalar, Vector, or Tensor6
 * (3D; in 2D the three components as a Vector); XDMF_NONE: not an attribute (x is the geometry). */
typedef enum { XDMF_NONE = 0, XDMF_SCALAR, XDMF_VECTOR, XDMF_SYM } FieldXdmf;

/* The field table: one entry F(id, name, width, snapshot, checkpoint, xdmf) a field.
 *   id          its FieldId (PField(P, id)); the entries' order is that of memory, checkpoints and
 *               summary.json
 *   name        its dataset in snapshots and checkpoints, its name in summary.json and messages
 *   width       reals per particle: a number, or WIDTH_VECTOR, WIDTH_SYM, WIDTH_TENSOR (above)
 *   snapshot    0: not in snapshots; k = 1, 2, ... (each k once): in every snapshot
 *               (particles_NNNNN.h5), k-th in particles.xmf (and io_space.c counts its bytes)
 *   checkpoint  PETSC_TRUE: checkpoints carry it and a restart reads it back (its allocation is then
 *               part of what a restart must match); PETSC_FALSE only for a field that every step
 *               computes before reading it (a restart zeroes it).  A snapshot field is carried:
 *               last_good.xmf shows a checkpoint as a snapshot.
 *   xdmf        its type in particles.xmf (FieldXdmf; XDMF_NONE for a field not in snapshots)
 * A field exists in a run only when a module enables it (ParticlesEnableField); migration, the halo,
 * snapshots, particles.xmf, checkpoints, restarts and summary.json take it from here.  Adding a field
 * is one entry, e.g. a vorticity in snapshots and checkpoints, shown as a scalar:
 *   F(FIELD_VORT, "vorticity", 1, 9, PETSC_TRUE, XDMF_SCALAR)
 * and enabling it where a module computes it.  Output that is not a field as it is stored (id, kind,
 * the XDMF's geometry and topology, WCSPH's pressure from the equation of state) is written
 * explicitly in io.c. */
#define PARTICLE_FIELDS(F) \
  /*id             name                  width       snap   ckpt         xdmf */ \
  F(FIELD_X,       "x",                  WIDTH_VECTOR,  1,  PETSC_TRUE,  XDMF_NONE)   /* position; the XDMF's geometry */ \
  F(FIELD_V,       "v",                  WIDTH_VECTOR,  2,  PETSC_TRUE,  XDMF_VECTOR) /* velocity */ \
  F(FIELD_RHO,     "rho",                1,             4,  PETSC_TRUE,  XDMF_SCALAR) /* density */ \
  F(FIELD_P,       "p",                  1,             3,  PETSC_TRUE,  XDMF_SCALAR) /* pressure */ \
  F(FIELD_M,       "m",                  1,             5,  PETSC_TRUE,  XDMF_SCALAR) /* mass */ \
  F(FIELD_H,       "h",                  1,             6,  PETSC_TRUE,  XDMF_SCALAR) /* smoothing length */ \
  F(FIELD_X0,      "x0",                 WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* initial position: displacement probes */ \
  F(FIELD_ACC,     "acc",                WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* acceleration */ \
  F(FIELD_DRHO,    "drho",               1,             0,  PETSC_TRUE,  XDMF_NONE)   /* density rate */ \
  F(FIELD_XSPH,    "xsph",               WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* XSPH velocity correction, Eq. 44 */ \
  F(FIELD_VWALL,   "vwall",              WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* wall velocity seen by the viscous term */ \
  F(FIELD_VSTAR,   "vstar",              WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* ISPH: intermediate velocity */ \
  F(FIELD_FS,      "free_surface",       1,             7,  PETSC_TRUE,  XDMF_SCALAR) /* free-surface flag (0/1) */ \
  F(FIELD_S,       "stress",             WIDTH_SYM,     8,  PETSC_TRUE,  XDMF_SYM)    /* solid deviatoric stress */ \
  F(FIELD_NORMAL,  "normal",             WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* interface normal */ \
  F(FIELD_ROW,     "row",                1,             0,  PETSC_TRUE,  XDMF_NONE)   /* ISPH: global row of the pressure equation (-1: none) */ \
  F(FIELD_KCORR,   "kernel_correction",  WIDTH_TENSOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* solid: kernel-gradient correction matrix */ \
  F(FIELD_FVIEW,   "fluid_view",         3,             0,  PETSC_TRUE,  XDMF_NONE)   /* solid next to fluid: the fluid's view of it (pressure, density, mass; boundary.h) */ \
  F(FIELD_AMEAN,   "mean_acc",           WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* solid with ISPH: mean acceleration over the last fluid step (ppe.c) */ \
  F(FIELD_XREB,    "x_rebuild",          WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* scenes with solids: position at the last rebuild; solids move after it, \
                                                                                      and a restart rebuilds the neighbour lists there to continue exactly (checkpoint.h) */ \
  F(FIELD_XLIST,   "x_list",             WIDTH_VECTOR,  0,  PETSC_TRUE,  XDMF_NONE)   /* WCSPH's Verlet skin with solids: position when the main list's pairs were last \
                                                                                      computed (a refresh or a rebuild); the solids move after it, and a restart computes them there (checkpoint.h) */ \
  F(FIELD_OPEN,    "open_zone",          1,             9,  PETSC_TRUE,  XDMF_SCALAR) /* open boundaries: 0 the fluid, k > 0 the buffer of open boundary k (open_boundary.h) */ \
  F(FIELD_BODY,    "body",               1,            10,  PETSC_TRUE,  XDMF_SCALAR) /* walls and solids: the body k > 0 whose force a scene measures (body_force.h; 0 none) */ \
  F(FIELD_QWALL,   "wall_riemann",       1,             0,  PETSC_TRUE,  XDMF_NONE)   /* WCSPH fluid: the Riemann dissipation against the walls, per unit density (wcsph.c) */ \
  F(FIELD_WNORMAL, "wall_normal",        WIDTH_VECTOR,  0,  PETSC_FALSE, XDMF_NONE)   /* ISPH: a fixed wall particle's unit normal into the fluid, from the walls' geometry (ppe.c) */

typedef enum {
#define PARTICLE_FIELD_ID(id, ...) id,
  PARTICLE_FIELDS(PARTICLE_FIELD_ID)
#undef PARTICLE_FIELD_ID
  FIELD_COUNT
} FieldId;

typedef struct {
  const char *name;
  PetscInt    width; /* as in the table: a number or WIDTH_* */
  PetscInt    snapshot;
  PetscBool   checkpoint;
  FieldXdmf   xdmf;
} FieldDesc;
extern const FieldDesc FieldTable[FIELD_COUNT];

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
/* The allocated fields a snapshot holds, in their order (the table's `snapshot`); returns how many. */
PetscInt ParticlesSnapshotFields(Particles P, FieldId out[FIELD_COUNT]);

static inline PetscReal *PField(Particles P, FieldId f) { return P->f[f].a; }
/* Whether checkpoints carry field f of this run (allocated, and so in the table). */
static inline PetscBool ParticlesCheckpointField(Particles P, FieldId f) { return (PetscBool)(P->f[f].on && FieldTable[f].checkpoint); }

