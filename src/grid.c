#include <sphfsi/grid.h>

PetscErrorCode GridSetUp(Grid *g, const PetscReal lo[2], const PetscReal hi[2], PetscReal support, const PetscBool periodic[2])
{
  PetscFunctionBeginUser;
  PetscCheck(support > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Support radius must be positive");
  g->cs = support;
  for (PetscInt d = 0; d < 2; d++) {
    PetscReal L = hi[d] - lo[d];
    PetscCheck(L > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Empty domain in direction %" PetscInt_FMT, d);
    g->lo[d] = lo[d]; g->hi[d] = hi[d]; g->periodic[d] = periodic[d];
    if (periodic[d]) {
      g->n[d] = (PetscInt)PetscFloorReal(L / support);
      PetscCheck(g->n[d] >= 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "Periodic length %g is less than 3 support radii (%g): use a smaller -dx", (double)L, (double)(3 * support));
    } else g->n[d] = (PetscInt)PetscCeilReal(L / support);
  }
  /* one cell size for both directions: the largest the periodic directions allow */
  for (PetscInt d = 0; d < 2; d++)
    if (periodic[d]) g->cs = PetscMax(g->cs, (hi[d] - lo[d]) / g->n[d]);
  for (PetscInt d = 0; d < 2; d++) {
    if (periodic[d]) {
      PetscReal L = hi[d] - lo[d];
      PetscCheck(PetscAbsReal(g->n[d] * g->cs - L) < 1e-9 * L, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "Periodic lengths in x and y must give cells of one size; choose the box so that both are multiples of one cell");
    } else {
      g->n[d]  = (PetscInt)PetscCeilReal((hi[d] - lo[d]) / g->cs);
      g->hi[d] = g->lo[d] + g->n[d] * g->cs;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
