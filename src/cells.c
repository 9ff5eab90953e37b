#include <sphfsi/cells.h>
#include <sphfsi/kernel.h>

PetscErrorCode CellsCreate(const Grid *g, Cells *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(c));
  (*c)->grid = g;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellsDestroy(Cells *c)
{
  PetscFunctionBeginUser;
  if (!*c) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree((*c)->start));
  PetscCall(PetscFree2((*c)->list, (*c)->cell));
  PetscCall(PetscFree((*c)->nstart));
  PetscCall(PetscFree3((*c)->nbr, (*c)->w, (*c)->f));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Local cell of particle coordinates (i, j) */
static inline PetscInt LocalCell(Cells c, PetscInt i, PetscInt j) { return (j - c->lo[1]) * c->n[0] + (i - c->lo[0]); }

PetscErrorCode CellsBuild(Cells c, Particles P)
{
  const Grid      *g = c->grid;
  const PetscReal *x = PField(P, FIELD_X);
  PetscInt         ntot = P->n + P->ng, imin[2] = {PETSC_MAX_INT, PETSC_MAX_INT}, imax[2] = {PETSC_MIN_INT, PETSC_MIN_INT}, nc;

  PetscFunctionBeginUser;
  if (ntot > c->cap_part) {
    PetscCall(PetscFree2(c->list, c->cell));
    c->cap_part = (3 * ntot) / 2 + 16;
    PetscCall(PetscMalloc2(c->cap_part, &c->list, c->cap_part, &c->cell));
    PetscCall(PetscFree(c->nstart));
    PetscCall(PetscMalloc1(c->cap_part + 1, &c->nstart));
  }
  for (PetscInt a = 0; a < ntot; a++)
    for (PetscInt d = 0; d < 2; d++) {
      PetscInt k = GridCoord(g, x[2 * a + d], d);
      imin[d] = PetscMin(imin[d], k); imax[d] = PetscMax(imax[d], k);
    }
  if (!ntot) { imin[0] = imin[1] = 0; imax[0] = imax[1] = 0; }
  for (PetscInt d = 0; d < 2; d++) { c->lo[d] = imin[d]; c->n[d] = imax[d] - imin[d] + 1; }
  nc = c->n[0] * c->n[1];
  if (nc + 1 > c->cap_cell) {
    PetscCall(PetscFree(c->start));
    c->cap_cell = (3 * (nc + 1)) / 2;
    PetscCall(PetscMalloc1(c->cap_cell, &c->start));
  }
  /* counting sort by cell */
  PetscCall(PetscArrayzero(c->start, nc + 1));
  for (PetscInt a = 0; a < ntot; a++) {
    c->cell[a] = LocalCell(c, GridCoord(g, x[2 * a], 0), GridCoord(g, x[2 * a + 1], 1));
    c->start[c->cell[a] + 1]++;
  }
  for (PetscInt k = 0; k < nc; k++) c->start[k + 1] += c->start[k];
  {
    PetscInt *fill;
    PetscCall(PetscMalloc1(nc, &fill));
    PetscCall(PetscArraycpy(fill, c->start, nc));
    for (PetscInt a = 0; a < ntot; a++) c->list[fill[c->cell[a]]++] = a;
    PetscCall(PetscFree(fill));
  }
  /* within a cell, by global id (insertion sort: a cell holds a handful of particles) */
  for (PetscInt k = 0; k < nc; k++)
    for (PetscInt s = c->start[k] + 1; s < c->start[k + 1]; s++) {
      PetscInt v = c->list[s], t = s;
      while (t > c->start[k] && P->id[c->list[t - 1]] > P->id[v]) { c->list[t] = c->list[t - 1]; t--; }
      c->list[t] = v;
    }
  PetscCall(CellsBuildNeighbours(c, P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellsBuildNeighbours(Cells c, Particles P)
{
  const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
  PetscInt         n = P->n, cnt = 0;

  PetscFunctionBeginUser;
  if (!c->nbr) {
    c->cap_nbr = PetscMax(64, 32 * n);
    PetscCall(PetscMalloc3(c->cap_nbr, &c->nbr, c->cap_nbr, &c->w, c->cap_nbr, &c->f));
  }
  c->max_nbr = 0;
  for (PetscInt a = 0; a < n; a++) {
    PetscInt  ca = c->cell[a], ia = ca % c->n[0], ja = ca / c->n[0];
    PetscReal xa = x[2 * a], ya = x[2 * a + 1], ha = h[a];
    c->nstart[a] = cnt;
    for (PetscInt dj = -1; dj <= 1; dj++) {
      PetscInt j = ja + dj;
      if (j < 0 || j >= c->n[1]) continue;
      for (PetscInt di = -1; di <= 1; di++) {
        PetscInt i = ia + di, cb;
        if (i < 0 || i >= c->n[0]) continue;
        cb = j * c->n[0] + i;
        if (cnt + (c->start[cb + 1] - c->start[cb]) > c->cap_nbr) {
          PetscInt  *nb;
          PetscReal *nw, *nf;
          c->cap_nbr = 2 * c->cap_nbr + (c->start[cb + 1] - c->start[cb]);
          PetscCall(PetscMalloc3(c->cap_nbr, &nb, c->cap_nbr, &nw, c->cap_nbr, &nf));
          PetscCall(PetscArraycpy(nb, c->nbr, cnt));
          PetscCall(PetscArraycpy(nw, c->w, cnt));
          PetscCall(PetscArraycpy(nf, c->f, cnt));
          PetscCall(PetscFree3(c->nbr, c->w, c->f));
          c->nbr = nb; c->w = nw; c->f = nf;
        }
        for (PetscInt s = c->start[cb]; s < c->start[cb + 1]; s++) {
          PetscInt  b = c->list[s];
          PetscReal dx = xa - x[2 * b], dy = ya - x[2 * b + 1], r2 = dx * dx + dy * dy, hab = PairH(ha, h[b]);
          if (b != a && r2 < 4.0 * hab * hab) {
            PetscReal r = PetscSqrtReal(r2);
            c->nbr[cnt] = b;
            c->w[cnt]   = KernelW(r, hab);
            c->f[cnt]   = KernelF(r, hab);
            cnt++;
          }
        }
      }
    }
    c->max_nbr = PetscMax(c->max_nbr, cnt - c->nstart[a]);
  }
  c->nstart[n] = cnt;
  PetscFunctionReturn(PETSC_SUCCESS);
}
