/* The global background grid of square cells (size >= support radius 2 h_max).
 * Cells are the unit of ownership (decomp), of ghost exchange (halo) and of neighbour search. */
#pragma once
#include <sphfsi/base.h>

typedef struct {
  PetscReal lo[2], hi[2]; /* domain box; particles outside it have left the domain */
  PetscReal cs;           /* cell size */
  PetscInt  n[2];         /* cells per direction */
  PetscBool periodic[2];  /* periodic directions: then hi - lo is the period and a multiple of cs */
} Grid;

/* Build a grid over [lo, hi] with cells of at least `support`; in periodic directions the cell
 * size is stretched so that a whole number of cells fills the period. */
PetscErrorCode GridSetUp(Grid *g, const PetscReal lo[2], const PetscReal hi[2], PetscReal support, const PetscBool periodic[2]);

static inline PetscInt GridNumCells(const Grid *g) { return g->n[0] * g->n[1]; }

/* Cell coordinate of a position that may lie one cell outside the box (ghost images). */
static inline PetscInt GridCoord(const Grid *g, PetscReal x, PetscInt d)
{
  PetscReal s = (x - g->lo[d]) / g->cs;
  return (PetscInt)PetscFloorReal(s);
}

/* Global cell index of a position inside the box, or -1 when it is outside. */
static inline PetscInt GridCellOf(const Grid *g, const PetscReal *x)
{
  PetscInt i = GridCoord(g, x[0], 0), j = GridCoord(g, x[1], 1);
  if (i < 0 || j < 0 || i >= g->n[0] || j >= g->n[1]) return -1;
  return j * g->n[0] + i;
}

/* Wrap a position into the box in its periodic directions. */
static inline void GridWrap(const Grid *g, PetscReal *x)
{
  for (PetscInt d = 0; d < 2; d++) {
    if (!g->periodic[d]) continue;
    PetscReal L = g->hi[d] - g->lo[d];
    if (x[d] >= g->hi[d]) x[d] -= L;
    else if (x[d] < g->lo[d]) x[d] += L;
    if (x[d] >= g->hi[d]) x[d] = g->lo[d]; /* lo - tiny + L rounds to hi: the same point */
  }
}
