#include "fluid/body_force.h"
#include "fluid/boundary_load.h"
#include "particles/pair_loop.h"

/* What the loop over a fluid particle's pairs gathers (BodyForceD). */
typedef struct {
  Physics         *ph;
  const PetscReal *body, *m, *x, *h;
  PetscInt         k, n; /* bodies k .. k + n - 1 */
  PetscReal        f[FLUID_MAX_BODIES][3];
  PetscReal        unit[FLUID_MAX_BODIES][3], level[FLUID_MAX_BODIES][2]; /* sum of g; sums of |g| q and |g| (FluidPairPressureUnit) */
} BodyForceSum;

/* A body particle b's share of pair (a, b): m_b times its acceleration from fluid particle a, with
 * F_ab at the current positions (ISPH's list holds F at the step's intermediate positions, and the
 * particles have moved since by up to a fifth of dx at CFL 0.25: that F with the current x_a - x_b
 * would put a noise of that order on the pressure's force) */
SPH_INLINE void BodyForcePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  BodyForceSum *s = (BodyForceSum *)ctx;
  PetscReal     acc[3] = {0, 0, 0}, d[3], F;
  PetscInt      j = (PetscInt)s->body[p.b] - s->k; /* the body's place among those measured */
  if (j < 0 || j >= s->n || !KindIsBoundary(s->ph->P->kind[p.b])) return;
  VSub(s->x + D * a, s->x + D * p.b, d, D);
  F = KernelF(&s->ph->kernel, PetscSqrtReal(VDot(d, d, D)), PairH(s->h[a], s->h[p.b]));
  FluidPairLoad(s->ph, p.b, a, F, acc, D);
  for (PetscInt i = 0; i < D; i++) s->f[j][i] += s->m[p.b] * acc[i];
  if (s->ph->fl.force_gauge) {
    PetscReal g[3], q = FluidPairPressureUnit(s->ph, p.b, a, F, g, D), gn = PetscSqrtReal(VDot(g, g, D));
    for (PetscInt i = 0; i < D; i++) s->unit[j][i] += g[i];
    s->level[j][0] += gn * q;
    s->level[j][1] += gn;
  }
}

/* Over the owned fluid particles, so that each pair counts once on any number of ranks.  With
 * -fluid_force_gauge (WCSPH's default) the pressure is measured from its mean over the body's pairs,
 * p_mean = sum |g| q / sum |g|: the force is sum (q - p_mean) g plus the other terms, the same for p
 * and p + c, as the reference's integral of the stress over a closed surface is (Turek-Hron CFD1,
 * WCSPH: the momentum exchanged is 7-8 % above the reference, a uniform pressure's push; ISPH's
 * moves by 0.04 N/m per 1000 Pa of level, and there p_mean's correlation with sum g is the
 * pressure's answer to disorder, not a gauge: docs/turek_hron.md). */
SPH_INLINE PetscErrorCode BodyForceD(Physics *ph, PetscInt k, PetscInt n, PetscReal force[][3], const PetscInt D)
{
  Particles    P = ph->P;
  BodyForceSum s = {.ph = ph, .body = PField(P, FIELD_BODY), .m = PField(P, FIELD_M), .x = PField(P, FIELD_X), .h = PField(P, FIELD_H), .k = k, .n = n};
  PetscReal    local[8 * FLUID_MAX_BODIES], sum[8 * FLUID_MAX_BODIES];
  PetscFunctionBeginUser;
  PetscCheck(s.body, ph->comm, PETSC_ERR_ORDER, "A body's force needs the field \"body\": enable it in the scene's create and set it in its populate");
  PetscCheck(k > 0 && n >= 1 && n <= FLUID_MAX_BODIES, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Bodies %" PetscInt_FMT " to %" PetscInt_FMT ": bodies are numbered from 1, at most %d at a time", k, k + n - 1, FLUID_MAX_BODIES);
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a])) SPHPairs(ph->cells, a, BodyForcePair, &s, D);
  for (PetscInt j = 0; j < n; j++) { /* per body: f, then (gauge) unit and level */
    PetscReal *l = local + 8 * j;
    for (PetscInt i = 0; i < 3; i++) { l[i] = s.f[j][i]; l[3 + i] = s.unit[j][i]; }
    l[6] = s.level[j][0];
    l[7] = s.level[j][1];
  }
  PetscCall(MPIU_Allreduce(local, sum, 8 * n, MPIU_REAL, MPIU_SUM, ph->comm));
  for (PetscInt j = 0; j < n; j++) {
    const PetscReal *t = sum + 8 * j, mean = ph->fl.force_gauge && t[7] > 0 ? t[6] / t[7] : 0;
    for (PetscInt i = 0; i < 3; i++) force[j][i] = ph->fl.force_gauge ? t[i] - mean * t[3 + i] : t[i];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidBodyForces(Physics *ph, PetscInt k, PetscInt n, PetscReal force[][3])
{
  return SPH_DIM_DISPATCH(ph->dim, BodyForceD, ph, k, n, force);
}
