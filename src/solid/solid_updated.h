/* The paper's hypo-elastic solid (solid_updated.c), as the solid's driver (solid.c) calls it. */
#pragma once
#include "solid/solid.h"

/* The seed's hypo-elastic formulation (solid_updated.c).  Rates: pressure, artificial stress and
 * accelerations at the current state; Deform: density and deviatoric stress over dt. */
PetscErrorCode SolidUpdatedRates(Physics *ph);
PetscErrorCode SolidUpdatedDeform(Physics *ph, PetscReal dt);
