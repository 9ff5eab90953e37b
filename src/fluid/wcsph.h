/* Weakly compressible fluid: EOS Eq. 20, continuity Eq. 18, momentum Eq. 19 with the viscous
 * term Eq. 16 and artificial viscosity Eq. 24, XSPH Eq. 44, optional delta-SPH density diffusion. */
#pragma once
#include "physics/physics.h"

/* -wcsph_skin default (particle spacings): the measured choice, docs/performance.md */
#define WCSPH_SKIN_DEFAULT 0.3
/* Its options, under the prefix -wcsph_ (-wcsph_alpha, -wcsph_delta, -wcsph_shift, -wcsph_wall_clip,
 * -wcsph_skin; -alpha and -delta work on for this version with a deprecation note), after
 * FluidMaterialSetFromOptions; then the set-up (fields), before ParticlesSetUp. */
PetscErrorCode WCSPHSetFromOptions(Physics *ph);
PetscErrorCode WCSPHSetUp(Physics *ph);
/* One line of the run's header: the WCSPH fluid's settings. */
PetscErrorCode WCSPHView(Physics *ph, PetscViewer v);
/* Pressure from density for owned and ghost fluid particles (Eq. 20). */
PetscErrorCode WCSPHPressure(Physics *ph);
/* acc, drho, xsph of owned fluid particles at the current state. */
PetscErrorCode WCSPHRates(Physics *ph);
/* Largest stable step: CFL on c0 + |v|, viscous and force limits. */
PetscErrorCode WCSPHTimeStep(Physics *ph, PetscReal *dt);
/* One kick-drift-kick step of length ph->dt (rebuilds neighbours). */
PetscErrorCode WCSPHStep(Physics *ph);
