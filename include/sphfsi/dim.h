/* One source, two dimensions.  The pair loops are written once for a dimension D that is a
 * parameter of an always-inlined function; each loop driver calls it with the constant 2 or 3
 * (SPH_DIM_DISPATCH), so the compiler builds both and unrolls the small vector loops.  The 2D
 * instance evaluates the same expressions as the 2D-only code before it, bit for bit: the vector
 * helpers below keep the order x, y (then z) of every sum. */
#pragma once
#include <sphfsi/base.h>

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
