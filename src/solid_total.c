/* Total-Lagrangian SPH solid (-solid_formulation total).  Gradients are taken in the reference
 * configuration X0 (the particles as built), by a weighted least-squares fit over the kernel
 * support, with weights w_ab = V0_b |grad0 W_ab| / |X_ab| and basis p_ab = (X, Y, X^2 / 2h, XY / h,
 * Y^2 / 2h) of the bond X_ab = X_b - X_a (-solid_order 2) or (X, Y) (order 1, which is the
 * kernel-gradient correction of Bonet & Lok):
 *   F_a = sum_b w_ab (x_b - x_a) (x) G_a p_ab,   G_a = the first two rows of [sum_b w_ab p p^T]^-1,
 * exact for every displacement of that order, also at a free surface or a clamp where the kernel
 * is cut.  Order 1 is exact only for affine fields: at the surface of a bent plate it takes the
 * strain of a point inside it, and at 5 particles across that makes the plate 42 % too compliant.
 * G_a is fixed by the reference configuration and computed after each rebuild.
 * The stress is hyper-elastic (neo-Hookean, solid_terms.h); the forces are minus the gradient of
 * the discrete strain energy sum_a V0_a W(F_a) (so energy and momentum are conserved):
 *   dv_a/dt = 1 / rho0 sum_b V0_b |grad0 W_ab| / |X_ab| (Q_a p_ab - Q_b p_ba),   Q = P G,
 * P = F S the first Piola-Kirchhoff stress; with order 1 this is the usual
 * 1 / rho0 sum_b V0_b (P_a B_a + P_b B_b) grad0 W_ab.  Rotations are exact: no Jaumann rate and no
 * tensile instability to hold off with an artificial stress.  An optional hourglass energy
 * (solid_terms.h) penalises bonds no affine map explains; the seed's artificial viscosity
 * (Eq. 24) acts on the current pairs as in the updated scheme.  Density, pressure and deviatoric
 * stress are derived from F for the output and the fluid. */
#include <sphfsi/solid_impl.h>
#include <sphfsi/solid_terms.h>
#include <sphfsi/kernel.h>
#include <sphfsi/halo.h>

/* Basis of the bond X (X, Y) from a particle of smoothing length h: p[0..4]. */
static inline void Basis(PetscReal X, PetscReal Y, PetscReal h, PetscReal p[5])
{
  PetscReal ih = 1.0 / h;
  p[0] = X; p[1] = Y; p[2] = 0.5 * X * X * ih; p[3] = X * Y * ih; p[4] = 0.5 * Y * Y * ih;
}

/* M^-1 for the symmetric n x n M (n = 2 or 5), into the 5 x 5 row-major G (zero beyond n), by
 * Gauss-Jordan elimination with partial pivoting; PETSC_FALSE when M is singular against its scale. */
