/* Total-Lagrangian SPH solid (-solid_formulation total).  Gradients are taken in the reference
 * configuration X0 (the particles as built), by a weighted least-squares fit over the kernel
 * support, with weights w_ab = V0_b |grad0 W_ab| / |X_ab| and basis p_ab = (X, Y, X^2 / 2h, XY / h,
 * Y^2 / 2h) of the bond X_ab = X_b - X_a (-solid_order 2; in 3D the 9 terms X, Y, Z and the six
 * products) or (X, Y[, Z]) (order 1, which is the kernel-gradient correction of Bonet & Lok):
 *   F_a = sum_b w_ab (x_b - x_a) (x) G_a p_ab,   G_a = the first D rows of [sum_b w_ab p p^T]^-1,
 * exact for every displacement of that order, also at a free surface or a clamp where the kernel
 * is cut.  Order 1 is exact only for affine fields: at the surface of a bent plate it takes the
 * strain of a point inside it, and at 5 particles across that makes the plate 42 % too compliant.
 * G_a is fixed by the reference configuration and computed after each rebuild.
 * The stress is hyper-elastic (neo-Hookean or St Venant-Kirchhoff, -solid_law, solid_terms.h);
 * the forces are minus the gradient of the discrete strain energy sum_a V0_a W(F_a) (so energy
 * and momentum are conserved):
 *   dv_a/dt = 1 / rho0 sum_b V0_b |grad0 W_ab| / |X_ab| (Q_a p_ab - Q_b p_ba),   Q = P G,
 * P = F S the first Piola-Kirchhoff stress; with order 1 this is the usual
 * 1 / rho0 sum_b V0_b (P_a B_a + P_b B_b) grad0 W_ab.  Rotations are exact: no Jaumann rate and no
 * tensile instability to hold off with an artificial stress.  An optional hourglass energy
 * (solid_terms.h) penalises bonds no affine map explains; the seed's artificial viscosity
 * (Eq. 24) acts on the current pairs as in the updated scheme.  Density, pressure and deviatoric
 * stress are derived from F for the output and the fluid. */
#include "solid/solid_impl.h"
#include "solid/solid_total.h"
#include "solid/solid_terms.h"
#include "base/kernel.h"
#include "particles/halo.h"
#include "particles/pair_loop.h"

/* The fit's basis size: D first-order terms and D (D + 1) / 2 second-order ones (5 or 9). */
#define NB(D) ((D) + (D) * ((D) + 1) / 2)

/* Basis of the bond X from a particle of smoothing length h: p[0..NB-1], the products in the
 * symmetric order of dim.h (2D: X^2 / 2h, XY / h, Y^2 / 2h). */
SPH_INLINE void Basis(const PetscReal *X, PetscReal h, PetscReal *p, const PetscInt D)
{
  PetscReal ih = 1.0 / h;
  PetscInt  n  = D;
  for (PetscInt i = 0; i < D; i++) p[i] = X[i];
  for (PetscInt j = 0; j < D; j++)
    for (PetscInt k = j; k < D; k++) p[n++] = j == k ? 0.5 * X[j] * X[j] * ih : X[j] * X[k] * ih;
}

/* M^-1 for the symmetric n x n M (n <= 9, row stride s), into the s x s row-major G (zero beyond
 * n), by Gauss-Jordan elimination with partial pivoting; PETSC_FALSE when M is singular against
 * its scale. */
static PetscBool Inverse(PetscInt n, PetscInt s, const PetscReal *M, PetscReal *G)
{
  PetscReal A[9][18], big = 0;
  for (PetscInt i = 0; i < n; i++) {
    for (PetscInt j = 0; j < n; j++) { A[i][j] = M[s * i + j]; A[i][n + j] = i == j; }
    big = PetscMax(big, PetscAbsReal(M[(s + 1) * i]));
  }
  for (PetscInt c = 0; c < n; c++) {
    PetscInt piv = c;
    for (PetscInt i = c + 1; i < n; i++) if (PetscAbsReal(A[i][c]) > PetscAbsReal(A[piv][c])) piv = i;
    if (PetscAbsReal(A[piv][c]) < 1e-9 * big) return PETSC_FALSE;
    for (PetscInt j = 0; j < 2 * n; j++) { PetscReal t = A[c][j]; A[c][j] = A[piv][j]; A[piv][j] = t; }
    for (PetscInt i = 0; i < n; i++) {
      PetscReal r;
      if (i == c) continue;
      r = A[i][c] / A[c][c];
      for (PetscInt j = c; j < 2 * n; j++) A[i][j] -= r * A[c][j];
    }
  }
  for (PetscInt i = 0; i < s; i++)
    for (PetscInt j = 0; j < s; j++) G[s * i + j] = i < n && j < n ? A[i][n + j] / A[i][i] : 0;
  return PETSC_TRUE;
}

