#include "fluid/body_force.h"
#include "fluid/boundary_load.h"
#include "particles/pair_loop.h"

/* What the loop over a fluid particle's pairs gathers (BodyForceD). */
typedef struct {
  Physics         *ph;
  const PetscReal *body, *m, *x, *h;
  PetscReal        k;
  PetscReal        f[3];
  PetscReal        unit[3], level[2]; /* sum of g; sums of |g| q and |g| (FluidPairPressureUnit) */
} BodyForceSum;

/* A body particle b's share of pair (a, b): m_b times its acceleration from fluid particle a, with
 * F_ab at the current positions (ISPH's list holds F at the step's intermediate positions, and the
 * particles have moved since by up to a fifth of dx at CFL 0.25: that F with the current x_a - x_b
 * would put a noise of that order on the pressure's force) */
SPH_INLINE void BodyForcePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  BodyForceSum *s = (BodyForceSum *)ctx;
  PetscReal     acc[3] = {0, 0, 0}, d[3], F;
  if (s->body[p.b] != s->k || !KindIsBoundary(s->ph->P->kind[p.b])) return;
  VSub(s->x + D * a, s->x + D * p.b, d, D);
  F = KernelF(&s->ph->kernel, PetscSqrtReal(VDot(d, d, D)), PairH(s->h[a], s->h[p.b]));
  FluidPairLoad(s->ph, p.b, a, F, acc, D);
  for (PetscInt i = 0; i < D; i++) s->f[i] += s->m[p.b] * acc[i];
  if (s->ph->fl.force_gauge) {
    PetscReal g[3], q = FluidPairPressureUnit(s->ph, p.b, a, F, g, D), gn = PetscSqrtReal(VDot(g, g, D));
    for (PetscInt i = 0; i < D; i++) s->unit[i] += g[i];
    s->level[0] += gn * q;
    s->level[1] += gn;
  }
}

/* Over the owned fluid particles, so that each pair counts once on any number of ranks.  With
 * -fluid_force_gauge (WCSPH's default) the pressure is measured from its mean over the body's pairs,
 * p_mean = sum |g| q / sum |g|: the force is sum (q - p_mean) g plus the other terms, the same for p
 * and p + c, as the reference's integral of the stress over a closed surface is (Turek-Hron CFD1,
 * WCSPH: the momentum exchanged is 7-8 % above the reference, a uniform pressure's push; ISPH's
 * moves by 0.04 N/m per 1000 Pa of level, and there p_mean's correlation with sum g is the
 * pressure's answer to disorder, not a gauge: docs/turek_hron.md). */
SPH_INLINE PetscErrorCode BodyForceD(Physics *ph, PetscInt k, PetscReal force[3], const PetscInt D)
{
  Particles    P = ph->P;
  BodyForceSum s = {.ph = ph, .body = PField(P, FIELD_BODY), .m = PField(P, FIELD_M), .x = PField(P, FIELD_X), .h = PField(P, FIELD_H), .k = (PetscReal)k};
  PetscFunctionBeginUser;
  PetscCheck(s.body, ph->comm, PETSC_ERR_ORDER, "A body's force needs the field \"body\": enable it in the scene's create and set it in its populate");
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a])) SPHPairs(ph->cells, a, BodyForcePair, &s, D);
  if (ph->fl.force_gauge) {
    PetscReal local[8] = {s.f[0], s.f[1], s.f[2], s.unit[0], s.unit[1], s.unit[2], s.level[0], s.level[1]}, sum[8], mean;
    PetscCall(MPIU_Allreduce(local, sum, 8, MPIU_REAL, MPIU_SUM, ph->comm));
    mean = sum[7] > 0 ? sum[6] / sum[7] : 0;
    for (PetscInt i = 0; i < 3; i++) force[i] = sum[i] - mean * sum[3 + i];
  } else PetscCall(MPIU_Allreduce(s.f, force, 3, MPIU_REAL, MPIU_SUM, ph->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidBodyForce(Physics *ph, PetscInt k, PetscReal force[3])
{
  return SPH_DIM_DISPATCH(ph->dim, BodyForceD, ph, k, force);
}
