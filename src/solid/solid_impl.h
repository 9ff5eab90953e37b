/* What the solid formulations (solid_total.c, solid_updated.c) and the solid's driver (solid.c)
 * share, below all three: the last step of a solid particle's acceleration, the kinds of a body
 * (the fluid's load on it is fluid/boundary_load.h's).  Private to the solid module. */
#pragma once
#include "solid/solid.h"
#include "fluid/boundary_load.h"
#include "base/dim.h"

/* Owned solid a: internal acceleration ai, the fluid's load fl, gravity and, with
 * -solid_damping, a drag -zeta v.  A clamp is
 * held: the support takes what would accelerate it; the sums feed the probes. */
SPH_INLINE void SolidAccelerate(Physics *ph, PetscInt a, const PetscReal *ai, const PetscReal *fl, PetscReal *acc, PetscReal *support, PetscReal *load, const PetscInt D)
{
  Particles        P    = ph->P;
  const PetscReal *mass = PField(P, FIELD_M);
  if (P->kind[a] == KIND_SOLID)
    for (PetscInt i = 0; i < D; i++) load[i] += mass[a] * fl[i];
  if (P->kind[a] == KIND_CLAMP) {
    for (PetscInt i = 0; i < D; i++) support[i] -= mass[a] * (ai[i] + fl[i] + ph->g[i]);
    for (PetscInt i = 0; i < D; i++) acc[D * a + i] = 0;
    return;
  }
  for (PetscInt i = 0; i < D; i++) acc[D * a + i] = ai[i] + fl[i] + ph->g[i];
  if (ph->solid->damping > 0) { /* dynamic relaxation */
    const PetscReal *v = PField(P, FIELD_V);
    for (PetscInt i = 0; i < D; i++) acc[D * a + i] -= ph->solid->damping * v[D * a + i];
  }
}

/* The kinds of a body (solid and clamp): the solid's neighbour list and its ghost refreshes. */
static inline PetscBool SolidKeep(PetscInt kind) { return KindIsSolid(kind); }
