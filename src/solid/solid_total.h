/* The total-Lagrangian solid (solid_total.c), as the solid's driver (solid.c) calls it. */
#pragma once
#include "solid/solid.h"

/* Prepare: after each rebuild of the solid's list,
 * the pairs' reference kernel values and each owned particle's correction; Rates: deformation
 * gradient, stress and accelerations at the current positions; StrainEnergy: owned, not reduced. */
PetscErrorCode SolidTotalPrepare(Physics *ph);
PetscErrorCode SolidTotalRates(Physics *ph);
PetscReal      SolidTotalStrainEnergy(Physics *ph);

