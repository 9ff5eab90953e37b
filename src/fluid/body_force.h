/* Forces on named bodies: the force of the fluid on the walls and solids whose field "body" is k,
 * integrated as the fluid's momentum equation exchanges it (each pair's force the fluid gets from a
 * body particle, reversed: boundary_load.h), so that what the fluid loses the body gets.  For the
 * probes of a scene (drag and lift on a cylinder, loads on a structure): computed when asked. */
#pragma once
#include "physics/physics.h"

#define FLUID_MAX_BODIES 8 /* bodies one pass measures */

/* The forces (N, or N/m in 2D) of the fluid on bodies k, k + 1, ..., k + n - 1 (k > 0, n <= FLUID_MAX_BODIES)
 * at the current state, in one pass over the pairs: collective. */
PetscErrorCode FluidBodyForces(Physics *ph, PetscInt k, PetscInt n, PetscReal force[][3]);