/* -solid_clamp face: a clamp is a boundary, not material.  Each clamp particle next to the body
 * (its nearest solid particle within 1.5 dx in the reference configuration) stands in the fits
 * for the point midway to that particle, on the face where the displacement is zero; deeper clamp
 * particles take no part, and clamps store no energy.  Fitted across the face as material, the
 * displacement (zero in the clamp, quadratic in the plate) has a jump in its second derivative
 * there, which made the root too compliant at first order.  Done once per particle: a moved X0
 * (x != X0; a clamp never moves) marks it, and a checkpoint keeps it. */
static PetscBool ClampFace(Particles P, PetscInt b)
{
  const PetscReal *x = PField(P, FIELD_X), *X = PField(P, FIELD_X0);
  PetscBool        moved = PETSC_FALSE;
  if (P->kind[b] != KIND_CLAMP) return PETSC_FALSE;
  for (PetscInt i = 0; i < P->dim; i++) moved = (PetscBool)(moved || x[P->dim * b + i] != X[P->dim * b + i]);
  return moved;
}

/* The nearest solid neighbour of clamp a in the reference configuration, within sqrt(best). */
typedef struct {
  Particles        P;
  const PetscReal *X;
  PetscReal        best;
  PetscInt         nearest;
} NearestSolid;

SPH_INLINE void NearestSolidPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  NearestSolid *s = (NearestSolid *)ctx;
  PetscReal     d[3], r2;
  if (s->P->kind[p.b] != KIND_SOLID) return;
  VSub(s->X + D * p.b, s->X + D * a, d, D);
  r2 = VDot(d, d, D);
  if (r2 < s->best * (1 - 1e-9)) { s->best = r2; s->nearest = p.b; }
}

