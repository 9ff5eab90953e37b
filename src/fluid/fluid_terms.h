/* Pair terms of the fluid equations shared by the WCSPH and ISPH schemes: each is a function of
 * one pair (a, b); the loop drivers in wcsph.c and isph*.c call the terms a step needs. */
#pragma once
#include "base/base.h"

/* Eq. 24: Monaghan artificial viscosity, added to the pressure term; vr = v_ab . r_ab */
static inline PetscReal ArtificialViscosity(PetscReal alpha, PetscReal c, PetscReal h, PetscReal rho_bar, PetscReal vr, PetscReal r2)
{
  if (vr >= 0) return 0.0;
  return -alpha * c * (h * vr / (r2 + 0.01 * h * h)) / rho_bar;
}

/* Zhang, Hu & Adams 2017: the dissipative part of the linearised (acoustic) Riemann solver's
 * interface pressure between a and b, P* = (p_a + p_b) / 2 + this, with their low-dissipation
 * limiter: rho c beta du / 2, beta = min(eta du / c, 1), where du = U_L - U_R > 0 is the speed at
 * which a and b approach along their line (-v_ab . r_ab / r).  Zero when they recede; quadratic in
 * du for small jumps (so it leaves shear and weak waves alone), the full acoustic impedance
 * rho c du / 2 for du >= c / eta.  It enters the momentum equation as 2 P* / (rho_a rho_b). */
static inline PetscReal RiemannDissipation(PetscReal eta, PetscReal c, PetscReal rho_bar, PetscReal du)
{
  if (du <= 0 || eta <= 0) return 0.0;
  return 0.5 * rho_bar * c * PetscMin(eta * du / c, 1.0) * du;
}

/* Eq. 16: laminar viscosity, the coefficient of (v_a - v_b); rgw = r_ab . grad_a W_ab; the
 * regularisation eta h (-fluid_eta; the paper 0.1) keeps r -> 0 finite; kappa normalises the operator to
 * be exact on the lattice (kernel.h, KernelLatticeSum, LATTICE_LAPLACIAN) */
static inline PetscReal LaminarViscosity(PetscReal mb, PetscReal mu, PetscReal rhoa, PetscReal rhob, PetscReal rgw, PetscReal r2, PetscReal h, PetscReal eta, PetscReal kappa)
{
  PetscReal rs = rhoa + rhob;
  return kappa * 4.0 * mb * (2.0 * mu) * rgw / (rs * rs * (r2 + eta * eta * h * h));
}

/* Eq. 22: coefficient c_ab of the Laplacian  div(grad P / rho)_a = sum_b c_ab (P_a - P_b);
 * F = (dW/dr)/r so r_ab . grad_a W_ab = F r2; eta and kappa as in Eq. 16.  c_ab <= 0 and
 * m_a c_ab is symmetric. */
static inline PetscReal PPECoefficient(PetscReal mb, PetscReal rhoa, PetscReal rhob, PetscReal F, PetscReal r2, PetscReal h, PetscReal eta, PetscReal kappa)
{
  PetscReal rs = rhoa + rhob;
  return kappa * 8.0 * mb * F * r2 / (rs * rs * (r2 + eta * eta * h * h));
}

/* Eq. 44: XSPH weight of neighbour b, m_b W_ab / rho_ab with rho_ab the mean density */
static inline PetscReal XSPHWeight(PetscReal W, PetscReal mb, PetscReal rhoa, PetscReal rhob) { return W * mb / (0.5 * (rhoa + rhob)); }

/* Eq. 41: repulsive acceleration of a fluid particle along the outward normal n of a solid
 * neighbour it approaches (u_n = (v_f - v_s) . n < 0), q = r / (2 h); the solid gets the
 * reaction.  Zero when receding, and at q = 1. */
static inline PetscReal FSIRepulsion(PetscReal un, PetscReal q, PetscReal dt)
{
  if (un >= 0 || q <= 0 || q >= 1 || dt <= 0) return 0.0;
  return (1.0 / 3.0) * (-un / dt) * (1.0 - 0.5 * q) / (0.5 * q);
}
