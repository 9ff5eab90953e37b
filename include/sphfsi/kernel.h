/* Cubic spline kernel, Eq. 12 (2D): support radius 2h; for particles of different sizes the
 * pair uses h_ab = sqrt(h_a h_b) (section 3.3). */
#pragma once
#include <sphfsi/base.h>

#define SPH_H_FACTOR 1.3 /* h = 1.3 dx */

static inline PetscReal KernelSigma(PetscReal h) { return 10.0 / (7.0 * PETSC_PI * h * h); }

/* W(r, h) */
static inline PetscReal KernelW(PetscReal r, PetscReal h)
{
  PetscReal R = r / h, s = KernelSigma(h);
  if (R < 1.0) return s * (1.0 - 1.5 * R * R + 0.75 * R * R * R);
  if (R < 2.0) { PetscReal t = 2.0 - R; return s * 0.25 * t * t * t; }
  return 0.0;
}

/* dW/dr(r, h); the gradient is grad_a W_ab = dW/dr * (x_a - x_b) / r, Eq. 15 */
static inline PetscReal KernelDW(PetscReal r, PetscReal h)
{
  PetscReal R = r / h, s = KernelSigma(h) / h;
  if (R < 1.0) return s * (-3.0 * R + 2.25 * R * R);
  if (R < 2.0) { PetscReal t = 2.0 - R; return -0.75 * s * t * t; }
  return 0.0;
}

/* F_ab = (dW/dr) / r, so that grad_a W_ab = F_ab (x_a - x_b); finite at r -> 0. */
static inline PetscReal KernelF(PetscReal r, PetscReal h)
{
  PetscReal R = r / h, s = KernelSigma(h) / (h * h);
  if (R < 1.0) return s * (-3.0 + 2.25 * R);
  if (R < 2.0) { PetscReal t = 2.0 - R; return -0.75 * s * t * t / R; }
  return 0.0;
}

static inline PetscReal PairH(PetscReal ha, PetscReal hb) { return ha == hb ? ha : PetscSqrtReal(ha * hb); }

/* Sums over a full square lattice of spacing 1 (h = SPH_H_FACTOR): sum W (divr false) or -sum F r^2
 * (divr true), the interior values of the summation density (Eq. 17, per rho0) and of div r
 * (2 in the continuum), used to normalise both. */
static inline PetscReal KernelLatticeSum(PetscBool divr)
{
  PetscReal s = 0;
  for (PetscInt j = -3; j <= 3; j++)
    for (PetscInt i = -3; i <= 3; i++) {
      PetscReal r = PetscSqrtReal((PetscReal)(i * i + j * j));
      s += divr ? -KernelF(r, SPH_H_FACTOR) * r * r : KernelW(r, SPH_H_FACTOR);
    }
  return s;
}