static PetscBool Inverse(PetscInt n, const PetscReal M[25], PetscReal G[25])
{
  PetscReal A[5][10], big = 0;
  for (PetscInt i = 0; i < n; i++) {
    for (PetscInt j = 0; j < n; j++) { A[i][j] = M[5 * i + j]; A[i][n + j] = i == j; }
    big = PetscMax(big, PetscAbsReal(M[6 * i]));
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
  for (PetscInt i = 0; i < 5; i++)
    for (PetscInt j = 0; j < 5; j++) G[5 * i + j] = i < n && j < n ? A[i][n + j] / A[i][i] : 0;
  return PETSC_TRUE;
}

/* -solid_clamp face: a clamp is a boundary, not material.  Each clamp particle next to the body
 * (its nearest solid particle within 1.5 dx in the reference configuration) stands in the fits
 * for the point midway to that particle, on the face where the displacement is zero; deeper clamp
 * particles take no part, and clamps store no energy.  Fitted across the face as material, the
 * displacement (zero in the clamp, quadratic in the plate) has a jump in its second derivative
 * there, which made the root too compliant at first order.  Done once per particle: a moved X0
 * (x != X0; a clamp never moves) marks it, and a checkpoint keeps it. */
static PetscBool ClampFace(Particles P, PetscInt b) { return (PetscBool)(P->kind[b] == KIND_CLAMP && (PField(P, FIELD_X)[2 * b] != PField(P, FIELD_X0)[2 * b] || PField(P, FIELD_X)[2 * b + 1] != PField(P, FIELD_X0)[2 * b + 1])); }

static PetscErrorCode ClampFaces(Sim sim)
{
  Cells            C = sim->solid->nl;
  Particles        P = sim->P;
  PetscReal       *X = PField(P, FIELD_X0);
  const PetscReal *h = PField(P, FIELD_H);
  const FieldId    x0[] = {FIELD_X0};
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal lim = 1.5 * h[a] / sim->kernel.h_factor, best = lim * lim, mid[2];
    PetscInt  nearest = -1;
    if (P->kind[a] != KIND_CLAMP || ClampFace(P, a)) continue;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal dx, dy;
      if (P->kind[b] != KIND_SOLID) continue;
      dx = X[2 * b] - X[2 * a]; dy = X[2 * b + 1] - X[2 * a + 1];
      if (dx * dx + dy * dy < best * (1 - 1e-9)) { best = dx * dx + dy * dy; nearest = b; }
    }
    if (nearest < 0) continue;
    mid[0] = 0.5 * (X[2 * a] + X[2 * nearest]); mid[1] = 0.5 * (X[2 * a + 1] + X[2 * nearest + 1]);
    X[2 * a] = mid[0]; X[2 * a + 1] = mid[1];
  }
  PetscCall(HaloRefresh(sim->halo, P, 1, x0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A clamp face point c pairs with solid a while the clamp particle itself is within the support
 * of a: the neighbour search, which runs at the particles' positions, then always holds the pair. */
static PetscBool FaceInSupport(Sim sim, PetscInt a, PetscInt c)
{
  const PetscReal *x = PField(sim->P, FIELD_X), *X = PField(sim->P, FIELD_X0), *h = PField(sim->P, FIELD_H);
  PetscReal        dx = x[2 * c] - X[2 * a], dy = x[2 * c + 1] - X[2 * a + 1], r = 2 * PairH(h[a], h[c]);
  return (PetscBool)(dx * dx + dy * dy < r * r);
}

/* Whether b enters the fit of a: solids both; with clamp faces, a clamp only as a face point and
 * never as the centre of a fit. */
static PetscBool InFit(Solid s, Particles P, PetscInt a, PetscInt b)
{
  if (!KindIsSolid(P->kind[a]) || !KindIsSolid(P->kind[b])) return PETSC_FALSE;
  if (!s->clamp_face) return PETSC_TRUE;
  return (PetscBool)(P->kind[a] == KIND_SOLID && (P->kind[b] == KIND_SOLID || ClampFace(P, b)));
}

PetscErrorCode SolidTotalPrepare(Sim sim)
{
  Solid            s = sim->solid;
  Cells            C = s->nl;
  Particles        P = sim->P;
  const PetscReal *X = PField(P, FIELD_X0), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), rho0 = sim->sl.rho0;
  PetscReal       *G = PField(P, FIELD_GRAD0);
  PetscInt         npair = 0, npairs = C->nstart[C->npart], nb = s->order == 2 ? 5 : 2;

  PetscFunctionBeginUser;
  if (s->clamp_face && !s->faces_placed) PetscCall(ClampFaces(sim)); /* the reference never changes: once per run (a restart finds them in X0) */
  s->faces_placed = PETSC_TRUE;
  if (npairs > s->cap_ref) {
    PetscCall(PetscFree(s->f0));
    s->cap_ref = C->cap_nbr;
    PetscCall(PetscMalloc1(s->cap_ref, &s->f0));
  }
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal M[25] = {0}, M2[25] = {0};
    if (!KindIsSolid(P->kind[a])) continue;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) s->f0[k] = 0;
    if (s->clamp_face && P->kind[a] == KIND_CLAMP) { /* no fit, no energy; a face point keeps its pairs with the solids that fit it, for the support's reaction */
      PetscCall(PetscArrayzero(G + 25 * a, 25));
      if (!ClampFace(P, a)) continue;
      for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
        PetscInt  b = C->nbr[k];
        PetscReal dx = X[2 * b] - X[2 * a], dy = X[2 * b + 1] - X[2 * a + 1];
        if (P->kind[b] != KIND_SOLID || !FaceInSupport(sim, b, a)) continue;
        s->f0[k] = KernelF(&sim->kernel, PetscSqrtReal(dx * dx + dy * dy), PairH(h[a], h[b]));
        if (s->f0[k] != 0) npair++;
      }
      continue;
    }
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal dx, dy, w, p[5];
      if (!InFit(s, P, a, b) || (P->kind[b] == KIND_CLAMP && !FaceInSupport(sim, a, b))) continue;
      dx = X[2 * b] - X[2 * a]; dy = X[2 * b + 1] - X[2 * a + 1];
      s->f0[k] = KernelF(&sim->kernel, PetscSqrtReal(dx * dx + dy * dy), PairH(h[a], h[b]));
      if (s->f0[k] == 0) continue;
      npair++;
      w = -m[b] / rho0 * s->f0[k];
      Basis(dx, dy, h[a], p);
      for (PetscInt i = 0; i < nb; i++)
        for (PetscInt j = 0; j < nb; j++) M[5 * i + j] += w * p[i] * p[j];
    }
    if (nb == 5 && Inverse(5, M, G + 25 * a)) continue;
    for (PetscInt i = 0; i < 2; i++) /* order 1, or a corner with too few neighbours for order 2 */
      for (PetscInt j = 0; j < 2; j++) M2[5 * i + j] = M[5 * i + j];
    PetscCheck(Inverse(2, M2, G + 25 * a), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Solid particle %" PetscInt_FMT " has too few neighbours in its reference configuration for a gradient: a solid must be at least 2 particles thick", P->id[a]);
  }
  /* the search runs in the current configuration: a body stretched by more than the skin over
   * 2 h loses pairs of its reference configuration, which the global count shows */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &npair, 1, MPIU_INT, MPI_SUM, sim->comm));
  if (!s->npair_ref) s->npair_ref = npair;
  /* a fault (guard.h): a body torn this far is a blow-up in all but the most extreme loadings */
  PetscCheck(npair == s->npair_ref, sim->comm, PETSC_ERR_NOT_CONVERGED, "The solid stretched so far that %" PetscInt_FMT " of its %" PetscInt_FMT " reference-configuration pairs left the neighbour search (2 h + %g dx): raise -solid_skin (at most 2) or use -solid_formulation updated", s->npair_ref - npair, s->npair_ref, (double)s->skin);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A_a = sum_b w_ab (x_b - x_a) (x) p_ab (2 x 5): F_a = A G01^T, the second derivatives A G234^T. */
