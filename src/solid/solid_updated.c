/* The seed's hypo-elastic solid (-solid_formulation updated; sections 2.2 and 2.4): pressure from
 * the equation of state Eq. 20, artificial stress Eqs. 25-34, momentum Eq. 23 with artificial
 * viscosity Eq. 24, and the deviatoric stress by the Jaumann rate Eqs. 35-40, all in the current
 * configuration, in 2D (plane strain) or 3D. */
#include "solid/solid_impl.h"
#include "solid/solid_updated.h"
#include "solid/solid_terms.h"
#include "base/kernel.h"
#include "fluid/operators.h"
#include "particles/halo.h"
#include "particles/pair_loop.h"

/* Pressure (Eq. 20) and artificial stress (Eqs. 25-34) of owned and ghost solids: both are
 * functions of the particle's own density and stress, so ghosts compute theirs. */
SPH_INLINE PetscErrorCode PressureAndArtificialStressD(Physics *ph, const PetscInt D)
{
  Particles            P = ph->P;
  Solid                s = ph->solid;
  const SolidMaterial *m = &ph->sl;
  const PetscReal     *rho = PField(P, FIELD_RHO), *S = PField(P, FIELD_S);
  PetscReal           *p = PField(P, FIELD_P);
  PetscInt             N = P->n + P->ng;
  const PetscInt       NS = D * (D + 1) / 2;

  PetscFunctionBeginUser;
  if (m->eps > 0 && s->cap_R < N) {
    PetscCall(PetscFree(s->R));
    s->cap_R = P->cap;
    PetscCall(PetscMalloc1(NS * s->cap_R, &s->R));
  }
  for (PetscInt a = 0; a < N; a++) {
    if (!KindIsSolid(P->kind[a])) continue;
    p[a] = SolidEOSPressure(m, rho[a]);
    if (m->eps <= 0) continue;
    if (D == 2) ArtificialStress(m->eps, S[3 * a] - p[a], S[3 * a + 1], S[3 * a + 2] - p[a], rho[a], s->R + 3 * a);
    else {
      const PetscReal *Sa = S + 6 * a;
      PetscReal        sigma[6] = {Sa[0] - p[a], Sa[1], Sa[2], Sa[3] - p[a], Sa[4], Sa[5] - p[a]};
      ArtificialStress3(m->eps, sigma, rho[a], s->R + 6 * a);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* out = L g for the D x D row-major L, or g itself without correction */
SPH_INLINE void Apply(const PetscReal *L, const PetscReal *g, PetscReal *out, const PetscInt D)
{
  for (PetscInt i = 0; i < D; i++) out[i] = L ? VDot(L + D * i, g, D) : g[i];
}

/* Row i of the symmetric tensor T (dim.h's order) of particle a minus c on the diagonal, times s. */
SPH_INLINE void SymRow(const PetscReal *T, PetscInt i, PetscReal c, PetscReal s, PetscReal *row, const PetscInt D)
{
  for (PetscInt j = 0; j < D; j++) row[j] = (j == i ? T[SymIndex(i, j, D)] - c : T[SymIndex(i, j, D)]) * s;
}

/* What Eq. 23 gathers over the pairs of solid a (MomentumD). */
typedef struct {
  Physics             *ph;
  Particles            P;
  const SolidMaterial *sm;
  const PetscReal     *x, *v, *rho, *p, *mass, *h, *S, *R, *L;
  PetscReal            ra, wdx, sa[9]; /* rho_a, W(dx, h_a), sigma_a / rho_a^2 */
  PetscInt             n_int;          /* the artificial stress's exponent when a whole number (1..16), else 0 */
  PetscReal            ac[3], fl[3];   /* the solid's own acceleration, the fluid's load */
} MomentumSum;

/* f^n for a whole n >= 1 by squaring: the default n = 4 is two multiplications, where pow() took a
 * sixth of the updated solid's instructions */
SPH_INLINE PetscReal IntPower(PetscReal f, PetscInt n)
{
  PetscReal r = 1;
  for (; n; n >>= 1, f *= f)
    if (n & 1) r *= f;
  return r;
}

/* Eq. 23's pair with Eq. 24 and the artificial stress, or the fluid's load */
SPH_INLINE void MomentumPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  MomentumSum         *s = (MomentumSum *)ctx;
  const SolidMaterial *m = s->sm;
  const PetscReal     *x = s->x, *v = s->v, *S = s->S, *R = s->R, *L = s->L, *mass = s->mass;
  const PetscInt       NS = D * (D + 1) / 2;
  PetscInt             b = pr.b;
  PetscReal            d[3], g[3], dv[3], r2, rb = s->rho[b], ib = 1.0 / (rb * rb), ga[3], gb[3], gm[3], pi;
  if (pr.F == 0) return; /* in the skin */
  if (KindIsFluid(s->P->kind[b])) { FluidPairLoad(s->ph, a, b, pr.F, s->fl, D); return; }
  if (!KindIsSolid(s->P->kind[b])) return;
  VSub(x + D * a, x + D * b, d, D);
  VSub(v + D * a, v + D * b, dv, D);
  r2 = VDot(d, d, D);
  for (PetscInt i = 0; i < D; i++) g[i] = pr.F * d[i];
  pi = ArtificialViscosity(m->alpha, m->c0, PairH(s->h[a], s->h[b]), 0.5 * (s->ra + rb), VDot(dv, d, D), r2);
  Apply(L ? L + D * D * a : NULL, g, ga, D);
  Apply(L ? L + D * D * b : NULL, g, gb, D);
  for (PetscInt i = 0; i < D; i++) gm[i] = 0.5 * (ga[i] + gb[i]);
  /* sigma_a / rho_a^2 through ga, sigma_b / rho_b^2 through gb, Pi (and R) through the mean */
  for (PetscInt i = 0; i < D; i++) {
    PetscReal sb[3];
    SymRow(S + NS * b, i, s->p[b], 1.0, sb, D);
    s->ac[i] += mass[b] * (VDot(s->sa + D * i, ga, D) + VDot(sb, gb, D) * ib - pi * gm[i]);
  }
  if (R) {
    PetscReal fn = s->n_int ? IntPower(pr.W / s->wdx, s->n_int) : PetscPowReal(pr.W / s->wdx, m->n), t[6], row[3];
    for (PetscInt q = 0; q < NS; q++) t[q] = fn * (R[NS * a + q] + R[NS * b + q]);
    for (PetscInt i = 0; i < D; i++) {
      SymRow(t, i, 0.0, 1.0, row, D);
      s->ac[i] += mass[b] * VDot(row, gm, D);
    }
  }
}

/* Eq. 23 for owned solids over their solid neighbours: stress, artificial viscosity (Eq. 24) and
 * artificial stress; the fluid's loads (FluidPairLoad); gravity.  Walls do not act; clamps do not
 * accelerate: what would, the support takes (Solid.support).  With the corrected gradient each
 * particle's stress acts through its own corrected kernel gradient, sigma_a L_a grad W +
 * sigma_b L_b grad W (pair terms with the mean), which keeps the pair forces opposite. */
SPH_INLINE PetscErrorCode MomentumD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P);
  const PetscReal *mass = PField(P, FIELD_M), *h = PField(P, FIELD_H), *S = PField(P, FIELD_S), *R = ph->solid->R, *L = PField(P, FIELD_KCORR);
  PetscReal       *acc = PField(P, FIELD_ACC), support[3] = {0, 0, 0}, load[3] = {0, 0, 0};
  const PetscInt   NS = D * (D + 1) / 2, n_int = ph->sl.n >= 1 && ph->sl.n <= 16 && ph->sl.n == PetscFloorReal(ph->sl.n) ? (PetscInt)ph->sl.n : 0;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    MomentumSum s = {.ph = ph, .P = P, .sm = &ph->sl, .x = x, .v = v, .rho = rho, .p = p, .mass = mass, .h = h, .S = S, .R = R, .L = L, .ra = rho[a]};
    PetscReal   ia = 1.0 / (s.ra * s.ra);
    if (!KindIsSolid(P->kind[a])) continue;
    for (PetscInt i = 0; i < D; i++) SymRow(S + NS * a, i, p[a], ia, s.sa + D * i, D); /* sigma_a / rho_a^2 */
    s.wdx   = R ? KernelW(&ph->kernel, h[a] / ph->kernel.h_factor, h[a]) : 1;
    s.n_int = n_int;
    SPHPairsW(ph->solid->nl, P, a, (PetscBool)!!R, MomentumPair, &s, D);
    SolidAccelerate(ph, a, s.ac, s.fl, acc, support, load, D);
  }
  for (PetscInt i = 0; i < D; i++) { ph->solid->support[i] = support[i]; ph->solid->load[i] = load[i]; }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidUpdatedRates(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(SPH_DIM_DISPATCH(ph->dim, PressureAndArtificialStressD, ph));
  if (ph->solid->gradient == SOLID_GRAD_CORRECTED) {
    const FieldId kc[] = {FIELD_KCORR};
    PetscCall(SPHGradientCorrection(ph->P, ph->solid->nl, SolidKeep, PField(ph->P, FIELD_KCORR)));
    PetscCall(HaloRefreshKinds(ph->halo, ph->P, SolidKeep, 1, kc));
  }
  PetscCall(SPH_DIM_DISPATCH(ph->dim, MomentumD, ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* sum_b V_b (v_b - v_a) (x) L_a grad_a W_ab over the solid neighbours of a */
typedef struct {
  Particles        P;
  const PetscReal *x, *v, *rho, *m, *L;
  PetscReal        g[9];
} VelocityGradientSum;

SPH_INLINE void VelocityGradientPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  VelocityGradientSum *s = (VelocityGradientSum *)ctx;
  PetscInt             b = p.b;
  PetscReal            gw[3], fd[3], V, dv[3];
  if (!KindIsSolid(s->P->kind[b]) || p.F == 0) return;
  for (PetscInt i = 0; i < D; i++) fd[i] = p.F * (s->x[D * a + i] - s->x[D * b + i]);
  Apply(s->L ? s->L + D * D * a : NULL, fd, gw, D);
  V = s->m[b] / s->rho[b];
  for (PetscInt i = 0; i < D; i++) dv[i] = V * (s->v[D * b + i] - s->v[D * a + i]);
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt j = 0; j < D; j++) s->g[D * i + j] += dv[i] * gw[j];
}

/* Velocity gradient g_ij = dv_i/dx_j (row-major) of owned solid a from its solid neighbours:
 * Eqs. 35-38 use g = sum V_b (v_b - v_a) (x) grad_a W; corrected, grad_a W becomes L_a grad_a W. */
SPH_INLINE void VelocityGradient(Physics *ph, PetscInt a, PetscReal *g, const PetscInt D)
{
  Particles           P = ph->P;
  VelocityGradientSum s = {.P = P, .x = PField(P, FIELD_X), .v = PField(P, FIELD_V), .rho = PField(P, FIELD_RHO), .m = PField(P, FIELD_M), .L = PField(P, FIELD_KCORR)};
  SPHPairs(ph->solid->nl, a, VelocityGradientPair, &s, D);
  for (PetscInt i = 0; i < D * D; i++) g[i] = s.g[i];
}

/* Density (continuity, Eq. 18 as -rho div v) and deviatoric stress (Eqs. 35-40) of owned solids
 * and clamps over dt, from the current velocities at the positions of the last SolidRates.  The
 * density changes after the loop: neighbours' volumes m/rho must be those of the step's start,
 * owned or ghost alike, or the answer would depend on the decomposition. */
SPH_INLINE PetscErrorCode DeformD(Physics *ph, PetscReal dt, const PetscInt D)
{
  Particles  P = ph->P;
  PetscReal *rho = PField(P, FIELD_RHO), *S = PField(P, FIELD_S), *drho = PField(P, FIELD_DRHO);

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal g[9], div;
    if (!KindIsSolid(P->kind[a])) continue;
    VelocityGradient(ph, a, g, D);
    div = g[0] + g[D + 1];
    if (D == 3) div += g[8];
    drho[a] = -rho[a] * div;
    /* D_xy = (du/dy + dv/dx) / 2, spin W_xy = (du/dy - dv/dx) / 2 (Eqs. 37-38) */
    if (D == 2) JaumannUpdate(ph->sl.G, dt, g[0], 0.5 * (g[1] + g[2]), g[3], 0.5 * (g[1] - g[2]), S + 3 * a);
    else JaumannUpdate3(ph->sl.G, dt, g, S + 6 * a);
  }
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsSolid(P->kind[a])) rho[a] += dt * drho[a];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidUpdatedDeform(Physics *ph, PetscReal dt) { return SPH_DIM_DISPATCH(ph->dim, DeformD, ph, dt); }
