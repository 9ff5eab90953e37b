#include <sphfsi/operators.h>

PetscErrorCode SPHGradientCorrection(Particles P, Cells C, PetscBool (*keep)(PetscInt), PetscReal *L)
{
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal M[4] = {0, 0, 0, 0}, det;
    if (keep && !keep(P->kind[a])) continue;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal dx = x[2 * a] - x[2 * b], dy = x[2 * a + 1] - x[2 * b + 1], s = -m[b] / rho[b] * C->f[k];
      if (keep && !keep(P->kind[b])) continue;
      /* (x_b - x_a)_i (grad_a W)_j = -(dx_i)(F dx_j) */
      M[0] += s * dx * dx; M[1] += s * dx * dy; M[2] += s * dy * dx; M[3] += s * dy * dy;
    }
    det = M[0] * M[3] - M[1] * M[2];
    if (PetscAbsReal(det) < 1e-3) { /* too few neighbours to invert: uncorrected */
      L[4 * a] = 1; L[4 * a + 1] = 0; L[4 * a + 2] = 0; L[4 * a + 3] = 1;
      continue;
    }
    /* L = M^-T so that L grad W applied to (f_b - f_a) reproduces grad f */
    L[4 * a]     = M[3] / det;  L[4 * a + 1] = -M[2] / det;
    L[4 * a + 2] = -M[1] / det; L[4 * a + 3] = M[0] / det;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHGradient(Particles P, Cells C, const PetscReal *L, const PetscReal *f, PetscReal *grad)
{
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal gx = 0, gy = 0;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal s = m[b] / rho[b] * (f[b] - f[a]) * C->f[k];
      gx += s * (x[2 * a] - x[2 * b]);
      gy += s * (x[2 * a + 1] - x[2 * b + 1]);
    }
    if (L) { grad[2 * a] = L[4 * a] * gx + L[4 * a + 1] * gy; grad[2 * a + 1] = L[4 * a + 2] * gx + L[4 * a + 3] * gy; }
    else { grad[2 * a] = gx; grad[2 * a + 1] = gy; }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