SPH_INLINE PetscErrorCode ClampFacesD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  PetscReal       *X = PField(P, FIELD_X0);
  const PetscReal *h = PField(P, FIELD_H);
  const FieldId    x0[] = {FIELD_X0};
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal    lim = 1.5 * h[a] / ph->kernel.h_factor, mid[3];
    NearestSolid s   = {.P = P, .X = X, .best = lim * lim, .nearest = -1};
    PetscInt     nearest;
    if (P->kind[a] != KIND_CLAMP || ClampFace(P, a)) continue;
    SPHPairs(ph->solid->nl, a, NearestSolidPair, &s, D);
    nearest = s.nearest;
    if (nearest < 0) continue;
    for (PetscInt i = 0; i < D; i++) mid[i] = 0.5 * (X[D * a + i] + X[D * nearest + i]);
    for (PetscInt i = 0; i < D; i++) X[D * a + i] = mid[i];
  }
  PetscCall(HaloRefresh(ph->halo, P, 1, x0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The smoothing length of the solid's own pair (a, b): the pair's h scaled by -solid_h_factor's
 * ratio to the run's (exactly 1 by default) */
SPH_INLINE PetscReal SolidPairH(Solid s, const PetscReal *h, PetscInt a, PetscInt b) { return PairH(h[a], h[b]) * s->h_ratio; }

/* A clamp face point c pairs with solid a while the clamp particle itself is within the support
 * of a: the neighbour search, which runs at the particles' positions, then always holds the pair. */
SPH_INLINE PetscBool FaceInSupport(Physics *ph, PetscInt a, PetscInt c, const PetscInt D)
{
  const PetscReal *x = PField(ph->P, FIELD_X), *X = PField(ph->P, FIELD_X0), *h = PField(ph->P, FIELD_H);
  PetscReal        d[3], r = 2 * SolidPairH(ph->solid, h, a, c);
  VSub(x + D * c, X + D * a, d, D);
  return (PetscBool)(VDot(d, d, D) < r * r);
}

/* Whether b enters the fit of a: solids both; with clamp faces, a clamp only as a face point and
 * never as the centre of a fit. */
static PetscBool InFit(Solid s, Particles P, PetscInt a, PetscInt b)
{
  if (!KindIsSolid(P->kind[a]) || !KindIsSolid(P->kind[b])) return PETSC_FALSE;
  if (!s->clamp_face) return PETSC_TRUE;
  return (PetscBool)(P->kind[a] == KIND_SOLID && (P->kind[b] == KIND_SOLID || ClampFace(P, b)));
}

/* The solid's own arrays (solid.h) for this rebuild's particles: each owned and ghost solid's slot,
 * the room, and the SF that refreshes the ghosts' slots. */
static PetscErrorCode SolidSlots(Physics *ph, const PetscInt D)
{
  Solid          s = ph->solid;
  Particles      P = ph->P;
  const PetscInt nb = NB(D), nt = P->n + P->ng;
  PetscFunctionBeginUser;
  if (nt > s->cap_slot) {
    PetscCall(PetscFree(s->slot));
    s->cap_slot = (3 * nt) / 2 + 16;
    PetscCall(PetscMalloc1(s->cap_slot, &s->slot));
  }
  s->nslot = 0;
  for (PetscInt a = 0; a < P->n; a++) s->slot[a] = KindIsSolid(P->kind[a]) ? s->nslot++ : -1;
  s->nown = s->nslot; /* the owned first, then the ghosts */
  for (PetscInt a = P->n; a < nt; a++) s->slot[a] = KindIsSolid(P->kind[a]) ? s->nslot++ : -1;
  if (s->nown > s->cap_G0) {
    PetscCall(PetscFree(s->G0));
    s->cap_G0 = (3 * s->nown) / 2 + 16;
    PetscCall(PetscMalloc1(nb * nb * s->cap_G0, &s->G0));
  }
  if (s->nslot > s->cap_FQ) {
    PetscCall(PetscFree2(s->Fd, s->Qd));
    s->cap_FQ = (3 * s->nslot) / 2 + 16;
    PetscCall(PetscMalloc2(D * D * s->cap_FQ, &s->Fd, D * nb * s->cap_FQ, &s->Qd));
  }
  PetscCall(HaloSlotSF(ph->halo, P, s->slot, s->nown, &s->sf_slot));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the reference fit of particle a gathers over its pairs: each pair's reference F0 (into the
 * solid's f0), their count, and the fit's moment matrix M. */
typedef struct {
  Physics         *ph;
  Solid            s;
  Particles        P;
  const PetscReal *X, *m, *h;
  PetscReal        rho0;
  PetscInt         nb, nbmax, npair;
  PetscReal        M[81];
} ReferenceFit;

/* F0 of clamp face point a's pair with solid b, which the face's reaction reads */
SPH_INLINE void FacePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  ReferenceFit *r = (ReferenceFit *)ctx;
  PetscInt      b = p.b;
  PetscReal     d[3];
  if (r->P->kind[b] != KIND_SOLID || !FaceInSupport(r->ph, b, a, D)) return;
  VSub(r->X + D * b, r->X + D * a, d, D);
  r->s->f0[p.k] = KernelF(&r->ph->kernel, PetscSqrtReal(VDot(d, d, D)), SolidPairH(r->s, r->h, a, b));
  if (r->s->f0[p.k] != 0) r->npair++;
}

/* F0 of a pair of the fit and its share of M = sum_b w_ab p_ab p_ab^T */
SPH_INLINE void FitMomentPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  ReferenceFit *r = (ReferenceFit *)ctx;
  Solid         s = r->s;
  PetscInt      b = pr.b, k = pr.k;
  PetscReal     d[3], w, p[9];
  if (!InFit(s, r->P, a, b) || (r->P->kind[b] == KIND_CLAMP && !FaceInSupport(r->ph, a, b, D))) return;
  VSub(r->X + D * b, r->X + D * a, d, D);
  s->f0[k] = KernelF(&r->ph->kernel, PetscSqrtReal(VDot(d, d, D)), SolidPairH(s, r->h, a, b));
  if (s->f0[k] == 0) return;
  r->npair++;
  w = -r->m[b] / r->rho0 * s->f0[k];
  Basis(d, r->h[a], p, D);
  for (PetscInt i = 0; i < r->nb; i++)
    for (PetscInt j = 0; j < r->nb; j++) r->M[r->nbmax * i + j] += w * p[i] * p[j];
}

SPH_INLINE PetscErrorCode TotalPrepareD(Physics *ph, const PetscInt D)
{
  Solid            s = ph->solid;
  Cells            C = s->nl;
  Particles        P = ph->P;
  const PetscReal *X = PField(P, FIELD_X0), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), rho0 = ph->sl.rho0;
  const PetscInt   nbmax = NB(D), nb = s->order == 2 ? nbmax : D, n2 = nbmax * nbmax;
  PetscInt         npair = 0, npairs = C->nstart[C->npart];

  PetscFunctionBeginUser;
  if (s->clamp_face && !s->faces_placed) PetscCall(ClampFacesD(ph, D)); /* the reference never changes: once per run (a restart finds them in X0) */
  s->faces_placed = PETSC_TRUE;
  if (npairs > s->cap_ref) {
    PetscCall(PetscFree(s->f0));
    s->cap_ref = C->cap_nbr;
    PetscCall(PetscMalloc1(s->cap_ref, &s->f0));
  }
  PetscCall(SolidSlots(ph, D));
  for (PetscInt a = 0; a < P->n; a++) {
    ReferenceFit     r = {.ph = ph, .s = s, .P = P, .X = X, .m = m, .h = h, .rho0 = rho0, .nb = nb, .nbmax = nbmax};
    const PetscReal *M = r.M;
    PetscReal        M2[81] = {0}, *G;
    if (!KindIsSolid(P->kind[a])) continue;
    G = s->G0 + n2 * s->slot[a];
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) s->f0[k] = 0;
    if (s->clamp_face && P->kind[a] == KIND_CLAMP) { /* no fit, no energy; a face point keeps its pairs with the solids that fit it, for the support's reaction */
      PetscCall(PetscArrayzero(G, n2));
      if (!ClampFace(P, a)) continue;
      SPHPairs(C, a, FacePair, &r, D);
      npair += r.npair;
      continue;
    }
    SPHPairs(C, a, FitMomentPair, &r, D);
    npair += r.npair;
    if (nb == nbmax && Inverse(nbmax, nbmax, M, G)) continue;
    for (PetscInt i = 0; i < D; i++) /* order 1, or a corner with too few neighbours for order 2 */
      for (PetscInt j = 0; j < D; j++) M2[nbmax * i + j] = M[nbmax * i + j];
    PetscCheck(Inverse(D, nbmax, M2, G), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Solid particle %" PetscInt_FMT " has too few neighbours in its reference configuration for a gradient: a solid must be at least 2 particles thick", P->id[a]);
  }
  /* the search runs in the current configuration: a body stretched by more than the skin over
   * 2 h loses pairs of its reference configuration, which the global count shows */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &npair, 1, MPIU_INT, MPI_SUM, ph->comm));
  if (!s->npair_ref) s->npair_ref = npair;
  /* a fault (guard.h): a body torn this far is a blow-up in all but the most extreme loadings */
  PetscCheck(npair == s->npair_ref, ph->comm, PETSC_ERR_NOT_CONVERGED, "The solid stretched so far that %" PetscInt_FMT " of its %" PetscInt_FMT " reference-configuration pairs left the neighbour search (2 h + %g dx): raise -solid_skin (at most 2) or use -solid_formulation updated", s->npair_ref - npair, s->npair_ref, (double)s->skin);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTotalPrepare(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, TotalPrepareD, ph); }