static void Fit(Sim sim, PetscInt a, PetscReal A[10])
{
  Solid            s = sim->solid;
  Cells            C = s->nl;
  Particles        P = sim->P;
  const PetscReal *X = PField(P, FIELD_X0), *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), ir0 = 1.0 / sim->sl.rho0;
  for (PetscInt i = 0; i < 10; i++) A[i] = 0;
  for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
    PetscInt  b = C->nbr[k];
    PetscReal w, pb[5], ux, uy;
    if (s->f0[k] == 0) continue; /* not a reference neighbour (or not a solid) */
    w = -m[b] * ir0 * s->f0[k];
    const PetscReal *xb = P->kind[b] == KIND_CLAMP && s->clamp_face ? X + 2 * b : x + 2 * b; /* a clamp face point does not move */
    Basis(X[2 * b] - X[2 * a], X[2 * b + 1] - X[2 * a + 1], h[a], pb);
    ux = w * (xb[0] - x[2 * a]); uy = w * (xb[1] - x[2 * a + 1]);
    for (PetscInt i = 0; i < 5; i++) { A[i] += ux * pb[i]; A[5 + i] += uy * pb[i]; }
  }
}

/* Energy density of a particle from its fit A and operator G (solid_terms.h: the neo-Hookean
 * W(F) and, with kappa > 0, the second-order quadrature of its cell, kappa = dx^2 / 24);
 * F, and with Q the derivative dW/dA = (dW/dF) G01 + (dW/dD) G234, D the second derivatives
 * times h, into W.  PETSC_FALSE for an inverted particle (det F <= 0). */
