/* Kernel (Eq. 12): normalisation, compact support, gradient antisymmetry; the neighbour lists of a
 * random cloud (one smoothing length, and two) equal a brute-force search; the corrected SPH gradient
 * of a linear field is exact to round-off on an irregular particle cloud. */
#include <sphfsi/kernel.h>
#include <sphfsi/cells.h>
#include <sphfsi/operators.h>

static PetscErrorCode CheckKernel(void)
{
  PetscReal h = 0.013, sum = 0, d = h / 200;
  PetscFunctionBeginUser;
  /* integral of W over the plane by the midpoint rule on a fine grid */
  for (PetscReal x = -2 * h + d / 2; x < 2 * h; x += d)
    for (PetscReal y = -2 * h + d / 2; y < 2 * h; y += d) sum += KernelW(PetscSqrtReal(x * x + y * y), h) * d * d;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kernel: integral of W = %.8f\n", (double)sum));
  PetscCheck(PetscAbsReal(sum - 1) < 1e-4, PETSC_COMM_SELF, PETSC_ERR_PLIB, "W not normalised: %g", (double)sum);
  PetscCheck(KernelW(2 * h, h) == 0 && KernelW(2.5 * h, h) == 0 && KernelDW(2 * h, h) == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "W not compact");
  PetscCheck(PetscAbsReal(KernelW(h * (1 - 1e-12), h) - KernelW(h * (1 + 1e-12), h)) < 1e-9 * KernelW(h, h), PETSC_COMM_SELF, PETSC_ERR_PLIB, "W discontinuous at R = 1");
  /* F = (dW/dr)/r consistent with dW/dr, and dW/dr with a finite difference of W */
  for (PetscReal R = 0.05; R < 2; R += 0.05) {
    PetscReal r = R * h, e = 1e-7 * h, fd = (KernelW(r + e, h) - KernelW(r - e, h)) / (2 * e);
    PetscCheck(PetscAbsReal(fd - KernelDW(r, h)) < 1e-5 * PetscAbsReal(KernelDW(h, h)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "dW/dr wrong at R = %g", (double)R);
    PetscCheck(PetscAbsReal(KernelF(r, h) * r - KernelDW(r, h)) < 1e-12 * PetscAbsReal(KernelDW(h, h)), PETSC_COMM_SELF, PETSC_ERR_PLIB, "F wrong at R = %g", (double)R);
  }
  /* grad_a W_ab = -grad_b W_ba exactly, with mixed sizes h_ab = sqrt(h_a h_b) */
  {
    PetscReal ha = 0.01, hb = 0.013, xa[2] = {0.1, 0.2}, xb[2] = {0.111, 0.193};
    PetscReal r = PetscSqrtReal((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]));
    PetscReal ga = KernelF(r, PairH(ha, hb)) * (xa[0] - xb[0]), gb = KernelF(r, PairH(hb, ha)) * (xb[0] - xa[0]);
    PetscCheck(ga == -gb, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Gradient not antisymmetric");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Neighbour lists of a random cloud (no lattice: the order in which candidates are pairs is
 * random, as in a splashing flow) against all pairs with r < 2 h_ab by brute force, with one
 * smoothing length and with two; two particles share a position (a pair at r = 0). */
static PetscErrorCode CheckNeighbours(PetscBool mixed)
{
  Particles   P;
  Grid        g;
  Cells       C;
  PetscReal   dx = 0.01, h0 = 1.3 * dx, lo[2] = {0, 0}, hi[2] = {0.2, 0.15};
  PetscBool   per[2] = {PETSC_FALSE, PETSC_FALSE};
  PetscRandom rnd;
  PetscInt    n = 300, pairs = 0, *mark;
  PetscReal   errw = 0, errf = 0;

  PetscFunctionBeginUser;
  PetscCall(ParticlesCreate(PETSC_COMM_SELF, &P));
  PetscCall(ParticlesSetUp(P));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal rx, ry, h = mixed && a % 3 == 0 ? 0.7 * h0 : h0;
    PetscCall(PetscRandomGetValueReal(rnd, &rx));
    PetscCall(PetscRandomGetValueReal(rnd, &ry));
    if (a == n - 1) { rx = PField(P, FIELD_X)[0] / hi[0]; ry = PField(P, FIELD_X)[1] / hi[1]; } /* on particle 0 */
    PetscCall(ParticlesAdd(P, a, KIND_FLUID, rx * hi[0], ry * hi[1], 1000 * dx * dx, h, 1000));
  }
  PetscCall(GridSetUp(&g, lo, hi, 2 * h0, per));
  PetscCall(CellsCreate(&g, &C));
  PetscCall(CellsBuild(C, P));
  PetscCall(PetscCalloc1(n, &mark));
  for (PetscInt a = 0; a < n; a++) {
    const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
    PetscInt         found = 0;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal r = PetscSqrtReal((x[2 * a] - x[2 * b]) * (x[2 * a] - x[2 * b]) + (x[2 * a + 1] - x[2 * b + 1]) * (x[2 * a + 1] - x[2 * b + 1])), hab = PairH(h[a], h[b]);
      PetscCheck(b != a && !mark[b], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Neighbour list of %d holds %d twice or itself", (int)a, (int)b);
      mark[b] = 1;
      errw    = PetscMax(errw, PetscAbsReal(C->w[k] - KernelW(r, hab)) / KernelW(0, hab));
      errf    = PetscMax(errf, PetscAbsReal(C->f[k] - KernelF(r, hab)) / PetscAbsReal(KernelF(hab, hab)));
    }
    for (PetscInt b = 0; b < n; b++) {
      PetscReal r2 = (x[2 * a] - x[2 * b]) * (x[2 * a] - x[2 * b]) + (x[2 * a + 1] - x[2 * b + 1]) * (x[2 * a + 1] - x[2 * b + 1]), hab = PairH(h[a], h[b]);
      PetscBool pair = (PetscBool)(b != a && r2 < 4 * hab * hab);
      PetscCheck(pair == (PetscBool)mark[b], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Particles %d and %d at r = %g h_ab: %s", (int)a, (int)b, (double)(PetscSqrtReal(r2) / hab), pair ? "a pair the list misses" : "listed but no pair");
      found += pair;
      mark[b] = 0;
    }
    PetscCheck(found == C->nstart[a + 1] - C->nstart[a], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Neighbour count of %d wrong", (int)a);
    pairs += found;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "neighbours (%s): %d particles, %d pairs as by brute force, max error of W %.1e, of F %.1e (relative)\n", mixed ? "two smoothing lengths" : "one smoothing length", (int)n, (int)pairs, (double)errw, (double)errf));
  PetscCheck(errw < 1e-12 && errf < 1e-12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Kernel values of the list differ from KernelW/KernelF");
  PetscCall(PetscFree(mark));
  PetscCall(CellsDestroy(&C));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(ParticlesDestroy(&P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckGradient(void)
{
  Particles P;
  Grid      g;
  Cells     C;
  PetscReal dx = 0.01, lo[2] = {0, 0}, hi[2] = {0.3, 0.3}, *f, *grad, *L, err = 0;
  PetscBool per[2] = {PETSC_FALSE, PETSC_FALSE};
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
      PetscCall(ParticlesAdd(P, j * n + i, KIND_FLUID, (i + 0.5) * dx + rx, (j + 0.5) * dx + ry, 1000 * dx * dx, 1.3 * dx, 1000));
    }
  PetscCall(GridSetUp(&g, lo, hi, 2.6 * dx, per));
  PetscCall(CellsCreate(&g, &C));
  PetscCall(CellsBuild(C, P));
  PetscCall(PetscMalloc3(P->n, &f, 2 * P->n, &grad, 4 * P->n, &L));
  for (PetscInt a = 0; a < P->n; a++) f[a] = 3.0 * PField(P, FIELD_X)[2 * a] - 2.0 * PField(P, FIELD_X)[2 * a + 1] + 1;
  PetscCall(SPHGradientCorrection(P, C, NULL, L));
  PetscCall(SPHGradient(P, C, L, f, grad));
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal *x = PField(P, FIELD_X) + 2 * a;
    if (x[0] < 3 * dx || x[1] < 3 * dx || x[0] > 0.27 || x[1] > 0.27) continue; /* interior */
    err = PetscMax(err, PetscMax(PetscAbsReal(grad[2 * a] - 3), PetscAbsReal(grad[2 * a + 1] + 2)));
    checked++;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "gradient: corrected SPH gradient of 3x - 2y + 1 at %d interior particles, max error %.3e\n", (int)checked, (double)err));
  PetscCheck(checked > 400 && err < 1e-10, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Corrected gradient of a linear field not exact: error %g", (double)err);
  PetscCall(PetscFree3(f, grad, L));
  PetscCall(CellsDestroy(&C));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(ParticlesDestroy(&P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CheckKernel());
  PetscCall(CheckNeighbours(PETSC_FALSE));
  PetscCall(CheckNeighbours(PETSC_TRUE));
  PetscCall(CheckGradient());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_kernel: ok\n"));
  PetscCall(PetscFinalize());
  return 0;
}