/* A_a = sum_b w_ab (x_b - x_a) (x) p_ab over the reference pairs of a */
typedef struct {
  Solid            s;
  Particles        P;
  const PetscReal *X, *x, *m, *h;
  PetscReal        ir0;
  PetscReal        A[27];
} FitSum;

SPH_INLINE void FitPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  FitSum          *f = (FitSum *)ctx;
  const PetscReal *X = f->X, *x = f->x, *f0 = f->s->f0;
  const PetscInt   nb = NB(D);
  PetscInt         b = p.b;
  PetscReal        w, pb[9], u[3], Xab[3];
  if (f0[p.k] == 0) return; /* not a reference neighbour (or not a solid) */
  w = -f->m[b] * f->ir0 * f0[p.k];
  const PetscReal *xb = f->P->kind[b] == KIND_CLAMP && f->s->clamp_face ? X + D * b : x + D * b; /* a clamp face point does not move */
  VSub(X + D * b, X + D * a, Xab, D);
  Basis(Xab, f->h[a], pb, D);
  for (PetscInt c = 0; c < D; c++) u[c] = w * (xb[c] - x[D * a + c]);
  for (PetscInt i = 0; i < nb; i++)
    for (PetscInt c = 0; c < D; c++) f->A[nb * c + i] += u[c] * pb[i];
}

