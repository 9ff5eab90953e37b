/* Forces on named bodies: the force of the fluid on the walls and solids whose field "body" is k,
 * integrated as the fluid's momentum equation exchanges it (each pair's force the fluid gets from a
 * body particle, reversed: boundary_load.h), so that what the fluid loses the body gets.  For the
 * probes of a scene (drag and lift on a cylinder, loads on a structure): computed when asked. */
#pragma once
#include "physics/physics.h"

/* The force (N, or N/m in 2D) of the fluid on body k > 0 at the current state: collective. */
PetscErrorCode FluidBodyForce(Physics *ph, PetscInt k, PetscReal force[3]);