static PetscBool ParticleEnergy(const SolidMaterial *sm, const PetscReal G[25], const PetscReal A[10], PetscReal h, PetscReal kappa, PetscReal F[4], PetscReal *Q, PetscReal *Wout)
{
  PetscReal D[6] = {0}, Sk[4], dF[4], dD[6], W, J;
  for (PetscInt i = 0; i < 2; i++) {
    for (PetscInt j = 0; j < 2; j++) {
      F[2 * i + j] = 0;
      for (PetscInt q = 0; q < 5; q++) F[2 * i + j] += A[5 * i + q] * G[5 * j + q];
    }
    for (PetscInt j = 0; j < 3 && kappa > 0; j++)
      for (PetscInt q = 0; q < 5; q++) D[3 * i + j] += A[5 * i + q] * G[5 * (2 + j) + q];
  }
  J = NeoHookeanPK2(sm->K, sm->G, F, Sk);
  if (J <= 0) return PETSC_FALSE;
  W = NeoHookeanEnergy(sm->K, sm->G, F);
  if (!Q) {
    *Wout = W + (kappa > 0 ? CellQuadrature(sm->K, sm->G, kappa, h, F, D, NULL, NULL) : 0);
    return PETSC_TRUE;
  }
  dF[0] = F[0] * Sk[0] + F[1] * Sk[2]; dF[1] = F[0] * Sk[1] + F[1] * Sk[3]; /* P = F S */
  dF[2] = F[2] * Sk[0] + F[3] * Sk[2]; dF[3] = F[2] * Sk[1] + F[3] * Sk[3];
  for (PetscInt q = 0; q < 6; q++) dD[q] = 0;
  if (kappa > 0) W += CellQuadrature(sm->K, sm->G, kappa, h, F, D, dF, dD);
  for (PetscInt i = 0; i < 2; i++)
    for (PetscInt q = 0; q < 5; q++) {
      PetscReal t = dF[2 * i] * G[q] + dF[2 * i + 1] * G[5 + q];
      for (PetscInt j = 0; j < 3; j++) t += dD[3 * i + j] * G[5 * (2 + j) + q];
      Q[5 * i + q] = t;
    }
  *Wout = W;
  return PETSC_TRUE;
}

/* F_a and Q_a of owned solids (refreshed on ghosts); density, pressure and deviatoric stress of
 * owned and ghost solids from their F. */