/* A_a = sum_b w_ab (x_b - x_a) (x) p_ab (D x NB): F_a = A G01^T, the second derivatives A G2^T. */
SPH_INLINE void Fit(Physics *ph, PetscInt a, PetscReal *A, const PetscInt D)
{
  Particles P = ph->P;
  FitSum    f = {.s = ph->solid, .P = P, .X = PField(P, FIELD_X0), .x = PField(P, FIELD_X), .m = PField(P, FIELD_M), .h = PField(P, FIELD_H), .ir0 = 1.0 / ph->sl.rho0};
  SPHPairs(ph->solid->nl, a, FitPair, &f, D);
  for (PetscInt i = 0; i < D * NB(D); i++) A[i] = f.A[i];
}

/* Energy density of a particle from its fit A and operator G (solid_terms.h: the law's W(F)
 * and, with kappa > 0, the second-order quadrature of its cell, kappa = dx^2 / 24); F, and
 * with Q the derivative dW/dA = (dW/dF) G01 + (dW/dD) G2, D the second derivatives times h, into
 * W.  The law is a constant of each instance below.  PETSC_FALSE for an inverted particle. */
SPH_INLINE PetscBool ParticleEnergyD(const SolidMaterial *sm, const PetscReal *G, const PetscReal *A, PetscReal h, PetscReal kappa, PetscReal *F, PetscReal *Q, PetscReal *Wout, const SolidLaw law, const PetscInt D)
{
  const PetscInt nb = NB(D), ns = nb - D;
  PetscReal      Dd[18] = {0}, Sk[9], dF[9], dD[18], W, J;
  for (PetscInt i = 0; i < D; i++) {
    for (PetscInt j = 0; j < D; j++) {
      F[D * i + j] = 0;
      for (PetscInt q = 0; q < nb; q++) F[D * i + j] += A[nb * i + q] * G[nb * j + q];
    }
    for (PetscInt j = 0; j < ns && kappa > 0; j++)
      for (PetscInt q = 0; q < nb; q++) Dd[ns * i + j] += A[nb * i + q] * G[nb * (D + j) + q];
  }
  J = SolidLawPK2D(law, sm->K, sm->G, F, Sk, D);
  if (J <= 0) return PETSC_FALSE;
  W = SolidLawEnergyD(law, sm->K, sm->G, F, D);
  if (!Q) {
    *Wout = W + (kappa > 0 ? CellQuadratureD(sm->K, sm->G, kappa, h, F, Dd, NULL, NULL, D) : 0);
    return PETSC_TRUE;
  }
  for (PetscInt i = 0; i < D; i++) /* P = F S */
    for (PetscInt j = 0; j < D; j++) {
      PetscReal t = F[D * i] * Sk[j];
      for (PetscInt m = 1; m < D; m++) t += F[D * i + m] * Sk[D * m + j];
      dF[D * i + j] = t;
    }
  for (PetscInt q = 0; q < D * ns; q++) dD[q] = 0;
  if (kappa > 0) W += CellQuadratureD(sm->K, sm->G, kappa, h, F, Dd, dF, dD, D);
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt q = 0; q < nb; q++) {
      PetscReal t = dF[D * i] * G[q];
      for (PetscInt j = 1; j < D; j++) t += dF[D * i + j] * G[nb * j + q];
      for (PetscInt j = 0; j < ns; j++) t += dD[ns * i + j] * G[nb * (D + j) + q];
      Q[nb * i + q] = t;
    }
  *Wout = W;
  return PETSC_TRUE;
}

/* An out-of-line instance per dimension and law (the law a constant in each): the 2D neo-Hookean one
 * compiles as the 2D-only code did, so its rounding is unchanged (inlined into the loop, the
 * compiler contracts its sums differently). */
