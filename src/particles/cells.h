/* Cell-linked lists over owned + ghost particles and the neighbour list of owned particles.
 * Within a cell particles are ordered by global id and cells are visited in a fixed stencil
 * order, so every neighbour sum is evaluated in the same order whatever the number of ranks. */
#pragma once
#include "particles/grid.h"
#include "particles/particles.h"
#include "base/kernel.h"

typedef struct _p_Cells *Cells;
struct _p_Cells {
  const Grid *grid;
  PetscInt    lo[3], n[3];     /* local box of cells (global cell coordinates; one layer in 2D) */
  PetscInt   *start, cap_cell; /* particles of local cell c: list[start[c] .. start[c+1]) */
  PetscInt   *list, *cell, cap_part;
  PetscInt   *nstart, *nbr, cap_nbr, cap_start, npart; /* neighbours of owned a < npart: nbr[nstart[a] .. nstart[a+1]) */
  PetscReal  *w, *f;                  /* per pair: W_ab and F_ab = (dW/dr)/r, so grad_a W_ab = F_ab (x_a - x_b) */
  PetscInt    max_nbr;
  PetscBool  *wet; PetscInt cap_wet; /* per local cell: holds a fluid particle (the main list's walls) */
  PetscReal   skin;                    /* Verlet skin of CellsBuild's list (0: none) */
  PetscBool   uniform;                 /* the last build saw one smoothing length (owned and ghosts) */
  PetscInt   *cstart, *cnbr, cap_cstart, cap_cnbr; /* with a skin: the candidates, r < 2 h_ab + skin at the build */
  const SPHKernel *kernel; /* the run's kernel (W, F of the pairs) */
  PetscBool   drop_w;          /* the main list keeps F but not W (8 B a pair): CellsPairW recomputes W */
  PetscReal  *wrow, *xk;       /* drop_w: one particle's W and F scratch (cap_wrow each); positions of the last kernel evaluation */
  PetscInt    cap_wrow, cap_xk;
};

PetscErrorCode CellsCreate(const Grid *g, const SPHKernel *K, Cells *c);
PetscErrorCode CellsDestroy(Cells *c);
/* Bin owned + ghost particles and build the neighbour list (r < 2 h_ab) of owned particles.  With
 * a skin (c->skin > 0) the pairs within 2 h_ab + skin are kept as candidates, and the list holds
 * those of them within 2 h_ab, in the same order as a build without skin on the same bins. */
PetscErrorCode CellsBuild(Cells c, Particles P);
/* With a skin: the list anew from the candidates at the current positions (complete while no
 * particle has moved skin / 2 since CellsBuild), with their kernel values. */
PetscErrorCode CellsRefreshPairs(Cells c, Particles P);
/* W of owned particle a's pairs, the pair nstart[a] + j at index j: the list's own, or with drop_w
 * recomputed here with the build's operations at the build's positions (the same bits).  Valid
 * until the next call. */
const PetscReal *CellsPairW(Cells c, Particles P, PetscInt a);
/* Cells with only a neighbour list (no bins of their own): for CellsBuildSubList. */
PetscErrorCode CellsCreateList(const SPHKernel *K, Cells *c);
/* Neighbour list in `sub` of the owned particles whose kind `keep` accepts, with the binning of
 * `c` and radius 2 h_ab + skin (skin + 2 h_max <= cell size), so that it stays complete while the
 * particles move less than skin / 2; kernel values at the current positions (zero beyond 2 h_ab). */
PetscErrorCode CellsBuildSubList(Cells c, Particles P, PetscBool (*keep)(PetscInt), PetscReal skin, Cells sub);
/* Kernel values of the pairs of a list at the current positions: W and F (grad W = F r_ab); F only
 * (the total-Lagrangian solid reads no W: it would be a sixth of its step's work). */
PetscErrorCode CellsUpdatePairs(Cells sub, Particles P);
PetscErrorCode CellsUpdatePairsF(Cells sub, Particles P);
/* Neighbour list and pair kernel values only, for the same binning but new positions (e.g. ISPH
 * predictor); particles must not have left their cell's stencil. */
PetscErrorCode CellsBuildNeighbours(Cells c, Particles P);
