/* What the solid formulations (solid_total.c, solid_updated.c) and the solid's driver (solid.c)
 * share, below all three: the fluid's load on a solid particle, the last step of its acceleration,
 * the kinds of a body.  Private to the solid module. */
#pragma once
#include "solid/solid.h"
#include "fluid/fluid_terms.h"
#include "fluid/isph.h"
#include "base/dim.h"

/* Acceleration of solid a from fluid neighbour b: the reverse of what the fluid gets from a
 * (wcsph.c, isph.c), with a as the fluid sees it (boundary.h): pressure and artificial viscosity,
 * laminar viscosity against a's no-slip velocity and, when on, the repulsive force Eq. 41. */
SPH_INLINE void FluidLoad(Physics *ph, PetscInt a, PetscInt b, PetscReal F, PetscReal *acc, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H);
  const PetscReal *fv = PField(P, FIELD_FVIEW), *vw = PField(P, FIELD_VWALL), *nrm = PField(P, FIELD_NORMAL);
  const PetscReal  alpha = ph->isph ? ph->isph->alpha : ph->fl.alpha;
  PetscReal        d[3], dv[3], r2, hab = PairH(h[a], h[b]);
  PetscReal        pa = fv[3 * a], ra = fv[3 * a + 1], ma = fv[3 * a + 2], rb = rho[b];
  PetscReal        pterm, visc, s = m[b] / m[a];
  PetscReal        rep = 0; /* the repulsive force's magnitude along a's normal */
  VSub(x + D * b, x + D * a, d, D);
  VSub(v + D * b, v + D * a, dv, D);
  r2    = VDot(d, d, D);
  pterm = p[b] / (rb * rb) + pa / (ra * ra) + ArtificialViscosity(alpha, ph->fl.c0, hab, 0.5 * (ra + rb), VDot(dv, d, D), r2);
  visc  = LaminarViscosity(ma, ph->fl.mu, rb, ra, F * r2, r2, hab, ph->fl.eta, ph->fl.lap_kappa);
  if (ph->solid->repulsion) rep = FSIRepulsion(VDot(dv, nrm + D * a, D), PetscSqrtReal(r2) / (2 * hab), ph->dt);
  rep *= ph->solid->repulsion_scale; /* 1 in 2D at h = 1.3 dx */
  for (PetscInt i = 0; i < D; i++) { /* the fluid's pair acceleration, reversed */
    PetscReal fb = visc * (v[D * b + i] - vw[D * a + i]) - ma * pterm * F * d[i];
    if (ph->solid->repulsion) fb += rep * nrm[D * a + i];
    acc[i] -= s * fb;
  }
}

/* Owned solid a: internal acceleration ai, the fluid's load fl, gravity and, with
 * -solid_damping, a drag -zeta v.  A clamp is
 * held: the support takes what would accelerate it; the sums feed the probes. */
SPH_INLINE void SolidAccelerate(Physics *ph, PetscInt a, const PetscReal *ai, const PetscReal *fl, PetscReal *acc, PetscReal *support, PetscReal *load, const PetscInt D)
{
  Particles        P    = ph->P;
  const PetscReal *mass = PField(P, FIELD_M);
  if (P->kind[a] == KIND_SOLID)
    for (PetscInt i = 0; i < D; i++) load[i] += mass[a] * fl[i];
  if (P->kind[a] == KIND_CLAMP) {
    for (PetscInt i = 0; i < D; i++) support[i] -= mass[a] * (ai[i] + fl[i] + ph->g[i]);
    for (PetscInt i = 0; i < D; i++) acc[D * a + i] = 0;
    return;
  }
  for (PetscInt i = 0; i < D; i++) acc[D * a + i] = ai[i] + fl[i] + ph->g[i];
  if (ph->solid->damping > 0) { /* dynamic relaxation */
    const PetscReal *v = PField(P, FIELD_V);
    for (PetscInt i = 0; i < D; i++) acc[D * a + i] -= ph->solid->damping * v[D * a + i];
  }
}

/* The kinds of a body (solid and clamp): the solid's neighbour list and its ghost refreshes. */
static inline PetscBool SolidKeep(PetscInt kind) { return KindIsSolid(kind); }