#define PARTICLE_ENERGY_INSTANCE(name, law, D) \
  static __attribute__((noinline)) PetscBool name(const SolidMaterial *sm, const PetscReal *G, const PetscReal *A, PetscReal h, PetscReal kappa, PetscReal *F, PetscReal *Q, PetscReal *W) { return ParticleEnergyD(sm, G, A, h, kappa, F, Q, W, law, D); }
PARTICLE_ENERGY_INSTANCE(ParticleEnergy2, SOLID_LAW_NEO_HOOKEAN, 2)
PARTICLE_ENERGY_INSTANCE(ParticleEnergy3, SOLID_LAW_NEO_HOOKEAN, 3)
PARTICLE_ENERGY_INSTANCE(ParticleEnergySVK2, SOLID_LAW_ST_VENANT_KIRCHHOFF, 2)
PARTICLE_ENERGY_INSTANCE(ParticleEnergySVK3, SOLID_LAW_ST_VENANT_KIRCHHOFF, 3)
SPH_INLINE PetscBool ParticleEnergy(const SolidMaterial *sm, const PetscReal *G, const PetscReal *A, PetscReal h, PetscReal kappa, PetscReal *F, PetscReal *Q, PetscReal *W, const SolidLaw law, const PetscInt D)
{
  if (law == SOLID_LAW_ST_VENANT_KIRCHHOFF) return D == 2 ? ParticleEnergySVK2(sm, G, A, h, kappa, F, Q, W) : ParticleEnergySVK3(sm, G, A, h, kappa, F, Q, W);
  return D == 2 ? ParticleEnergy2(sm, G, A, h, kappa, F, Q, W) : ParticleEnergy3(sm, G, A, h, kappa, F, Q, W);
}

/* F_a and Q_a of owned solids (refreshed on ghosts); density, pressure and deviatoric stress of
 * owned and ghost solids from their F. */