static PetscErrorCode DeformationAndStress(Sim sim)
{
  Solid                s = sim->solid;
  Particles            P = sim->P;
  const SolidMaterial *sm = &sim->sl;
  const PetscReal     *h = PField(P, FIELD_H), *G = PField(P, FIELD_GRAD0);
  PetscReal           *F = PField(P, FIELD_DEFGRAD), *Q = PField(P, FIELD_PK1B), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *S = PField(P, FIELD_S);
  const FieldId        refresh[] = {FIELD_DEFGRAD, FIELD_PK1B};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal A[10], dxa = h[a] / sim->kernel.h_factor, W;
    if (!KindIsSolid(P->kind[a])) continue;
    if (s->clamp_face && P->kind[a] == KIND_CLAMP) { /* a boundary: no strain, no energy */
      F[4 * a] = F[4 * a + 3] = 1; F[4 * a + 1] = F[4 * a + 2] = 0;
      PetscCall(PetscArrayzero(Q + 10 * a, 10));
      continue;
    }
    Fit(sim, a, A);
    if (!ParticleEnergy(sm, G + 25 * a, A, h[a], s->quadrature ? dxa * dxa / 24 : 0, F + 4 * a, Q + 10 * a, &W)) /* inverted: the run guard stops on the NaN and names the particle */
      for (PetscInt q = 0; q < 10; q++) Q[10 * a + q] = NAN;
  }
  PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
  PetscCall(HaloRefresh(sim->halo, P, 2, refresh));
  PetscCall(PetscLogStagePop());
  for (PetscInt a = 0; a < P->n + P->ng; a++) {
    const PetscReal *Fa = F + 4 * a;
    PetscReal        Sk[4], J;
    if (!KindIsSolid(P->kind[a])) continue;
    J = NeoHookeanPK2(sm->K, sm->G, Fa, Sk);
    if (J <= 0) { rho[a] = NAN; continue; }
    rho[a] = sm->rho0 / J;
    NeoHookeanCauchy(sm->K, sm->G, Fa, Sk, p + a, S + 3 * a);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Owned solids: the elastic forces over the reference pairs, hourglass control and Eq. 24 on
 * the current pairs, the fluid's loads; clamps held (solid_impl.h). */
static PetscErrorCode Momentum(Sim sim)
{
  Solid                s = sim->solid;
  Cells                C = s->nl;
  Particles            P = sim->P;
  const SolidMaterial *sm = &sim->sl;
  const PetscReal     *X = PField(P, FIELD_X0), *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *rho = PField(P, FIELD_RHO);
  const PetscReal     *F = PField(P, FIELD_DEFGRAD), *Q = PField(P, FIELD_PK1B);
  PetscReal           *acc = PField(P, FIELD_ACC), support[2] = {0, 0}, load[2] = {0, 0};
  const PetscReal      ir0 = 1.0 / sm->rho0;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal        ax = 0, ay = 0, fl[2] = {0, 0}, hg[2] = {0, 0};
    const PetscReal *Qa = Q + 10 * a;
    if (!KindIsSolid(P->kind[a])) continue;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal dx = x[2 * a] - x[2 * b], dy = x[2 * a + 1] - x[2 * b + 1];
      if (KindIsFluid(P->kind[b])) { if (C->f[k] != 0) FluidLoad(sim, a, b, C->f[k], fl); continue; }
      if (!KindIsSolid(P->kind[b])) continue;
      if (s->f0[k] != 0) {
        const PetscReal *Qb = Q + 10 * b;
        PetscReal        c = -m[b] * ir0 * s->f0[k] * ir0, Xab[2] = {X[2 * b] - X[2 * a], X[2 * b + 1] - X[2 * a + 1]}, pa[5], pb[5];
        Basis(Xab[0], Xab[1], h[a], pa);   /* the bond from a */
        Basis(-Xab[0], -Xab[1], h[b], pb); /* from b */
        for (PetscInt q = 0; q < 5; q++) {
          ax += c * (Qa[q] * pa[q] - Qb[q] * pb[q]);
          ay += c * (Qa[5 + q] * pa[q] - Qb[5 + q] * pb[q]);
        }
        if (s->hourglass > 0 && !(s->clamp_face && P->kind[b] == KIND_CLAMP)) {
          const PetscReal xab[2] = {-dx, -dy};
          HourglassAcc(s->hourglass * sm->G * m[b] * ir0 * -s->f0[k] * ir0, F + 4 * a, F + 4 * b, Xab, xab, hg);
        }
      }
      if (C->f[k] != 0 && sm->alpha > 0) {
        PetscReal pi = ArtificialViscosity(sm->alpha, sm->c0, PairH(h[a], h[b]), 0.5 * (rho[a] + rho[b]), (v[2 * a] - v[2 * b]) * dx + (v[2 * a + 1] - v[2 * b + 1]) * dy, dx * dx + dy * dy);
        ax -= m[b] * pi * C->f[k] * dx;
        ay -= m[b] * pi * C->f[k] * dy;
      }
    }
    SolidAccelerate(sim, a, ax + hg[0], ay + hg[1], fl, acc, support, load);
  }
  s->support[0] = support[0]; s->support[1] = support[1];
  s->load[0]    = load[0];    s->load[1]    = load[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTotalRates(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(DeformationAndStress(sim));
  PetscCall(Momentum(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal SolidTotalStrainEnergy(Sim sim)
{
  Solid            s = sim->solid;
  Cells            C = s->nl;
  Particles        P = sim->P;
  const PetscReal *F = PField(P, FIELD_DEFGRAD), *m = PField(P, FIELD_M), *X = PField(P, FIELD_X0), *x = PField(P, FIELD_X), *h = PField(P, FIELD_H), *G = PField(P, FIELD_GRAD0);
  const PetscReal  ir0 = 1.0 / sim->sl.rho0;
  PetscReal        e = 0;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal A[10], Fa[4], dxa = h[a] / sim->kernel.h_factor, ea;
    if (!KindIsSolid(P->kind[a]) || (s->clamp_face && P->kind[a] == KIND_CLAMP)) continue;
    Fit(sim, a, A);
    if (!ParticleEnergy(&sim->sl, G + 25 * a, A, h[a], s->quadrature ? dxa * dxa / 24 : 0, Fa, NULL, &ea)) ea = NAN;
    if (s->hourglass > 0)
      for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
        PetscInt        b = C->nbr[k];
        const PetscReal Xab[2] = {X[2 * b] - X[2 * a], X[2 * b + 1] - X[2 * a + 1]}, xab[2] = {x[2 * b] - x[2 * a], x[2 * b + 1] - x[2 * a + 1]};
        if (s->f0[k] != 0) ea += HourglassEnergy(0.5 * s->hourglass * sim->sl.G * m[b] * ir0 * -s->f0[k], F + 4 * a, Xab, xab);
      }
    e += m[a] * ir0 * ea;
  }
  return e;
}
