#include "particles/grid.h"

PetscErrorCode GridSetUp(Grid *g, PetscInt dim, const PetscReal lo[], const PetscReal hi[], PetscReal support, const PetscBool periodic[])
{
  PetscFunctionBeginUser;
  PetscCheck(support > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Support radius must be positive");
  PetscCheck(dim == 2 || dim == 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Dimension %" PetscInt_FMT " must be 2 or 3", dim);
  g->dim = dim;
  g->cs  = support;
  for (PetscInt d = 0; d < dim; d++) {
    PetscReal L = hi[d] - lo[d];
    PetscCheck(L > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Empty domain in direction %" PetscInt_FMT, d);
    g->lo[d] = lo[d]; g->hi[d] = hi[d]; g->periodic[d] = periodic[d];
    if (periodic[d]) {
      g->n[d] = (PetscInt)PetscFloorReal(L / support);
      PetscCheck(g->n[d] >= 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "Periodic length %g is less than 3 support radii (%g): use a smaller -dx", (double)L, (double)(3 * support));
    } else g->n[d] = (PetscInt)PetscCeilReal(L / support);
  }
  /* one cell size for every direction: the largest the periodic directions allow */
  for (PetscInt d = 0; d < dim; d++)
    if (periodic[d]) g->cs = PetscMax(g->cs, (hi[d] - lo[d]) / g->n[d]);
  for (PetscInt d = 0; d < dim; d++) {
    if (periodic[d]) {
      PetscReal L = hi[d] - lo[d];
      PetscCheck(PetscAbsReal(g->n[d] * g->cs - L) < 1e-9 * L, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "Periodic lengths must give cells of one size; choose the box so that every periodic length is a multiple of one cell");
    } else {
      g->n[d]  = (PetscInt)PetscCeilReal((hi[d] - lo[d]) / g->cs);
      g->hi[d] = g->lo[d] + g->n[d] * g->cs;
    }
  }
  if (dim == 2) { /* one layer of cells */
    g->lo[2] = 0; g->hi[2] = g->cs; g->n[2] = 1; g->periodic[2] = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