SPH_INLINE PetscErrorCode DeformationAndStressD(Physics *ph, const SolidLaw law, const PetscInt D)
{
  Solid                s = ph->solid;
  Particles            P = ph->P;
  const SolidMaterial *sm = &ph->sl;
  const PetscReal     *h = PField(P, FIELD_H);
  PetscReal           *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *S = PField(P, FIELD_S);
  const PetscInt       nb = NB(D), ns = D * (D + 1) / 2, *slot = s->slot;
  PetscReal *const     FQ[2]    = {s->Fd, s->Qd};
  const PetscInt       width[2] = {D * D, D * nb};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal A[27], dxa = h[a] / ph->kernel.h_factor, W, *Fa, *Qa;
    if (!KindIsSolid(P->kind[a])) continue;
    Fa = s->Fd + D * D * slot[a];
    Qa = s->Qd + D * nb * slot[a];
    if (s->clamp_face && P->kind[a] == KIND_CLAMP) { /* a boundary: no strain, no energy */
      for (PetscInt i = 0; i < D * D; i++) Fa[i] = i % (D + 1) == 0;
      PetscCall(PetscArrayzero(Qa, D * nb));
      continue;
    }
    Fit(ph, a, A, D);
    if (!ParticleEnergy(sm, s->G0 + nb * nb * slot[a], A, h[a], s->quadrature ? dxa * dxa / 24 : 0, Fa, Qa, &W, law, D)) /* inverted: the run guard stops on the NaN and names the particle */
      for (PetscInt q = 0; q < D * nb; q++) Qa[q] = NAN;
  }
  PetscCall(HaloRefreshSlots(ph->halo, s->sf_slot, s->nown, 2, width, FQ));
  for (PetscInt a = 0; a < P->n + P->ng; a++) {
    const PetscReal *Fa;
    PetscReal        Sk[9], J;
    if (!KindIsSolid(P->kind[a])) continue;
    Fa = s->Fd + D * D * slot[a];
    J = SolidLawPK2D(law, sm->K, sm->G, Fa, Sk, D);
    if (J <= 0) { rho[a] = NAN; continue; }
    rho[a] = sm->rho0 / J;
    SolidLawCauchyD(law, sm->K, sm->G, Fa, Sk, p + a, S + ns * a, D);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the momentum of solid a gathers over its pairs (MomentumD). */
typedef struct {
  Physics             *ph;
  Solid                s;
  Particles            P;
  const SolidMaterial *sm;
  const PetscReal     *X, *x, *v, *m, *h, *rho, *F, *Q, *Qa;
  const PetscInt      *slot;
  PetscReal            ir0;
  PetscReal            ac[3], fl[3], hg[3]; /* elastic and Eq. 24; the fluid's load; hourglass control */
} MomentumSum;

/* The elastic force of a reference pair and its hourglass control, Eq. 24 on a current pair, or a
 * fluid neighbour's load */
SPH_INLINE void MomentumPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  MomentumSum         *ms = (MomentumSum *)ctx;
  Solid                s = ms->s;
  const SolidMaterial *sm = ms->sm;
  const PetscReal     *X = ms->X, *x = ms->x, *m = ms->m, ir0 = ms->ir0;
  const PetscInt       nb = NB(D), b = pr.b, k = pr.k;
  PetscReal            d[3];
  if (KindIsFluid(ms->P->kind[b])) { if (pr.F != 0) FluidPairLoad(ms->ph, a, b, pr.F, ms->fl, D); return; }
  if (!KindIsSolid(ms->P->kind[b])) return;
  VSub(x + D * a, x + D * b, d, D);
  if (s->f0[k] != 0) {
    const PetscReal *Qa = ms->Qa, *Qb = ms->Q + D * nb * ms->slot[b];
    PetscReal        c = -m[b] * ir0 * s->f0[k] * ir0, Xab[3], Xba[3], pa[9], pb[9];
    VSub(X + D * b, X + D * a, Xab, D);
    for (PetscInt i = 0; i < D; i++) Xba[i] = -Xab[i];
    Basis(Xab, ms->h[a], pa, D); /* the bond from a */
    Basis(Xba, ms->h[b], pb, D); /* from b */
    for (PetscInt q = 0; q < nb; q++)
      for (PetscInt i = 0; i < D; i++) ms->ac[i] += c * (Qa[nb * i + q] * pa[q] - Qb[nb * i + q] * pb[q]);
    if (s->hourglass > 0 && !(s->clamp_face && ms->P->kind[b] == KIND_CLAMP)) {
      PetscReal xab[3];
      for (PetscInt i = 0; i < D; i++) xab[i] = -d[i];
      HourglassAcc(s->hourglass * sm->G * m[b] * ir0 * -s->f0[k] * ir0, ms->F + D * D * ms->slot[a], ms->F + D * D * ms->slot[b], Xab, xab, ms->hg, D);
    }
  }
  if (pr.F != 0 && sm->alpha > 0) {
    PetscReal dv[3], pi;
    VSub(ms->v + D * a, ms->v + D * b, dv, D);
    pi = ArtificialViscosity(sm->alpha, sm->c0, PairH(ms->h[a], ms->h[b]), 0.5 * (ms->rho[a] + ms->rho[b]), VDot(dv, d, D), VDot(d, d, D));
    for (PetscInt i = 0; i < D; i++) ms->ac[i] -= m[b] * pi * pr.F * d[i];
  }
}

/* Owned solids: the elastic forces over the reference pairs, hourglass control and Eq. 24 on
 * the current pairs, the fluid's loads; clamps held (solid_impl.h). */
SPH_INLINE PetscErrorCode MomentumD(Physics *ph, const PetscInt D)
{
  Solid                s = ph->solid;
  Particles            P = ph->P;
  const SolidMaterial *sm = &ph->sl;
  const PetscReal     *X = PField(P, FIELD_X0), *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *rho = PField(P, FIELD_RHO);
  const PetscReal     *F = s->Fd, *Q = s->Qd;
  const PetscInt      *slot = s->slot;
  PetscReal           *acc = PField(P, FIELD_ACC), support[3] = {0, 0, 0}, load[3] = {0, 0, 0};
  const PetscReal      ir0 = 1.0 / sm->rho0;
  const PetscInt       nb = NB(D);

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsSolid(P->kind[a])) continue;
    MomentumSum ms = {.ph = ph, .s = s, .P = P, .sm = sm, .X = X, .x = x, .v = v, .m = m, .h = h, .rho = rho, .F = F, .Q = Q, .Qa = Q + D * nb * slot[a], .slot = slot, .ir0 = ir0};
    SPHPairs(s->nl, a, MomentumPair, &ms, D);
    for (PetscInt i = 0; i < D; i++) ms.ac[i] += ms.hg[i];
    SolidAccelerate(ph, a, ms.ac, ms.fl, acc, support, load, D);
  }
  for (PetscInt i = 0; i < D; i++) { s->support[i] = support[i]; s->load[i] = load[i]; }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rates and the strain energy are instantiated per law, the law a constant in each and chosen
 * once per call: the neo-Hookean instance is the code every existing case ran before the laws
 * were selectable, bit for bit.  (With the law chosen per particle inside them, the compiler fused
 * other products of the fluid's loads into FMAs: the 2D and 3D elastic gates' solid velocities
 * changed in the last bit.) */
