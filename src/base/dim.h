/* One source, two dimensions.  The pair loops are written once for a dimension D that is a
 * parameter of an always-inlined function; each loop driver calls it with the constant 2 or 3
 * (SPH_DIM_DISPATCH), so the compiler builds both and unrolls the small vector loops.  The 2D
 * instance evaluates the same expressions as the 2D-only code before it, bit for bit: the vector
 * helpers below keep the order x, y (then z) of every sum. */
#pragma once
#include "base/base.h"

#define SPH_INLINE static inline __attribute__((always_inline))

/* call f(args..., D) with D the constant 2 or 3 */
#define SPH_DIM_DISPATCH(dim, f, ...) ((dim) == 3 ? f(__VA_ARGS__, 3) : f(__VA_ARGS__, 2))

/* a . b */
SPH_INLINE PetscReal VDot(const PetscReal *a, const PetscReal *b, const PetscInt D)
{
  PetscReal s = a[0] * b[0] + a[1] * b[1];
  if (D == 3) s += a[2] * b[2];
  return s;
}

/* d = a - b */
SPH_INLINE void VSub(const PetscReal *a, const PetscReal *b, PetscReal *d, const PetscInt D)
{
  for (PetscInt k = 0; k < D; k++) d[k] = a[k] - b[k];
}

/* Symmetric D x D matrices stored by their upper triangle: 2D xx, xy, yy; 3D xx, xy, xz, yy, yz, zz. */

/* M -= c d (x) d */
SPH_INLINE void SymOuterSubtract(PetscReal *M, PetscReal c, const PetscReal *d, const PetscInt D)
{
  if (D == 2) { M[0] -= c * d[0] * d[0]; M[1] -= c * d[0] * d[1]; M[2] -= c * d[1] * d[1]; return; }
  M[0] -= c * d[0] * d[0]; M[1] -= c * d[0] * d[1]; M[2] -= c * d[0] * d[2];
  M[3] -= c * d[1] * d[1]; M[4] -= c * d[1] * d[2]; M[5] -= c * d[2] * d[2];
}

/* Smallest and largest eigenvalue of a symmetric 3 x 3 matrix (the trigonometric solution of the
 * characteristic cubic, Smith 1961). */
static inline void Sym3EigenRange(const PetscReal *M, PetscReal *lmin, PetscReal *lmax)
{
  PetscReal p1 = M[1] * M[1] + M[2] * M[2] + M[4] * M[4], q = (M[0] + M[3] + M[5]) / 3.0;
  PetscReal a = M[0] - q, b = M[3] - q, c = M[5] - q, p2 = a * a + b * b + c * c + 2.0 * p1, p, r, phi;
  if (p2 <= 0) { *lmin = *lmax = q; return; }
  p = PetscSqrtReal(p2 / 6.0);
  /* r = det((M - q I) / p) / 2 */
  r = (a * (b * c - M[4] * M[4]) - M[1] * (M[1] * c - M[4] * M[2]) + M[2] * (M[1] * M[4] - b * M[2])) / (2.0 * p * p * p);
  r   = PetscMin(1.0, PetscMax(-1.0, r));
  phi = PetscAcosReal(r) / 3.0;
  *lmax = q + 2.0 * p * PetscCosReal(phi);
  *lmin = q + 2.0 * p * PetscCosReal(phi + 2.0 * PETSC_PI / 3.0);
}

/* Smallest and largest eigenvalue of a symmetric D x D matrix (2D: the closed form). */
SPH_INLINE void SymEigenRange(const PetscReal *M, PetscReal *lmin, PetscReal *lmax, const PetscInt D)
{
  if (D == 2) {
    PetscReal half = 0.5 * (M[0] + M[2]), disc = PetscSqrtReal(0.25 * (M[0] - M[2]) * (M[0] - M[2]) + M[1] * M[1]);
    *lmin = half - disc;
    *lmax = half + disc;
  } else Sym3EigenRange(M, lmin, lmax);
}

/* x = M^-1 b where M (symmetric, positive) is well conditioned: its smallest over its largest
 * eigenvalue above cond, and its determinant clear of round-off; returns whether it solved. */
SPH_INLINE PetscBool SymSolveConditioned(const PetscReal *M, const PetscReal *b, PetscReal cond, PetscReal *x, const PetscInt D)
{
  if (D == 2) {
    PetscReal det = M[0] * M[2] - M[1] * M[1], lmin, lmax;
    SymEigenRange(M, &lmin, &lmax, 2);
    if (!(lmin > cond * lmax && det > 1e-6 * (M[0] * M[0] + M[2] * M[2]))) return PETSC_FALSE;
    x[0] = (M[2] * b[0] - M[1] * b[1]) / det;
    x[1] = (-M[1] * b[0] + M[0] * b[1]) / det;
    return PETSC_TRUE;
  } else {
    PetscReal lmin, lmax, c[6], det;
    Sym3EigenRange(M, &lmin, &lmax);
    if (!(lmin > cond * lmax && lmin > 1e-3 * lmax)) return PETSC_FALSE;
    /* cofactors: the inverse is c / det */
    c[0] = M[3] * M[5] - M[4] * M[4]; c[1] = M[2] * M[4] - M[1] * M[5]; c[2] = M[1] * M[4] - M[2] * M[3];
    c[3] = M[0] * M[5] - M[2] * M[2]; c[4] = M[1] * M[2] - M[0] * M[4]; c[5] = M[0] * M[3] - M[1] * M[1];
    det  = M[0] * c[0] + M[1] * c[1] + M[2] * c[2];
    x[0] = (c[0] * b[0] + c[1] * b[1] + c[2] * b[2]) / det;
    x[1] = (c[1] * b[0] + c[3] * b[1] + c[4] * b[2]) / det;
    x[2] = (c[2] * b[0] + c[4] * b[1] + c[5] * b[2]) / det;
    return PETSC_TRUE;
  }
}
