#include "fluid/operators.h"
#include "base/dim.h"
#include "particles/pair_loop.h"

/* sum_b V_b (x_b - x_a) (x) grad_a W_ab over the neighbours that keep accepts */
typedef struct {
  Particles        P;
  const PetscReal *x, *m, *rho;
  PetscBool (*keep)(PetscInt);
  PetscReal M[9];
} CorrectionSum;

SPH_INLINE void CorrectionPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  CorrectionSum *s = (CorrectionSum *)ctx;
  PetscReal      d[3], c = -s->m[p.b] / s->rho[p.b] * p.F;
  if (s->keep && !s->keep(s->P->kind[p.b])) return;
  VSub(s->x + D * a, s->x + D * p.b, d, D);
  /* (x_b - x_a)_i (grad_a W)_j = -(dx_i)(F dx_j) */
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt j = 0; j < D; j++) s->M[D * i + j] += c * d[i] * d[j];
}

SPH_INLINE PetscErrorCode GradientCorrectionD(Particles P, Cells C, PetscBool (*keep)(PetscInt), PetscReal *L, const PetscInt D)
{
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    CorrectionSum    s = {.P = P, .x = x, .m = m, .rho = rho, .keep = keep};
    const PetscReal *M = s.M;
    PetscReal        det, *La = L + D * D * a;
    if (keep && !keep(P->kind[a])) continue;
    SPHPairs(C, a, CorrectionPair, &s, D);
    if (D == 2) det = M[0] * M[3] - M[1] * M[2];
    else det = M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) + M[2] * (M[3] * M[7] - M[4] * M[6]);
    if (PetscAbsReal(det) < 1e-3) { /* too few neighbours to invert: uncorrected */
      for (PetscInt i = 0; i < D * D; i++) La[i] = i % (D + 1) == 0;
      continue;
    }
    /* L = M^-T (the cofactor matrix over det) so that L grad W applied to (f_b - f_a) reproduces grad f */
    if (D == 2) {
      La[0] = M[3] / det;  La[1] = -M[2] / det;
      La[2] = -M[1] / det; La[3] = M[0] / det;
    } else
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) {
          PetscInt i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
          La[3 * i + j] = (M[3 * i1 + j1] * M[3 * i2 + j2] - M[3 * i1 + j2] * M[3 * i2 + j1]) / det;
        }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHGradientCorrection(Particles P, Cells C, PetscBool (*keep)(PetscInt), PetscReal *L) { return SPH_DIM_DISPATCH(P->dim, GradientCorrectionD, P, C, keep, L); }

/* sum_b V_b (f_b - f_a) grad_a W_ab */
typedef struct {
  const PetscReal *x, *m, *rho, *f;
  PetscReal        g[3];
} GradientSum;

SPH_INLINE void GradientPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  GradientSum *s = (GradientSum *)ctx;
  PetscReal    c = s->m[p.b] / s->rho[p.b] * (s->f[p.b] - s->f[a]) * p.F;
  for (PetscInt i = 0; i < D; i++) s->g[i] += c * (s->x[D * a + i] - s->x[D * p.b + i]);
}

SPH_INLINE PetscErrorCode GradientD(Particles P, Cells C, const PetscReal *L, const PetscReal *f, PetscReal *grad, const PetscInt D)
{
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    GradientSum s = {.x = x, .m = m, .rho = rho, .f = f};
    SPHPairs(C, a, GradientPair, &s, D);
    for (PetscInt i = 0; i < D; i++) grad[D * a + i] = L ? VDot(L + D * D * a + D * i, s.g, D) : s.g[i];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHGradient(Particles P, Cells C, const PetscReal *L, const PetscReal *f, PetscReal *grad) { return SPH_DIM_DISPATCH(P->dim, GradientD, P, C, L, f, grad); }
