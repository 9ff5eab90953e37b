/* A scene's particles: their kinds, adding them, and reading or writing their fields by name
 * through Get/Restore (as DMSwarm does).  Owned particles are [0, n) of every field; a field of
 * width w holds w reals a particle (x: SimDim(sim) coordinates, x fastest). */
#ifndef SPHFSI_PARTICLES_H
#define SPHFSI_PARTICLES_H
#include <sphfsi/base.h>

SPHFSI_EXTERN_C_BEGIN

/* Fluid; wall (the row next to the fluid) and dummy (the rows behind it); an elastic solid and its
 * clamp (solid particles held in place). */
typedef enum { KIND_FLUID = 0, KIND_WALL, KIND_DUMMY, KIND_SOLID, KIND_CLAMP, KIND_COUNT } ParticleKind;

static inline PetscBool KindIsFluid(PetscInt k) { return (PetscBool)(k == KIND_FLUID); }
static inline PetscBool KindIsWall(PetscInt k) { return (PetscBool)(k == KIND_WALL || k == KIND_DUMMY); }
static inline PetscBool KindIsSolid(PetscInt k) { return (PetscBool)(k == KIND_SOLID || k == KIND_CLAMP); }

/* The number of particles this rank owns. */
PetscErrorCode SimGetLocalSize(Sim sim, PetscInt *n);
/* The array of a field of this rank's particles, by its name in the snapshots ("x", "v", "p", "rho",
 * "m", "h", "x0", "stress", ... docs/output.md): *array (pass the address of a PetscReal pointer)
 * points at its first particle's values, *width (NULL: not wanted) is the reals a particle; "id" and
 * "kind" give PetscInt arrays (width 1).  Restore it when done.  An unknown name or a field this run
 * does not allocate is an error. */
PetscErrorCode SimGetField(Sim sim, const char name[], PetscInt *width, void *array);
PetscErrorCode SimRestoreField(Sim sim, const char name[], PetscInt *width, void *array);
/* In the scene's create: allocate a field the run would not (e.g. "x0", for displacement probes). */
PetscErrorCode SimEnableField(Sim sim, const char name[]);
/* Whether the run allocates the field. */
PetscErrorCode SimHasField(Sim sim, const char name[], PetscBool *has);
/* In the scene's populate: append one owned particle of global id `id` at x (SimDim(sim)
 * coordinates), mass m, smoothing length h, density rho; its other fields start at zero.  Ids must
 * be unique across ranks (the builders of <sphfsi/scene.h> number theirs from SimNextId). */
PetscErrorCode SimAddParticle(Sim sim, PetscInt id, ParticleKind kind, const PetscReal x[], PetscReal m, PetscReal h, PetscReal rho);
/* The next global id the builders hand out, and setting it (after adding ids of one's own). */
PetscInt       SimNextId(Sim sim);
PetscErrorCode SimSetNextId(Sim sim, PetscInt id);
/* Call pair(ctx, a, b) for each neighbour b of owned particle a within the kernel's reach (b may be a
 * ghost: index >= the local size), in the neighbour list's order (collective only in the sense that
 * the list is the run's; for probes). */
PetscErrorCode SimForEachNeighbour(Sim sim, PetscInt a, void (*pair)(void *ctx, PetscInt a, PetscInt b), void *ctx);

SPHFSI_EXTERN_C_END
#endif