#define TOTAL_RATES_INSTANCE(name, law) \
  static __attribute__((noinline)) PetscErrorCode name(Physics *ph) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(SPH_DIM_DISPATCH(ph->dim, DeformationAndStressD, ph, law)); \
    PetscCall(SPH_DIM_DISPATCH(ph->dim, MomentumD, ph)); \
    PetscFunctionReturn(PETSC_SUCCESS); \
  }
TOTAL_RATES_INSTANCE(RatesNeoHookean, SOLID_LAW_NEO_HOOKEAN)
TOTAL_RATES_INSTANCE(RatesStVenantKirchhoff, SOLID_LAW_ST_VENANT_KIRCHHOFF)

PetscErrorCode SolidTotalRates(Physics *ph) { return ph->sl.law == SOLID_LAW_ST_VENANT_KIRCHHOFF ? RatesStVenantKirchhoff(ph) : RatesNeoHookean(ph); }

/* The hourglass energy of particle a's reference bonds (TotalStrainEnergyD) */
typedef struct {
  Solid            s;
  const PetscReal *X, *x, *m, *Fa;
  PetscReal        G, ir0;
  PetscReal        e;
} HourglassSum;

SPH_INLINE void HourglassPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  HourglassSum *hs = (HourglassSum *)ctx;
  PetscInt      b = p.b;
  PetscReal     Xab[3], xab[3];
  VSub(hs->X + D * b, hs->X + D * a, Xab, D);
  VSub(hs->x + D * b, hs->x + D * a, xab, D);
  if (hs->s->f0[p.k] != 0) hs->e += HourglassEnergy(0.5 * hs->s->hourglass * hs->G * hs->m[b] * hs->ir0 * -hs->s->f0[p.k], hs->Fa, Xab, xab, D);
}

SPH_INLINE PetscReal TotalStrainEnergyD(Physics *ph, const SolidLaw law, const PetscInt D)
{
  Solid            s = ph->solid;
  Particles        P = ph->P;
  const PetscReal *m = PField(P, FIELD_M), *X = PField(P, FIELD_X0), *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
  const PetscReal  ir0 = 1.0 / ph->sl.rho0;
  const PetscInt   nb = NB(D);
  PetscReal        e = 0;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal A[27], Fa[9], dxa = h[a] / ph->kernel.h_factor, ea;
    if (!KindIsSolid(P->kind[a]) || (s->clamp_face && P->kind[a] == KIND_CLAMP)) continue;
    Fit(ph, a, A, D);
    if (!ParticleEnergy(&ph->sl, s->G0 + nb * nb * s->slot[a], A, h[a], s->quadrature ? dxa * dxa / 24 : 0, Fa, NULL, &ea, law, D)) ea = NAN;
    if (s->hourglass > 0) {
      HourglassSum hs = {.s = s, .X = X, .x = x, .m = m, .Fa = Fa, .G = ph->sl.G, .ir0 = ir0, .e = ea};
      SPHPairs(s->nl, a, HourglassPair, &hs, D);
      ea = hs.e;
    }
    e += m[a] * ir0 * ea;
  }
  return e;
}

static __attribute__((noinline)) PetscReal EnergyNeoHookean(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, TotalStrainEnergyD, ph, SOLID_LAW_NEO_HOOKEAN); }
static __attribute__((noinline)) PetscReal EnergyStVenantKirchhoff(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, TotalStrainEnergyD, ph, SOLID_LAW_ST_VENANT_KIRCHHOFF); }
PetscReal SolidTotalStrainEnergy(Physics *ph) { return ph->sl.law == SOLID_LAW_ST_VENANT_KIRCHHOFF ? EnergyStVenantKirchhoff(ph) : EnergyNeoHookean(ph); }
