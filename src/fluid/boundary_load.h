/* The fluid's pair force on a particle that bounds it (a wall, a dummy or a solid): what the fluid
 * gets from it, reversed (Newton's third law).  The solid's load (solid_impl.h) and the forces on
 * named bodies (body_force.h) are both this sum. */
#pragma once
#include "fluid/boundary.h"
#include "fluid/fluid_terms.h"
#include "fluid/isph.h"
#include "solid/solid.h"
#include "base/dim.h"

/* Acceleration of boundary particle a from fluid neighbour b (F = F_ab of the pair): the reverse of
 * what the fluid gets from a (wcsph.c, isph.c), with a as the fluid sees it (FluidView): pressure
 * (Eq. 19, Eq. 14's symmetric form with ISPH), artificial viscosity and WCSPH's Riemann dissipation, laminar viscosity against
 * a's no-slip velocity and, on a solid with the repulsive force on, Eq. 41. */
SPH_INLINE void FluidPairLoad(Physics *ph, PetscInt a, PetscInt b, PetscReal F, PetscReal *acc, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H);
  const PetscReal *fv = PField(P, FIELD_FVIEW), *vw = PField(P, FIELD_VWALL), *nrm = PField(P, FIELD_NORMAL);
  const PetscReal  alpha = (ph->isph ? ph->isph->alpha : ph->fl.alpha) * ph->fl.wall_av; /* a is a wall or a solid */
  const PetscBool  riemann = (PetscBool)(!ph->isph && ph->fl.riemann > 0); /* WCSPH's Riemann dissipation */
  const PetscBool  repulsion = (PetscBool)(KindIsSolid(P->kind[a]) && ph->solid && ph->solid->repulsion);
  PetscReal        d[3], dv[3], r2, hab = PairH(h[a], h[b]);
  PetscReal        pa, ra, ma, rb = rho[b];
  PetscReal        pterm, visc, s = m[b] / m[a];
  PetscReal        rep = 0; /* the repulsive force's magnitude along a's normal */
  FluidView(fv, P->kind[a], a, m, rho, p, &ma, &ra, &pa);
  VSub(x + D * b, x + D * a, d, D);
  VSub(v + D * b, v + D * a, dv, D);
  r2    = VDot(d, d, D);
  pterm = p[b] / (rb * rb) + pa / (ra * ra) + ArtificialViscosity(alpha, ph->fl.c0, hab, 0.5 * (ra + rb), VDot(dv, d, D), r2);
  visc  = LaminarViscosity(ma, ph->fl.mu, rb, ra, F * r2, r2, hab, ph->fl.eta, ph->fl.lap_kappa);
  if (riemann) pterm += PField(P, FIELD_QWALL)[b] * (ra + rb) / (ra * rb); /* b's Riemann dissipation against the walls (wcsph.c) */
  if (repulsion) rep = ph->solid->repulsion_scale * FSIRepulsion(VDot(dv, nrm + D * a, D), PetscSqrtReal(r2) / (2 * hab), ph->dt); /* the scale is 1 in 2D at h = 1.3 dx */
  for (PetscInt i = 0; i < D; i++) { /* the fluid's pair acceleration, reversed */
    PetscReal fb = visc * (v[D * b + i] - vw[D * a + i]) - ma * pterm * F * d[i];
    if (repulsion) fb += rep * nrm[D * a + i];
    acc[i] -= s * fb;
  }
}

/* The pressure part of m_a times FluidPairLoad's acceleration, written m_a acc = q g: g is the push a
 * pressure of 1 Pa on both particles gives boundary particle a through the pair (with fluid particle
 * b, F = F_ab), q = (p_a / rho_a^2 + p_b / rho_b^2) / (1 / rho_a^2 + 1 / rho_b^2) the pair's pressure.
 * A uniform pressure c adds c to every q, so a body's sum of q g moves by c sum g, which is zero on a
 * closed surface in the continuum but not over disordered particles (body_force.c). */
SPH_INLINE PetscReal FluidPairPressureUnit(Physics *ph, PetscInt a, PetscInt b, PetscReal F, PetscReal *g, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *m = PField(P, FIELD_M);
  PetscReal        ma, ra, pa, wa, wb;
  FluidView(PField(P, FIELD_FVIEW), P->kind[a], a, m, rho, p, &ma, &ra, &pa);
  wa = 1 / (ra * ra);
  wb = 1 / (rho[b] * rho[b]);
  for (PetscInt i = 0; i < D; i++) g[i] = m[b] * ma * (wa + wb) * F * (x[D * b + i] - x[D * a + i]);
  return (pa * wa + p[b] * wb) / (wa + wb);
}
