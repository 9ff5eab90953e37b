#include "fluid/body_force.h"
#include "fluid/boundary_load.h"
#include "particles/pair_loop.h"

/* What the loop over a fluid particle's pairs gathers (BodyForceD). */
typedef struct {
  Physics         *ph;
  const PetscReal *body, *m, *x, *h;
  PetscReal        k;
  PetscReal        f[3];
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
}

/* Over the owned fluid particles, so that each pair counts once on any number of ranks. */
SPH_INLINE PetscErrorCode BodyForceD(Physics *ph, PetscInt k, PetscReal force[3], const PetscInt D)
{
  Particles    P = ph->P;
  BodyForceSum s = {.ph = ph, .body = PField(P, FIELD_BODY), .m = PField(P, FIELD_M), .x = PField(P, FIELD_X), .h = PField(P, FIELD_H), .k = (PetscReal)k};
  PetscFunctionBeginUser;
  PetscCheck(s.body, ph->comm, PETSC_ERR_ORDER, "A body's force needs the field \"body\": enable it in the scene's create and set it in its populate");
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a])) SPHPairs(ph->cells, a, BodyForcePair, &s, D);
  PetscCall(MPIU_Allreduce(s.f, force, 3, MPIU_REAL, MPIU_SUM, ph->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidBodyForce(Physics *ph, PetscInt k, PetscReal force[3])
{
  return SPH_DIM_DISPATCH(ph->dim, BodyForceD, ph, k, force);
}
