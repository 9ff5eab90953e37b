/* Hypo-elastic solids by WCSPH (sections 2.2 and 2.4): pressure from the equation of state Eq. 20
 * with c0^2 = K / rho0, deviatoric stress from the Jaumann rate (Eqs. 7-8, 35-40), momentum Eq. 23
 * with artificial viscosity (Eq. 24) and artificial stress (Eqs. 25-34).  Explicit and per rank.
 * Particles of kind `clamp` are the part of a body held fixed: their density and stress evolve
 * like the solid's, so the stress field runs on into the clamp, but they never move. */
#pragma once
#include <sphfsi/sim.h>

typedef enum { SOLID_GRAD_STANDARD = 0, SOLID_GRAD_CORRECTED } SolidGradient;
extern const char *const SolidGradients[];

struct _p_Solid {
  SolidGradient gradient;
  PetscReal    *R;     /* artificial stress (xx, xy, yy) of owned + ghost particles, Eqs. 32-34 */
  PetscInt      cap_R;
  PetscInt      nsub_last, nsub_max; /* solid sub-steps in the last / any fluid step (progress line, summary) */
};

/* Options (-solid_*; the scene's material defaults are in sim->sl) and fields (before
 * ParticlesSetUp). */
PetscErrorCode SolidSetUp(Sim sim);
PetscErrorCode SolidDestroy(Solid *s);
/* Pressure, artificial stress and accelerations of solids at the current state (after a rebuild). */
PetscErrorCode SolidRates(Sim sim);
/* Step limit from the solid sound speed: cfl h / (c0 + |v|), and the force limit. */
PetscErrorCode SolidTimeStep(Sim sim, PetscReal *dt);
/* One kick-drift-kick step of length dt of the solids (fluids held still). */
PetscErrorCode SolidStep(Sim sim, PetscReal dt);
/* Kinetic and strain energy of owned solids at the state of the last SolidRates (collective):
 * strain energy density
 * S:S / (4 G) + P^2 / (2 K), S_zz = -(S_xx + S_yy) in plane strain. */
PetscErrorCode SolidEnergy(Sim sim, PetscReal *ekin, PetscReal *estrain);
PetscErrorCode SolidView(Sim sim, PetscViewer v);
