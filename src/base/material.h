/* Material constants of each medium. */
#pragma once
#include "base/base.h"
#include "base/dim.h"
#include "base/kernel.h"

#include <sphfsi/material.h> /* FluidMaterial, SolidMaterial, the equation of state (Eq. 20) */

/* The fluid material's options, both schemes', under the prefix -fluid_ (one PetscOptionsBegin block):
 * -fluid_rho0, -fluid_mu, -fluid_eta, -fluid_lap_normalise (sets lap_kappa for `kernel` in `dim`
 * dimensions), -fluid_c0 (default 10 v_ref), -fluid_xsph, -fluid_shift_correct into *fl, and
 * -fluid_start_jitter into *start_jitter; called after the scene has set its defaults.  The names
 * without the prefix work on for this version with a deprecation note. */
PetscErrorCode FluidMaterialSetFromOptions(MPI_Comm comm, const SPHKernel *kernel, PetscInt dim, PetscReal v_ref, FluidMaterial *fl, PetscReal *start_jitter);

/* Step limit of one particle of an explicit (weakly compressible) medium of sound speed c:
 * CFL  cfl h / (c + |v|)  and the force limit  0.25 sqrt(h / |a|). */
static inline PetscReal AcousticStepLimit(PetscReal cfl, PetscReal h, PetscReal c, const PetscReal v[], const PetscReal acc[], PetscInt dim)
{
  PetscReal vn = PetscSqrtReal(VDot(v, v, dim)), an = PetscSqrtReal(VDot(acc, acc, dim));
  PetscReal lim = cfl * h / (c + vn);
  return an > 0 ? PetscMin(lim, 0.25 * PetscSqrtReal(h / an)) : lim;
}
