/* Incompressible SPH (section 2.8): projection with a predictor (Eqs. 45-47), density by summation
 * (Eq. 17), free-surface detection (section 2.5), the pressure Poisson equation (Eqs. 22, 48;
 * ppe.h) and a corrector (Eqs. 49-51, gradient Eq. 14). */
#pragma once
#include "physics/physics.h"
#include "fluid/ppe.h"

typedef enum { ISPH_FS_DENSITY = 0, ISPH_FS_DIVR } ISPHFreeSurface;
typedef enum { ISPH_SOURCE_DIVERGENCE = 0, ISPH_SOURCE_DENSITY, ISPH_SOURCE_BLEND } ISPHSource;
typedef enum { ISPH_GRAD_EQ14 = 0, ISPH_GRAD_CORRECTED, ISPH_GRAD_HYBRID } ISPHGradient;
extern const char *const ISPHFreeSurfaces[];
extern const char *const ISPHGradients[];
extern const char *const ISPHSources[];

struct _p_ISPH {
  ISPHFreeSurface fs;
  ISPHSource      source;
  ISPHGradient    gradient;
  PetscReal       beta;     /* free surface where rho* < beta rho0 */
  PetscReal       divr_min; /* free surface where div r < divr_min (2 inside, in 2D) */
  PetscReal       blend;    /* weight of the density-invariant source in the blend */
  PetscReal       alpha;    /* artificial viscosity in the predictor */
  PetscReal       shift;    /* Fickian shifting coefficient A (Skillen et al. 2013); 0 = off */
  PetscBool       solid_eq14;   /* Eq. 14 for fluid next to a solid, whatever the gradient (isph.c) */
  PetscReal       grad_cond;    /* -isph_gradient_cond: the corrected gradient where its matrix's eigenvalue ratio exceeds this */
  PetscBool       wall_contact; /* free-surface particles stopped kinematically at walls (isph.c, WallContact) */
  PetscReal       lat_w, lat_divr; /* sum of m W and div r of a full square lattice: normalisation */
  PetscReal      *src;
  PetscInt        cap_src, nfree; /* free-surface particles of the last step */
  PPE             ppe;
};

/* Creates ph->isph and reads its options, under the prefix -isph_, after
 * FluidMaterialSetFromOptions; then the set-up (the pressure equation, fields), before
 * ParticlesSetUp. */
PetscErrorCode ISPHSetFromOptions(Physics *ph);
PetscErrorCode ISPHSetUp(Physics *ph);
/* State of walls after the first rebuild. */
PetscErrorCode ISPHInitialize(Physics *ph);
PetscErrorCode ISPHDestroy(ISPH *isph);
/* Step from CFL on the flow speed (not a sound speed), force and viscous limits. */
PetscErrorCode ISPHTimeStep(Physics *ph, PetscReal *dt);
/* At the current positions (r*): rho*, free surface, PPE matrix and right-hand side (needs ph->dt
 * and the predicted velocity): the source of ISPHPredict, then ISPHAssemble. */
PetscErrorCode ISPHPressureEquation(Physics *ph);
/* One predictor-projection-corrector step of length ph->dt is these four in turn (the driver's
 * Step, which logs each in its stage):
 *   ISPHPredict   the predictor (v*, r*), the neighbours at r*, rho*, free surface and source;
 *   ISPHAssemble  the PPE's rows and matrix;
 *   ISPHSolve     the pressure;
 *   ISPHCorrect   the corrector, the drift, the move to the end of the step and its neighbours. */
PetscErrorCode ISPHPredict(Physics *ph);
PetscErrorCode ISPHAssemble(Physics *ph);
PetscErrorCode ISPHSolve(Physics *ph);
PetscErrorCode ISPHCorrect(Physics *ph);
PetscErrorCode ISPHView(Physics *ph, PetscViewer v);
