/* Kernels (Eq. 12, Wendland C2 and C4): normalisation in 2D and 3D, interior lattice sums (2D and
 * 3D), compact support, gradient antisymmetry; kernel.h's two groupings of the same kernel
 * (KernelShape, KernelShapeList) within a few ulp of each other; the neighbour lists of a random
 * cloud in 2D and 3D (one smoothing length, and two) equal a brute-force search, their kernel values
 * are kernel.h's bit for bit (no copy of the kernel elsewhere) and KernelW/KernelF's to round-off;
 * the corrected SPH gradient of a linear field is exact to round-off on an irregular particle cloud. */
#include "base/kernel.h"
#include "particles/cells.h"
#include "fluid/operators.h"

/* The interior lattice sums (Eq. 17's normalisation, div r = d) cover the whole support: within
 * the lattice quadrature error of a kernel at h >= 1.3 dx (Wendland C2 there: 1 %, 2.6 % in 2D),
 * where a missing ring (3D: shell) of neighbours would take 10 % or more. */
static PetscErrorCode CheckLattice(const SPHKernel *K)
{
  PetscReal lw = KernelLatticeSum(K, LATTICE_W, 0), ld = KernelLatticeSum(K, LATTICE_DIVR, 0);
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kernel %s %dD at h = %g dx: lattice sum of W %.5f, div r %.5f\n", KernelTypes[K->type], (int)K->dim, (double)K->h_factor, (double)lw, (double)ld));
  PetscCheck(PetscAbsReal(lw - 1) < 0.03 && PetscAbsReal(ld - K->dim) < 0.03 * K->dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Lattice sums %g, %g far from 1, %d", (double)lw, (double)ld, (int)K->dim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* KernelShiftCeiling against a direct measurement: the lattice's particles displaced by a mode,
 * eps cos(k . x_b) along each axis in turn, grad C of the particle at the origin from the kernel
 * itself (no Hessian) over eps gives the mode's matrix; the largest eigenvalue over the same k
 * (a cheaper grid of pi/8 in 3D) is 1 / the ceiling to the finite difference's error (and, in 3D,
 * the coarser grid's: the ceiling may then be lower, by less than 1 %). */
static PetscErrorCode CheckShiftCeiling(const SPHKernel *K)
{
  const PetscReal h = K->h_factor, eps = 1e-6, dmax = KernelShiftCeiling(K);
  const PetscInt  n = (PetscInt)PetscCeilReal(2.0 * h), D = K->dim, nz = D == 3 ? n : 0, s = D == 3 ? 9 : 17, nk = D == 3 ? s * s * s : s * s;
  const PetscReal dk = PETSC_PI / (s - 1);
  PetscReal       lmax = 0, ratio;
  PetscFunctionBeginUser;
  for (PetscInt m = 1; m < nk; m++) {
    PetscReal kv[3] = {dk * (m % s), dk * ((m / s) % s), dk * (m / (s * s))}, M[3][3] = {{0}}, S[6], lo, hi;
    for (PetscInt e = 0; e < D; e++) /* a displaced along axis e by eps, b by eps cos(k . x_b) */
      for (PetscInt c = -nz; c <= nz; c++)
        for (PetscInt j = -n; j <= n; j++)
          for (PetscInt i = -n; i <= n; i++) {
            PetscReal xb[3] = {(PetscReal)i, (PetscReal)j, (PetscReal)c}, d[3], r, F;
            if (!i && !j && !c) continue;
            for (PetscInt q = 0; q < 3; q++) d[q] = -xb[q];
            d[e] += eps * (1 - PetscCosReal(VDot(kv, xb, D)));
            r = PetscSqrtReal(VDot(d, d, D));
            F = KernelF(K, r, h);
            for (PetscInt q = 0; q < D; q++) M[q][e] += F * d[q] / eps; /* V_b = 1 */
          }
    for (PetscInt q = 0, k = 0; q < D; q++) /* the symmetric part, dim.h's order */
      for (PetscInt e = q; e < D; e++) S[k++] = 0.5 * (M[q][e] + M[e][q]);
    SymEigenRange(S, &lo, &hi, D);
    lmax = PetscMax(lmax, hi);
  }
  ratio = dmax * lmax * h * h;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kernel %s %dD at h = %g dx: shifting's ceiling %.4f h^2, measured modes' %.4f h^2\n", KernelTypes[K->type], (int)D, (double)h, (double)dmax, (double)(1 / (lmax * h * h))));
  PetscCheck(ratio < 1 + 1e-4 && ratio > (D == 3 ? 0.99 : 1 - 1e-4), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Shifting's ceiling %g h^2 against the measured modes' %g h^2", (double)dmax, (double)(1 / (lmax * h * h)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* KernelShape (the terms') and KernelShapeList (the neighbour list's, without branches) group the
 * products differently (kernel.h): at the same R they may differ in the last bits, by at most 8 eps
 * relative (measured: 2.1 for the cubic spline, 2.5-3.4 for the Wendland kernels). */
static PetscErrorCode CheckForms(const SPHKernel *K)
{
  const PetscInt n = 200000;
  PetscReal      h = 0.013, sw = KernelSigma(K, h), sf = sw / (h * h), worst = 0;
  PetscInt       differ = 0;
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k <= n; k++) {
    PetscReal R = 2.0 * k / n, v[2], u[2];
    KernelShape(K->type, R, sw, sf, &v[0], &v[1]);
    KernelShapeList(K->type, R, sw, sf, &u[0], &u[1]);
    for (PetscInt i = 0; i < 2; i++) {
      PetscReal e = v[i] == u[i] ? 0 : PetscAbsReal(v[i] - u[i]) / (PETSC_MACHINE_EPSILON * PetscAbsReal(v[i]));
      differ += e > 0;
      worst = PetscMax(worst, e);
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kernel %s %dD: KernelShape and KernelShapeList differ in %.1f %% of W and F at R in [0, 2], by at most %.1f eps (relative)\n", KernelTypes[K->type], (int)K->dim, 100.0 * differ / (2.0 * (n + 1)), (double)worst));
  PetscCheck(worst <= 8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "KernelShape and KernelShapeList differ by %g eps", (double)worst);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* W and F of the list's pair (a, b) as cells.c evaluates them with kernel.h: r^2 as the list's
 * (PairDistance2), R = r (1 / h), the pairs of another h and all pairs of a particle that has one by
 * KernelShapePair, the others by KernelShapeList (the loop cells.c vectorises). */
static void ListPairKernel(const SPHKernel *K, const PetscReal *x, const PetscReal *h, PetscInt D, PetscInt a, PetscInt b, PetscBool mixed, PetscReal *w, PetscReal *f)
{
  PetscReal dx = x[D * a] - x[D * b], dy = x[D * a + 1] - x[D * b + 1], r2 = fma(dy, dy, dx * dx), hab = PairH(h[a], h[b]), sw, R;
  if (D == 3) {
    PetscReal dz = x[D * a + 2] - x[D * b + 2];
    r2 = fma(dz, dz, r2);
  }
  sw = KernelSigma(K, hab);
  R  = PetscSqrtReal(r2) * (1.0 / hab);
  if (mixed) KernelShapePair(K->type, R, sw, sw / (hab * hab), w, f);
  else KernelShapeList(K->type, R, sw, sw / (hab * hab), w, f);
}

static PetscErrorCode CheckKernel(const SPHKernel *K)
{
  PetscReal h = 0.013, sum = 0, d = h / 200, rad2 = 0, rad3 = 0, dr = h / 20000;
  SPHKernel K3;
  PetscFunctionBeginUser;
  /* integral of W over the plane by the midpoint rule on a fine grid, and radially in 2D and 3D */
  for (PetscReal x = -2 * h + d / 2; x < 2 * h; x += d)
    for (PetscReal y = -2 * h + d / 2; y < 2 * h; y += d) sum += KernelW(K, PetscSqrtReal(x * x + y * y), h) * d * d;
  KernelInit(&K3, K->type, 3, K->h_factor);
  for (PetscReal r = dr / 2; r < 2 * h; r += dr) {
    rad2 += 2 * PETSC_PI * r * KernelW(K, r, h) * dr;
    rad3 += 4 * PETSC_PI * r * r * KernelW(&K3, r, h) * dr;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kernel %s: integral of W = %.8f (plane), %.10f (2D radial), %.10f (3D radial)\n", KernelTypes[K->type], (double)sum, (double)rad2, (double)rad3));
  PetscCheck(PetscAbsReal(sum - 1) < 1e-4 && PetscAbsReal(rad2 - 1) < 1e-8 && PetscAbsReal(rad3 - 1) < 1e-8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "W not normalised: %g, %g, %g", (double)sum, (double)rad2, (double)rad3);
  PetscCheck(KernelW(K, 2 * h, h) == 0 && KernelW(K, 2.5 * h, h) == 0 && KernelDW(K, 2 * h, h) == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "W not compact");
  PetscCheck(PetscAbsReal(KernelW(K, h * (1 - 1e-12), h) - KernelW(K, h * (1 + 1e-12), h)) < 1e-9 * KernelW(K, h, h), PETSC_COMM_SELF, PETSC_ERR_PLIB, "W discontinuous at R = 1");
  /* F = (dW/dr)/r consistent with dW/dr, and dW/dr with a finite difference of W */
  for (PetscReal R = 0.05; R < 2; R += 0.05) {
    PetscReal r = R * h, e = 1e-7 * h, fd = (KernelW(K, r + e, h) - KernelW(K, r - e, h)) / (2 * e);
    PetscCheck(PetscAbsReal(fd - KernelDW(K, r, h)) < 1e-5 * PetscAbsReal(KernelDW(K, h, h)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "dW/dr wrong at R = %g", (double)R);
    PetscCheck(PetscAbsReal(KernelF(K, r, h) * r - KernelDW(K, r, h)) < 1e-12 * PetscAbsReal(KernelDW(K, h, h)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "F wrong at R = %g", (double)R);
  }
  /* grad_a W_ab = -grad_b W_ba exactly, with mixed sizes h_ab = sqrt(h_a h_b) */
  {
    PetscReal ha = 0.01, hb = 0.013, xa[2] = {0.1, 0.2}, xb[2] = {0.111, 0.193};
    PetscReal r = PetscSqrtReal((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]));
    PetscReal ga = KernelF(K, r, PairH(ha, hb)) * (xa[0] - xb[0]), gb = KernelF(K, r, PairH(hb, ha)) * (xb[0] - xa[0]);
    PetscCheck(ga == -gb, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Gradient not antisymmetric");
  }
  PetscCall(CheckLattice(K));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |x_a - x_b|^2 in D dimensions */
static PetscReal Dist2(const PetscReal *x, PetscInt D, PetscInt a, PetscInt b)
{
  PetscReal s = 0;
  for (PetscInt d = 0; d < D; d++) s += (x[D * a + d] - x[D * b + d]) * (x[D * a + d] - x[D * b + d]);
  return s;
}

/* Neighbour lists of a random cloud in 2D or 3D (no lattice: the order in which candidates are
 * pairs is random, as in a splashing flow) against all pairs with r < 2 h_ab by brute force, with
 * one smoothing length and with two; two particles share a position (a pair at r = 0).  With a
 * skin (in dx): the list built with it, then every particle moved by just under half the skin in a
 * random direction and the list refreshed from its candidates (CellsRefreshPairs).  A second list
 * that keeps no W (drop_w) must hold the same pairs and F, and CellsPairW the same W bit for bit,
 * also after the particles have moved on without a new list. */
static PetscErrorCode CheckNeighbours(const SPHKernel *K, PetscBool mixed, PetscReal skin)
{
  Particles   P;
  Grid        g;
  Cells       C, Cd;
  const PetscInt D = K->dim;
  PetscReal   dx = 0.01, h0 = K->h_factor * dx, lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.15, 0.12};
  PetscBool   per[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
  PetscRandom rnd;
  PetscInt    n = D == 3 ? 1500 : 300, pairs = 0, *mark, notbits = 0;
  PetscReal   errw = 0, errf = 0;

  PetscFunctionBeginUser;
  PetscCall(ParticlesCreate(PETSC_COMM_SELF, &P));
  PetscCall(ParticlesSetDimension(P, D));
  PetscCall(ParticlesSetUp(P));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal r[3], h = mixed && a % 3 == 0 ? 0.7 * h0 : h0;
    for (PetscInt d = 0; d < D; d++) {
      PetscCall(PetscRandomGetValueReal(rnd, &r[d]));
      r[d] *= hi[d];
    }
    if (a == n - 1) PetscCall(PetscArraycpy(r, PField(P, FIELD_X), D)); /* on particle 0 */
    PetscCall(ParticlesAdd(P, a, KIND_FLUID, r, 1000 * dx * dx, h, 1000));
  }
  PetscCall(GridSetUp(&g, D, lo, hi, 2 * h0 + skin * dx, per));
  PetscCall(CellsCreate(&g, K, &C));
  PetscCall(CellsCreate(&g, K, &Cd));
  C->skin = Cd->skin = skin * dx;
  Cd->drop_w = PETSC_TRUE;
  PetscCall(CellsBuild(C, P));
  PetscCall(CellsBuild(Cd, P));
  if (skin > 0) {
    PetscReal *x = PField(P, FIELD_X);
    for (PetscInt a = 0; a < n; a++) {
      PetscReal u[3] = {0, 0, 0}, norm = 0;
      for (PetscInt d = 0; d < D; d++) {
        PetscCall(PetscRandomGetValueReal(rnd, &u[d]));
        u[d] -= 0.5;
        norm += u[d] * u[d];
      }
      norm = PetscSqrtReal(norm) + 1e-30;
      for (PetscInt d = 0; d < D; d++) x[D * a + d] += 0.499 * skin * dx * u[d] / norm;
    }
    PetscCall(CellsRefreshPairs(C, P));
    PetscCall(CellsRefreshPairs(Cd, P));
  }
  PetscCall(PetscCalloc1(n, &mark));
  for (PetscInt a = 0; a < n; a++) {
    const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
    PetscInt         found = 0;
    PetscBool        other = PETSC_FALSE; /* a has a pair of another h */
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) other = (PetscBool)(other || h[C->nbr[k]] != h[a]);
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal r = PetscSqrtReal(Dist2(x, D, a, b)), hab = PairH(h[a], h[b]), wf[2];
      PetscCheck(b != a && !mark[b], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Neighbour list of %d holds %d twice or itself", (int)a, (int)b);
      mark[b] = 1;
      ListPairKernel(K, x, h, D, a, b, other, &wf[0], &wf[1]);
      notbits += memcmp(&wf[0], &C->w[k], sizeof(PetscReal)) || memcmp(&wf[1], &C->f[k], sizeof(PetscReal));
      errw    = PetscMax(errw, PetscAbsReal(C->w[k] - KernelW(K, r, hab)) / KernelW(K, 0, hab));
      errf    = PetscMax(errf, PetscAbsReal(C->f[k] - KernelF(K, r, hab)) / PetscAbsReal(KernelF(K, hab, hab)));
    }
    for (PetscInt b = 0; b < n; b++) {
      PetscReal r2 = Dist2(x, D, a, b), hab = PairH(h[a], h[b]);
      PetscBool pair = (PetscBool)(b != a && r2 < 4 * hab * hab);
      PetscCheck(pair == (PetscBool)mark[b], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Particles %d and %d at r = %g h_ab: %s", (int)a, (int)b, (double)(PetscSqrtReal(r2) / hab), pair ? "a pair the list misses" : "listed but no pair");
      found += pair;
      mark[b] = 0;
    }
    PetscCheck(found == C->nstart[a + 1] - C->nstart[a], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Neighbour count of %d wrong", (int)a);
    pairs += found;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "neighbours (%dD, %s, %s%s): %d particles, %d pairs as by brute force, %d of them not kernel.h's values bit for bit, against KernelW/KernelF max error of W %.1e, of F %.1e (relative)\n", (int)D, KernelTypes[K->type], mixed ? "two smoothing lengths" : "one smoothing length", skin > 0 ? ", refreshed after moves of half the skin" : "", (int)n, (int)pairs, (int)notbits, (double)errw, (double)errf));
  PetscCheck(errw < 1e-12 && errf < 1e-12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Kernel values of the list differ from KernelW/KernelF");
  PetscCheck(!notbits, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%d pairs' kernel values of the list are not kernel.h's KernelShapeList/KernelShapePair bit for bit", (int)notbits);
  for (PetscInt pass = 0; pass < 2; pass++) { /* the list without W; pass 1: the particles moved on since it was made */
    PetscCheck(!memcmp(C->nstart, Cd->nstart, (n + 1) * sizeof(PetscInt)) && !memcmp(C->nbr, Cd->nbr, pairs * sizeof(PetscInt)) && !memcmp(C->f, Cd->f, pairs * sizeof(PetscReal)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "The list without W has other pairs or F");
    for (PetscInt a = 0; a < n; a++) {
      const PetscReal *w = CellsPairW(Cd, P, a);
      PetscCheck(!memcmp(w, C->w + C->nstart[a], (C->nstart[a + 1] - C->nstart[a]) * sizeof(PetscReal)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "CellsPairW of particle %d differs from the stored W (pass %d)", (int)a, (int)pass);
    }
    for (PetscInt a = 0; a < D * n; a++) PField(P, FIELD_X)[a] += 0.1 * dx;
  }
  PetscCall(PetscFree(mark));
  PetscCall(CellsDestroy(&Cd));
  PetscCall(CellsDestroy(&C));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(ParticlesDestroy(&P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckGradient(const SPHKernel *K)
{
  Particles P;
  Grid      g;
  Cells     C;
  PetscReal dx = 0.01, lo[2] = {0, 0}, hi[2] = {0.3, 0.3}, *f, *grad, *L, err = 0;
  PetscBool per[2] = {PETSC_FALSE, PETSC_FALSE};
  SPHKernel K2;
  PetscRandom rnd;
  PetscInt  n = 30, checked = 0;

  PetscFunctionBeginUser;
  PetscCall(ParticlesCreate(PETSC_COMM_SELF, &P));
  PetscCall(ParticlesSetUp(P));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -0.2 * dx, 0.2 * dx));
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) {
      PetscReal rx, ry;
      PetscCall(PetscRandomGetValueReal(rnd, &rx));
      PetscCall(PetscRandomGetValueReal(rnd, &ry));
      PetscCall(ParticlesAdd(P, j * n + i, KIND_FLUID, (PetscReal[]){(i + 0.5) * dx + rx, (j + 0.5) * dx + ry}, 1000 * dx * dx, K->h_factor * dx, 1000));
    }
  KernelInit(&K2, K->type, 2, K->h_factor);
  PetscCall(GridSetUp(&g, 2, lo, hi, 2 * K->h_factor * dx, per));
  PetscCall(CellsCreate(&g, &K2, &C));
  PetscCall(CellsBuild(C, P));
  PetscCall(PetscMalloc3(P->n, &f, 2 * P->n, &grad, 4 * P->n, &L));
  for (PetscInt a = 0; a < P->n; a++) f[a] = 3.0 * PField(P, FIELD_X)[2 * a] - 2.0 * PField(P, FIELD_X)[2 * a + 1] + 1;
  PetscCall(SPHGradientCorrection(P, C, NULL, L));
  PetscCall(SPHGradient(P, C, L, f, grad));
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal *x = PField(P, FIELD_X) + 2 * a;
    if (x[0] < 5 * dx || x[1] < 5 * dx || x[0] > 0.25 || x[1] > 0.25) continue; /* interior */
    err = PetscMax(err, PetscMax(PetscAbsReal(grad[2 * a] - 3), PetscAbsReal(grad[2 * a + 1] + 2)));
    checked++;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "gradient: corrected SPH gradient of 3x - 2y + 1 at %d interior particles, max error %.3e\n", (int)checked, (double)err));
  PetscCheck(checked > 300 && err < 1e-10, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Corrected gradient of a linear field not exact: error %g", (double)err);
  PetscCall(PetscFree3(f, grad, L));
  PetscCall(CellsDestroy(&C));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(ParticlesDestroy(&P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  /* every kernel at the paper's h = 1.3 dx and at a wider 2 dx */
  for (PetscInt t = 0; t < 3; t++)
    for (PetscInt k = 0; k < 2; k++) {
      SPHKernel K, K3;
      KernelInit(&K, (KernelType)t, 2, k ? 2.0 : SPH_H_FACTOR);
      KernelInit(&K3, (KernelType)t, 3, k ? 2.0 : SPH_H_FACTOR);
      PetscCall(CheckKernel(&K));
      PetscCall(CheckLattice(&K3));
      PetscCall(CheckShiftCeiling(&K));
      PetscCall(CheckShiftCeiling(&K3));
      if (!k) {
        PetscCall(CheckForms(&K));
        PetscCall(CheckForms(&K3));
      }
      for (PetscInt k = 0; k < 2; k++) { /* without a skin, and with WCSPH's default skin of 0.3 dx */
        PetscReal skin = k ? 0.3 : 0;
        PetscCall(CheckNeighbours(&K, PETSC_FALSE, skin));
        PetscCall(CheckNeighbours(&K, PETSC_TRUE, skin));
        PetscCall(CheckNeighbours(&K3, PETSC_FALSE, skin));
        PetscCall(CheckNeighbours(&K3, PETSC_TRUE, skin));
      }
      PetscCall(CheckGradient(&K));
    }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_kernel: ok\n"));
  PetscCall(PetscFinalize());
  return 0;
}
