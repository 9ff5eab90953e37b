/* What both solid formulations (solid.c, solid_total.c) share: the fluid's load on a solid
 * particle and the last step of its acceleration.  Private to the solid module. */
#pragma once
#include <sphfsi/solid.h>
#include <sphfsi/fluid_terms.h>
#include <sphfsi/isph.h>

/* Acceleration of solid a from fluid neighbour b: the reverse of what the fluid gets from a
 * (wcsph.c, isph.c), with a as the fluid sees it (boundary.h): pressure and artificial viscosity,
 * laminar viscosity against a's no-slip velocity and, when on, the repulsive force Eq. 41. */
static inline void FluidLoad(Sim sim, PetscInt a, PetscInt b, PetscReal F, PetscReal acc[2])
{
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H);
  const PetscReal *fv = PField(P, FIELD_FVIEW), *vw = PField(P, FIELD_VWALL), *nrm = PField(P, FIELD_NORMAL);
  const PetscReal  alpha = sim->isph ? sim->isph->alpha : sim->fl.alpha;
  PetscReal        dx = x[2 * b] - x[2 * a], dy = x[2 * b + 1] - x[2 * a + 1], r2 = dx * dx + dy * dy, hab = PairH(h[a], h[b]);
  PetscReal        pa = fv[3 * a], ra = fv[3 * a + 1], ma = fv[3 * a + 2], rb = rho[b];
  PetscReal        dvx = v[2 * b] - v[2 * a], dvy = v[2 * b + 1] - v[2 * a + 1];
  PetscReal        pterm = p[b] / (rb * rb) + pa / (ra * ra) + ArtificialViscosity(alpha, sim->fl.c0, hab, 0.5 * (ra + rb), dvx * dx + dvy * dy, r2);
  PetscReal        visc = LaminarViscosity(ma, sim->fl.mu, rb, ra, F * r2, r2, hab, sim->fl.eta, sim->fl.lap_kappa), s = m[b] / m[a];
  PetscReal        fb[2]; /* the fluid's pair acceleration */
  fb[0] = visc * (v[2 * b] - vw[2 * a]) - ma * pterm * F * dx;
  fb[1] = visc * (v[2 * b + 1] - vw[2 * a + 1]) - ma * pterm * F * dy;
  if (sim->solid->repulsion) {
    PetscReal f = FSIRepulsion(dvx * nrm[2 * a] + dvy * nrm[2 * a + 1], PetscSqrtReal(r2) / (2 * hab), sim->dt);
    fb[0] += f * nrm[2 * a]; fb[1] += f * nrm[2 * a + 1];
  }
  acc[0] -= s * fb[0];
  acc[1] -= s * fb[1];
}

/* Owned solid a: internal acceleration (ax, ay), the fluid's load fl, gravity and, with
 * -solid_damping, a drag -zeta v.  A clamp is
 * held: the support takes what would accelerate it; the sums feed the probes. */
static inline void SolidAccelerate(Sim sim, PetscInt a, PetscReal ax, PetscReal ay, const PetscReal fl[2], PetscReal *acc, PetscReal support[2], PetscReal load[2])
{
  Particles        P    = sim->P;
  const PetscReal *mass = PField(P, FIELD_M);
  if (P->kind[a] == KIND_SOLID) { load[0] += mass[a] * fl[0]; load[1] += mass[a] * fl[1]; }
  if (P->kind[a] == KIND_CLAMP) {
    support[0] -= mass[a] * (ax + fl[0] + sim->g[0]);
    support[1] -= mass[a] * (ay + fl[1] + sim->g[1]);
    acc[2 * a] = acc[2 * a + 1] = 0;
    return;
  }
  acc[2 * a]     = ax + fl[0] + sim->g[0];
  acc[2 * a + 1] = ay + fl[1] + sim->g[1];
  if (sim->solid->damping > 0) { /* dynamic relaxation */
    const PetscReal *v = PField(P, FIELD_V);
    acc[2 * a] -= sim->solid->damping * v[2 * a];
    acc[2 * a + 1] -= sim->solid->damping * v[2 * a + 1];
  }
}

/* Total-Lagrangian formulation (solid_total.c).  Prepare: after each rebuild of the solid's list,
 * the pairs' reference kernel values and each owned particle's correction; Rates: deformation
 * gradient, stress and accelerations at the current positions; StrainEnergy: owned, not reduced. */
PetscErrorCode SolidTotalPrepare(Sim sim);
PetscErrorCode SolidTotalRates(Sim sim);
PetscReal      SolidTotalStrainEnergy(Sim sim);
