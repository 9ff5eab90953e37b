/* Material constants of each medium. */
#pragma once
#include "base/base.h"
#include "base/dim.h"
#include "base/kernel.h"

typedef struct {
  PetscReal rho0;     /* reference density */
  PetscReal c0;       /* artificial sound speed, Eq. 20 (WCSPH) */
  PetscReal mu;       /* dynamic viscosity, Eq. 16 */
  PetscReal eta;      /* regularisation of Eqs. 16 and 22 over h (-fluid_eta) */
  PetscReal lap_kappa; /* normalisation of Eqs. 16 and 22: exact on the lattice (-fluid_lap_normalise) */
  PetscReal alpha;    /* artificial viscosity, Eq. 24 (WCSPH) */
  PetscReal delta;    /* density diffusion (delta-SPH), 0 = off */
  PetscReal xsph;     /* XSPH epsilon, Eq. 44, 0 = off */
  PetscReal shift;    /* WCSPH Fickian shifting coefficient A (shifting.h), 0 = off */
  PetscBool shift_correct; /* both schemes: a shifted particle's velocity corrected to its new place (shifting.h) */
  PetscReal lat_divr; /* WCSPH with shifting: bulk value of -sum V F r^2, normalises div r */
  PetscBool wall_clip; /* WCSPH: the Adami wall pressure clipped at 0, so that a wall never pulls fluid */
} FluidMaterial;

typedef struct {
  PetscReal rho0;  /* reference density */
  PetscReal K, G;  /* bulk and shear modulus */
  PetscReal c0;    /* sqrt(K / rho0), Eq. 20 */
  PetscReal alpha; /* artificial viscosity, Eq. 24 */
  PetscReal eps;   /* artificial stress e, Eqs. 25-31 (0 = off) */
  PetscReal n;     /* exponent of f = W_ab / W(dx, h) in Eq. 23 */
} SolidMaterial;

/* The fluid material's options, both schemes', under the prefix -fluid_ (one PetscOptionsBegin block):
 * -fluid_rho0, -fluid_mu, -fluid_eta, -fluid_lap_normalise (sets lap_kappa for `kernel` in `dim`
 * dimensions), -fluid_c0 (default 10 v_ref), -fluid_xsph, -fluid_shift_correct into *fl, and
 * -fluid_start_jitter into *start_jitter; called after the scene has set its defaults.  The names
 * without the prefix work on for this version with a deprecation note. */
PetscErrorCode FluidMaterialSetFromOptions(MPI_Comm comm, const SPHKernel *kernel, PetscInt dim, PetscReal v_ref, FluidMaterial *fl, PetscReal *start_jitter);

/* EOS, Eq. 20 */
static inline PetscReal EOSPressure(const FluidMaterial *m, PetscReal rho) { return m->c0 * m->c0 * (rho - m->rho0); }
static inline PetscReal EOSDensity(const FluidMaterial *m, PetscReal p) { return m->rho0 + p / (m->c0 * m->c0); }
static inline PetscReal SolidEOSPressure(const SolidMaterial *m, PetscReal rho) { return m->c0 * m->c0 * (rho - m->rho0); }

/* Step limit of one particle of an explicit (weakly compressible) medium of sound speed c:
 * CFL  cfl h / (c + |v|)  and the force limit  0.25 sqrt(h / |a|). */
static inline PetscReal AcousticStepLimit(PetscReal cfl, PetscReal h, PetscReal c, const PetscReal v[], const PetscReal acc[], PetscInt dim)
{
  PetscReal vn = PetscSqrtReal(VDot(v, v, dim)), an = PetscSqrtReal(VDot(acc, acc, dim));
  PetscReal lim = cfl * h / (c + vn);
  return an > 0 ? PetscMin(lim, 0.25 * PetscSqrtReal(h / an)) : lim;
}
