/* The global background grid of cubic (2D: square) cells of size >= support radius 2 h_max.
 * Cells are the unit of ownership (decomp), of ghost exchange (halo) and of neighbour search.
 * A 2D grid is one layer of cells: n[2] = 1 and z is never read. */
#pragma once
#include "base/base.h"
#include <stdio.h>

typedef struct {
  PetscInt  dim;          /* 2 or 3 */
  PetscReal lo[3], hi[3]; /* domain box; particles outside it have left the domain */
  PetscReal cs;           /* cell size */
  PetscInt  n[3];         /* cells per direction (n[2] = 1 in 2D) */
  PetscBool periodic[3];  /* periodic directions: then hi - lo is the period and a multiple of cs */
} Grid;

/* Build a grid of dimension dim over [lo, hi] (dim values each) with cells of at least `support`;
 * in periodic directions the cell size is stretched so that a whole number of cells fills the period. */
PetscErrorCode GridSetUp(Grid *g, PetscInt dim, const PetscReal lo[], const PetscReal hi[], PetscReal support, const PetscBool periodic[]);

static inline PetscInt GridNumCells(const Grid *g) { return g->n[0] * g->n[1] * g->n[2]; }

/* Cell coordinate of a position that may lie one cell outside the box (ghost images). */
static inline PetscInt GridCoord(const Grid *g, PetscReal x, PetscInt d)
{
  PetscReal s = (x - g->lo[d]) / g->cs;
  return (PetscInt)PetscFloorReal(s);
}

/* Global cell index of cell coordinates (i, j, k) inside the grid (k = 0 in 2D). */
static inline PetscInt GridIndex(const Grid *g, PetscInt i, PetscInt j, PetscInt k) { return (k * g->n[1] + j) * g->n[0] + i; }

/* Cell coordinates of a global cell index. */
static inline void GridCellCoords(const Grid *g, PetscInt c, PetscInt ijk[3])
{
  ijk[0] = c % g->n[0];
  ijk[1] = (c / g->n[0]) % g->n[1];
  ijk[2] = c / (g->n[0] * g->n[1]);
}

/* Global cell index of a position inside the box, or -1 when it is outside. */
static inline PetscInt GridCellOf(const Grid *g, const PetscReal *x)
{
  PetscInt i = GridCoord(g, x[0], 0), j = GridCoord(g, x[1], 1), k = g->dim == 3 ? GridCoord(g, x[2], 2) : 0;
  if (i < 0 || j < 0 || k < 0 || i >= g->n[0] || j >= g->n[1] || k >= g->n[2]) return -1;
  return GridIndex(g, i, j, k);
}

/* The cells around cell c (8 in 2D, 26 in 3D; fewer at a non-periodic edge), wrapped in periodic
 * directions, in the order z, y, x of the offsets; c itself is left out.  Returns their number. */
static inline PetscInt GridCellNeighbours(const Grid *g, PetscInt c, PetscInt nb[26])
{
  PetscInt ijk[3], cnt = 0, kz = g->dim == 3 ? 1 : 0;
  GridCellCoords(g, c, ijk);
  for (PetscInt dk = -kz; dk <= kz; dk++)
    for (PetscInt dj = -1; dj <= 1; dj++)
      for (PetscInt di = -1; di <= 1; di++) {
        PetscInt cc[3] = {ijk[0] + di, ijk[1] + dj, ijk[2] + dk}, out = 0;
        if (!di && !dj && !dk) continue;
        for (PetscInt d = 0; d < 3; d++) {
          if (g->periodic[d]) cc[d] = (cc[d] + g->n[d]) % g->n[d];
          if (cc[d] < 0 || cc[d] >= g->n[d]) out = 1;
        }
        if (!out) nb[cnt++] = GridIndex(g, cc[0], cc[1], cc[2]);
      }
  return cnt;
}

/* "(x, y)" or "(x, y, z)" of a point of dimension D, for messages; returns buf. */
static inline const char *GridFormatPoint(char *buf, size_t len, PetscInt D, const PetscReal *x)
{
  if (D == 3) snprintf(buf, len, "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]);
  else snprintf(buf, len, "(%g, %g)", (double)x[0], (double)x[1]);
  return buf;
}

/* Wrap a position into the box in its periodic directions. */
static inline void GridWrap(const Grid *g, PetscReal *x)
{
  for (PetscInt d = 0; d < g->dim; d++) {
    if (!g->periodic[d]) continue;
    PetscReal L = g->hi[d] - g->lo[d];
    if (x[d] >= g->hi[d]) x[d] -= L;
    else if (x[d] < g->lo[d]) x[d] += L;
    if (x[d] >= g->hi[d]) x[d] = g->lo[d]; /* lo - tiny + L rounds to hi: the same point */
  }
}
