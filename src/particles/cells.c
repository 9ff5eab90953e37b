#include "particles/cells.h"
#include "base/kernel.h"
#include "base/dim.h"
#include <math.h>

PetscErrorCode CellsCreate(const Grid *g, const SPHKernel *K, Cells *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(c));
  (*c)->grid   = g;
  (*c)->kernel = K;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellsCreateList(const SPHKernel *K, Cells *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(c));
  (*c)->kernel = K;
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
  PetscCall(PetscFree((*c)->wet));
  PetscCall(PetscFree2((*c)->cstart, (*c)->cnbr));
  PetscCall(PetscFree((*c)->wrow)); /* two allocations, not one PetscMalloc2 */
  PetscCall(PetscFree((*c)->xk));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Local cell of cell coordinates (i, j, k) (k = 0 in 2D) */
static inline PetscInt LocalCell(Cells c, PetscInt i, PetscInt j, PetscInt k) { return ((k - c->lo[2]) * c->n[1] + (j - c->lo[1])) * c->n[0] + (i - c->lo[0]); }

/* The range of cell coordinates of n particles (D a constant: the loops unroll) */
SPH_INLINE void CellRange(const Grid *g, const PetscReal *x, PetscInt n, PetscInt imin[], PetscInt imax[], const PetscInt D)
{
  for (PetscInt a = 0; a < n; a++)
    for (PetscInt d = 0; d < D; d++) {
      PetscInt k = GridCoord(g, x[D * a + d], d);
      imin[d] = PetscMin(imin[d], k); imax[d] = PetscMax(imax[d], k);
    }
}

/* Each particle's local cell, and the counts per cell in start[cell + 1] */
SPH_INLINE void BinParticles(Cells c, const PetscReal *x, PetscInt n, const PetscInt D)
{
  const Grid *g = c->grid;
  for (PetscInt a = 0; a < n; a++) {
    c->cell[a] = LocalCell(c, GridCoord(g, x[D * a], 0), GridCoord(g, x[D * a + 1], 1), D == 3 ? GridCoord(g, x[D * a + 2], 2) : 0);
    c->start[c->cell[a] + 1]++;
  }
}

static PetscErrorCode NeighbourPass(Cells, Particles, PetscBool (*)(PetscInt), PetscReal, Cells);
static PetscErrorCode KeepCandidates(Cells);

PetscErrorCode CellsBuild(Cells c, Particles P)
{
  const Grid      *g = c->grid;
  const PetscReal *x = PField(P, FIELD_X);
  const PetscInt   D = g->dim;
  PetscInt         ntot = P->n + P->ng, imin[3] = {PETSC_MAX_INT, PETSC_MAX_INT, 0}, imax[3] = {PETSC_MIN_INT, PETSC_MIN_INT, 0}, nc;

  PetscFunctionBeginUser;
  if (ntot > c->cap_part) {
    PetscCall(PetscFree2(c->list, c->cell));
    c->cap_part = (3 * ntot) / 2 + 16;
    PetscCall(PetscMalloc2(c->cap_part, &c->list, c->cap_part, &c->cell));
  }
  if (D == 3) { imin[2] = PETSC_MAX_INT; imax[2] = PETSC_MIN_INT; }
  SPH_DIM_DISPATCH(D, CellRange, g, x, ntot, imin, imax);
  if (!ntot)
    for (PetscInt d = 0; d < 3; d++) imin[d] = imax[d] = 0;
  for (PetscInt d = 0; d < 3; d++) { c->lo[d] = imin[d]; c->n[d] = imax[d] - imin[d] + 1; }
  nc = c->n[0] * c->n[1] * c->n[2];
  if (nc + 1 > c->cap_cell) {
    PetscCall(PetscFree(c->start));
    c->cap_cell = (3 * (nc + 1)) / 2;
    PetscCall(PetscMalloc1(c->cap_cell, &c->start));
  }
  /* counting sort by cell */
  PetscCall(PetscArrayzero(c->start, nc + 1));
  SPH_DIM_DISPATCH(D, BinParticles, c, x, ntot);
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
  if (c->skin > 0) {
    PetscCall(NeighbourPass(c, P, NULL, c->skin, c));
    PetscCall(KeepCandidates(c));
    PetscCall(CellsRefreshPairs(c, P));
  } else PetscCall(CellsBuildNeighbours(c, P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Kernel values of n pairs of smoothing length h (ih = 1 / h) from their r^2, stored in w: kernel.h's
 * KernelShapeList, the kernel t a constant in each loop (UniformPairKernels), so that the compiler
 * can vectorise the square roots and divisions. */
SPH_INLINE void UniformPairKernelsT(PetscReal *restrict w, PetscReal *restrict f, PetscInt n, PetscReal ih, PetscReal sw, PetscReal sf, const KernelType t)
{
  for (PetscInt k = 0; k < n; k++) KernelShapeList(t, PetscSqrtReal(w[k]) * ih, sw, sf, &w[k], &f[k]);
}

/* Neither inlined nor cloned (noipa): the build and CellsPairW run the same instructions. */
static __attribute__((noipa)) void UniformPairKernels(KernelType type, PetscReal *restrict w, PetscReal *restrict f, PetscInt n, PetscReal ih, PetscReal sw, PetscReal sf)
{
  switch (type) {
  case KERNEL_CUBIC: UniformPairKernelsT(w, f, n, ih, sw, sf, KERNEL_CUBIC); break;
  case KERNEL_WENDLAND_C2: UniformPairKernelsT(w, f, n, ih, sw, sf, KERNEL_WENDLAND_C2); break;
  case KERNEL_WENDLAND_C4: UniformPairKernelsT(w, f, n, ih, sw, sf, KERNEL_WENDLAND_C4); break;
  }
}

/* Make room for `more` pairs after the first `cnt` of a list, filled for particles [0, a) of n: the
 * new capacity adds what the rest of the list needs at the mean so far (+15 %), and at least a
 * quarter of the old capacity, so that the copies stay rare.  (Not doubling: with PETSc's heap, which superlu_dist
 * keeps from returning memory to the system, a freed block stays resident; doubling a 3D list once
 * left a hole of a third of the list in the peak memory.) */
static PetscErrorCode ReserveNeighbours(Cells out, PetscInt cnt, PetscInt more, PetscInt a, PetscInt n)
{
  PetscInt  *nb, need;
  PetscReal *nw, *nf;
  PetscFunctionBeginUser;
  if (cnt + more <= out->cap_nbr) PetscFunctionReturn(PETSC_SUCCESS);
  need         = (PetscInt)(1.15 * (PetscReal)cnt / (PetscReal)PetscMax(a, 1) * (PetscReal)(n - a));
  out->cap_nbr = cnt + more + PetscMax(need, out->cap_nbr / 4);
  PetscCall(PetscMalloc3(out->cap_nbr, &nb, out->drop_w ? 1 : out->cap_nbr, &nw, out->cap_nbr, &nf));
  PetscCall(PetscArraycpy(nb, out->nbr, cnt));
  if (!out->drop_w) PetscCall(PetscArraycpy(nw, out->w, cnt));
  PetscCall(PetscArraycpy(nf, out->f, cnt));
  PetscCall(PetscFree3(out->nbr, out->w, out->f));
  out->nbr = nb; out->w = nw; out->f = nf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* W and F of a pair of smoothing lengths ha and hb at r^2, with the pair's h_ab (Eq. 13's mean). */
static inline void OtherHPairKernel(const SPHKernel *K, PetscReal ha, PetscReal hb, PetscReal r2, PetscReal *w, PetscReal *f)
{
  PetscReal hab = PairH(ha, hb), sw = KernelSigma(K, hab);
  KernelShapePair(K->type, PetscSqrtReal(r2) * (1.0 / hab), sw, sw / (hab * hab), w, f);
}

/* Kernel values of particle a's n pairs (nbr, w, f from a's first pair): the pairs of a's own h hold
 * r^2 in w (evaluated here, vectorised when all are), those of another h their values already. */
static inline void OwnPairKernels(KernelType type, const PetscReal *h, PetscReal ha, const PetscInt *nbr, PetscReal *w, PetscReal *f, PetscInt n, PetscBool mixed, PetscReal iha, PetscReal swa, PetscReal sfa)
{
  if (!mixed) UniformPairKernels(type, w, f, n, iha, swa, sfa);
  else
    for (PetscInt k = 0; k < n; k++)
      if (h[nbr[k]] == ha) KernelShapePair(type, PetscSqrtReal(w[k]) * iha, swa, sfa, &w[k], &f[k]);
}

/* Room for one particle's n pair values in the W/F scratch of drop_w. */
static PetscErrorCode ReserveRow(Cells c, PetscInt n)
{
  PetscFunctionBeginUser;
  if (!c->drop_w || n <= c->cap_wrow) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree(c->wrow));
  c->cap_wrow = 2 * n + 64;
  PetscCall(PetscMalloc1(2 * c->cap_wrow, &c->wrow));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* drop_w: the positions (owned and ghosts) at which the list's kernel values were just evaluated. */
static PetscErrorCode KeepKernelPositions(Cells c, Particles P)
{
  PetscInt m = P->dim * (P->n + P->ng);
  PetscFunctionBeginUser;
  if (!c->drop_w) PetscFunctionReturn(PETSC_SUCCESS);
  if (m > c->cap_xk) {
    PetscCall(PetscFree(c->xk));
    c->cap_xk = (3 * m) / 2 + 16;
    PetscCall(PetscMalloc1(c->cap_xk, &c->xk));
  }
  PetscCall(PetscArraycpy(c->xk, PField(P, FIELD_X), m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |x_a - x_b|^2 in D dimensions (D a constant where it is called, so that it unrolls); in 2D the
 * compiler's contraction of dx dx + dy dy from before, bit for bit. */
SPH_INLINE PetscReal PairDistance2(const PetscReal *restrict x, const PetscReal xa[], PetscInt b, const PetscInt D)
{
  PetscReal dx = xa[0] - x[D * b], dy = xa[1] - x[D * b + 1], r2 = fma(dy, dy, dx * dx);
  if (D == 3) {
    PetscReal dz = xa[2] - x[D * b + 2];
    r2 = fma(dz, dz, r2);
  }
  return r2;
}

/* Pairs (a, b) of one candidate range list[s0 .. s1) of particles with a's smoothing length:
 * r^2 into w (the kernel follows for all of a's pairs at once); returns the new count.  Every
 * candidate is stored and kept if it is a pair: in a splashing flow one candidate in three is a
 * pair, in no order a branch predictor learns, and this runs twice as fast as a test per
 * candidate (7 % slower on the initial lattice, where the test is predictable). */
SPH_INLINE PetscInt UniformCandidates(const PetscInt *restrict list, PetscInt s0, PetscInt s1, const PetscReal *restrict x, PetscInt a, const PetscReal xa[], PetscReal rc2, PetscInt *restrict nbr, PetscReal *restrict wb, PetscInt cnt, const PetscInt D)
{
  PetscInt *nb = nbr + cnt; /* pointers advanced by the test: no index to widen in the loop's chain; wb: where pair cnt's r^2 goes */
  for (PetscInt s = s0; s < s1; s++) {
    PetscInt b = list[s];
    PetscReal r2 = PairDistance2(x, xa, b, D);
    size_t    keep = (size_t)((b != a) & (r2 < rc2));
    *wb = r2;
    *nb = b;
    wb += keep;
    nb += keep;
  }
  return (PetscInt)(nb - nbr);
}

/* The candidate ranges of owned particle a in the binning c: the rows of its 3 (2D) or 9 (3D) stencil
 * rows of three cells, and their total.  Returns whether a is `dry` (a wall of the main list) and
 * no cell of its stencil holds fluid: then it gets no list. */
SPH_INLINE PetscBool StencilRows(Cells c, PetscInt a, PetscBool dry, PetscInt r0[9], PetscInt r1[9], PetscInt *nrow, PetscInt *ncand, const PetscInt D)
{
  PetscInt ca = c->cell[a], ia = ca % c->n[0], ja = ca / c->n[0], ka = 0;
  *nrow = 0; *ncand = 0;
  if (D == 3) { ka = ja / c->n[1]; ja = ja % c->n[1]; } /* (2D: one layer, no division) */
  for (PetscInt dk = D == 3 ? -1 : 0; dk <= (D == 3 ? 1 : 0); dk++) {
    PetscInt k = ka + dk;
    if (k < 0 || k >= c->n[2]) continue;
    for (PetscInt dj = -1; dj <= 1; dj++) {
      PetscInt j = ja + dj, i0 = PetscMax(ia - 1, 0), i1 = PetscMin(ia + 1, c->n[0] - 1), row = (k * c->n[1] + j) * c->n[0];
      if (j < 0 || j >= c->n[1]) continue;
      r0[*nrow] = c->start[row + i0];
      r1[*nrow] = c->start[row + i1 + 1];
      *ncand += r1[*nrow] - r0[*nrow];
      (*nrow)++;
      for (PetscInt i = i0; i <= i1 && dry; i++) dry = (PetscBool)!c->wet[row + i];
    }
  }
  return dry;
}

/* Neighbour list into `out` of the owned particles that `keep` accepts (NULL: all), using the
 * binning of `bins`: pairs with r < 2 h_ab + skin, kernel values at r (zero beyond 2 h_ab).
 * Pairs of equal h (the usual case) use the cut-off and kernel normalisation of particle a.
 * The three cells of a stencil row are consecutive in the binning, so each row (3 in 2D, 9 in 3D)
 * is one range of candidates, visited in the order of the cells and, within a cell, of the ids. */
SPH_INLINE PetscErrorCode NeighbourPassD(Cells bins, Particles P, PetscBool (*keep)(PetscInt), PetscReal skin, Cells out, const PetscInt D)
{
  Cells            c = bins;
  const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
  const PetscInt  *list = c->list;
  PetscInt         n = P->n, ntot = P->n + P->ng, cnt = 0;
  PetscBool        uniform = PETSC_TRUE; /* one smoothing length for owned and ghosts: no h per candidate */
  const SPHKernel *K = out->kernel;

  PetscFunctionBeginUser;
  if (n + 1 > out->cap_start) {
    PetscCall(PetscFree(out->nstart));
    out->cap_start = (3 * (n + 1)) / 2 + 16;
    PetscCall(PetscMalloc1(out->cap_start, &out->nstart));
  }
  for (PetscInt a = 1; a < ntot && uniform; a++) uniform = (PetscBool)(h[a] == h[0]);
  out->max_nbr = 0;
  out->uniform = uniform;
  if (!keep) { /* the main list: a wall or dummy particle with no fluid in its cells' reach gets none (its
                * list would hold no fluid, and only its fluid pairs are ever used: half the particles
                * of a 3D tank are such walls) */
    PetscInt nc = c->n[0] * c->n[1] * c->n[2];
    if (nc > c->cap_wet) {
      PetscCall(PetscFree(c->wet));
      c->cap_wet = (3 * nc) / 2 + 16;
      PetscCall(PetscMalloc1(c->cap_wet, &c->wet));
    }
    PetscCall(PetscArrayzero(c->wet, nc));
    for (PetscInt a = 0; a < ntot; a++)
      if (KindIsFluid(P->kind[a])) c->wet[c->cell[a]] = PETSC_TRUE;
  }
  if (!out->nbr) { /* the first list: sized from the candidates, a sphere of the cut-off's volume in their cells' */
    PetscReal est = 0, cells = PetscPowRealInt(3.0 * c->grid->cs, D), ball = D == 3 ? 4.0 / 3.0 * PETSC_PI : PETSC_PI;
    PetscInt  most = 0;
    for (PetscInt a = 0; a < n; a++) {
      PetscInt r0[9], r1[9], nrow, ncand;
      if ((keep && !keep(P->kind[a])) || StencilRows(c, a, (PetscBool)(!keep && KindIsWall(P->kind[a])), r0, r1, &nrow, &ncand, D)) continue;
      est += ncand * ball * PetscPowRealInt(2.0 * h[a] + skin, D) / cells;
      most = PetscMax(most, ncand);
    }
    out->cap_nbr = PetscMax(64, (PetscInt)(1.5 * est) + most); /* pages never written are not resident */
    PetscCall(PetscMalloc3(out->cap_nbr, &out->nbr, out->drop_w ? 1 : out->cap_nbr, &out->w, out->cap_nbr, &out->f));
  }
  for (PetscInt a = 0; a < n; a++) {
    PetscInt  r0[9], r1[9], nrow, ncand;
    PetscReal xa[3] = {x[D * a], x[D * a + 1], D == 3 ? x[D * a + 2] : 0}, ha = h[a], rca = 2.0 * ha + skin, rc2a = rca * rca;
    PetscReal swa = KernelSigma(K, ha), sfa = swa / (ha * ha), iha = 1.0 / ha;
    PetscBool mixed = PETSC_FALSE; /* a pair of another h: its kernel values are already in place */
    PetscInt  *nbr, first = cnt; /* a's first pair */
    PetscReal *wa, *f; /* wa: a's r^2 and W, in the list or (drop_w) in the scratch */
    out->nstart[a] = cnt;
    if (keep && !keep(P->kind[a])) continue;
    if (StencilRows(c, a, (PetscBool)(!keep && KindIsWall(P->kind[a])), r0, r1, &nrow, &ncand, D)) continue;
    PetscCall(ReserveNeighbours(out, cnt, ncand, a, n));
    PetscCall(ReserveRow(out, ncand));
    nbr = out->nbr; f = out->f; wa = out->drop_w ? out->wrow : out->w + first;
    for (PetscInt r = 0; r < nrow; r++) {
      if (uniform) {
        cnt = UniformCandidates(list, r0[r], r1[r], x, a, xa, rc2a, nbr, wa + (cnt - first), cnt, D);
        continue;
      }
      for (PetscInt s = r0[r]; s < r1[r]; s++) {
        PetscInt  b = list[s];
        PetscReal r2 = PairDistance2(x, xa, b, D);
        if (h[b] == ha) {
          if (b == a || !(r2 < rc2a)) continue;
          wa[cnt - first] = r2;
        } else {
          PetscReal rc = 2.0 * PairH(ha, h[b]) + skin;
          if (b == a || !(r2 < rc * rc)) continue;
          OtherHPairKernel(K, ha, h[b], r2, &wa[cnt - first], &f[cnt]);
          mixed = PETSC_TRUE;
        }
        nbr[cnt++] = b;
      }
    }
    OwnPairKernels(K->type, h, ha, nbr + first, wa, f + first, cnt - first, mixed, iha, swa, sfa);
    out->max_nbr = PetscMax(out->max_nbr, cnt - first);
  }
  out->nstart[n] = cnt;
  out->npart     = n;
  PetscCall(KeepKernelPositions(out, P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode NeighbourPass(Cells bins, Particles P, PetscBool (*keep)(PetscInt), PetscReal skin, Cells out) { return SPH_DIM_DISPATCH(P->dim, NeighbourPassD, bins, P, keep, skin, out); }

PetscErrorCode CellsBuildNeighbours(Cells c, Particles P)
{
  PetscFunctionBeginUser;
  PetscCall(NeighbourPass(c, P, NULL, 0.0, c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellsBuildSubList(Cells c, Particles P, PetscBool (*keep)(PetscInt), PetscReal skin, Cells sub)
{
  PetscFunctionBeginUser;
  PetscCall(NeighbourPass(c, P, keep, skin, sub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode UpdatePairs(Cells sub, Particles P, PetscBool with_w)
{
  const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
  const PetscInt   D = P->dim;
  PetscFunctionBeginUser;
  PetscCheck(!sub->drop_w || !with_w, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "CellsUpdatePairs needs a list that keeps W");
  for (PetscInt a = 0; a < sub->npart; a++)
    for (PetscInt k = sub->nstart[a]; k < sub->nstart[a + 1]; k++) {
      PetscInt  b = sub->nbr[k];
      PetscReal dx = x[D * a] - x[D * b], dy = x[D * a + 1] - x[D * b + 1], r2 = dx * dx + dy * dy, r, hab = PairH(h[a], h[b]);
      if (D == 3) r2 += (x[D * a + 2] - x[D * b + 2]) * (x[D * a + 2] - x[D * b + 2]);
      r = PetscSqrtReal(r2);
      if (with_w) sub->w[k] = KernelW(sub->kernel, r, hab);
      sub->f[k] = KernelF(sub->kernel, r, hab);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellsUpdatePairs(Cells sub, Particles P) { return UpdatePairs(sub, P, PETSC_TRUE); }
PetscErrorCode CellsUpdatePairsF(Cells sub, Particles P) { return UpdatePairs(sub, P, PETSC_FALSE); }

/* The list just built (r < 2 h_ab + skin) becomes the candidates. */
static PetscErrorCode KeepCandidates(Cells c)
{
  PetscInt n = c->npart, m = c->nstart[n];
  PetscFunctionBeginUser;
  if (n + 1 > c->cap_cstart || m > c->cap_cnbr) {
    PetscCall(PetscFree2(c->cstart, c->cnbr));
    c->cap_cstart = PetscMax(c->cap_cstart, (3 * (n + 1)) / 2 + 16);
    c->cap_cnbr   = PetscMax(c->cap_cnbr, (3 * m) / 2 + 16);
    PetscCall(PetscMalloc2(c->cap_cstart, &c->cstart, c->cap_cnbr, &c->cnbr));
  }
  PetscCall(PetscArraycpy(c->cstart, c->nstart, n + 1));
  PetscCall(PetscArraycpy(c->cnbr, c->nbr, m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The candidates within 2 h_ab at the current positions, in their order, with the kernel values
 * NeighbourPassD gives a build without skin (the same cut-off tests and kernel evaluations).  The
 * list never outgrows the candidates, whose arrays it held. */
SPH_INLINE void RefreshPairsD(Cells c, Particles P, const PetscInt D)
{
  const PetscReal *x = PField(P, FIELD_X), *h = PField(P, FIELD_H);
  const SPHKernel *K = c->kernel;
  PetscInt         cnt = 0;
  c->max_nbr = 0;
  for (PetscInt a = 0; a < c->npart; a++) {
    PetscReal ha = h[a], rca = 2.0 * ha, rc2a = rca * rca, swa = KernelSigma(K, ha), sfa = swa / (ha * ha), iha = 1.0 / ha;
    PetscReal xa[3] = {x[D * a], x[D * a + 1], D == 3 ? x[D * a + 2] : 0};
    PetscBool  mixed = PETSC_FALSE;
    PetscInt   s     = cnt;
    PetscReal *wa    = c->drop_w ? c->wrow : c->w + s; /* the scratch holds the build's candidates, so any subset */
    c->nstart[a] = cnt;
    if (c->uniform) { /* the build's branch-free filter (UniformCandidates), with a never among the candidates */
      cnt = UniformCandidates(c->cnbr, c->cstart[a], c->cstart[a + 1], x, -1, xa, rc2a, c->nbr, wa, cnt, D);
      OwnPairKernels(K->type, h, ha, c->nbr + s, wa, c->f + s, cnt - s, PETSC_FALSE, iha, swa, sfa);
      c->max_nbr = PetscMax(c->max_nbr, cnt - s);
      continue;
    }
    for (PetscInt k = c->cstart[a]; k < c->cstart[a + 1]; k++) {
      PetscInt  b  = c->cnbr[k];
      PetscReal r2 = PairDistance2(x, xa, b, D);
      if (h[b] == ha) {
        if (!(r2 < rc2a)) continue;
        wa[cnt - s] = r2;
      } else {
        PetscReal rc = 2.0 * PairH(ha, h[b]);
        if (!(r2 < rc * rc)) continue;
        OtherHPairKernel(K, ha, h[b], r2, &wa[cnt - s], &c->f[cnt]);
        mixed = PETSC_TRUE;
      }
      c->nbr[cnt++] = b;
    }
    OwnPairKernels(K->type, h, ha, c->nbr + s, wa, c->f + s, cnt - s, mixed, iha, swa, sfa);
    c->max_nbr = PetscMax(c->max_nbr, cnt - s);
  }
  c->nstart[c->npart] = cnt;
}

PetscErrorCode CellsRefreshPairs(Cells c, Particles P)
{
  PetscFunctionBeginUser;
  PetscCheck(c->skin > 0 && c->cstart, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "CellsRefreshPairs needs a list built with a skin");
  SPH_DIM_DISPATCH(P->dim, RefreshPairsD, c, P);
  PetscCall(KeepKernelPositions(c, P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* W of a's pairs again, as NeighbourPassD and RefreshPairsD evaluated them: r^2 from the same
 * positions, the pairs of another h by KernelShapePair, a's own by OwnPairKernels. */
SPH_INLINE const PetscReal *PairWD(Cells c, Particles P, PetscInt a, const PetscInt D)
{
  const PetscReal *x = c->xk, *h = PField(P, FIELD_H);
  const SPHKernel *K = c->kernel;
  const PetscInt   s = c->nstart[a], n = c->nstart[a + 1] - s, *nbr = c->nbr + s;
  PetscReal        ha = h[a], swa = KernelSigma(K, ha), xa[3] = {0, 0, 0};
  PetscReal       *w = c->wrow, *f;
  PetscBool        mixed = PETSC_FALSE;
  if (!n) return w; /* (no scratch yet on a rank whose particles have no pairs) */
  f = w + c->cap_wrow;
  for (PetscInt i = 0; i < D; i++) xa[i] = x[D * a + i];
  for (PetscInt j = 0; j < n; j++) {
    PetscInt  b  = nbr[j];
    PetscReal r2 = PairDistance2(x, xa, b, D);
    if (h[b] == ha) w[j] = r2;
    else {
      OtherHPairKernel(K, ha, h[b], r2, &w[j], &f[j]);
      mixed = PETSC_TRUE;
    }
  }
  OwnPairKernels(K->type, h, ha, nbr, w, f, n, mixed, 1.0 / ha, swa, swa / (ha * ha));
  return w;
}

const PetscReal *CellsPairW(Cells c, Particles P, PetscInt a)
{
  if (!c->drop_w) return c->w + c->nstart[a];
  return SPH_DIM_DISPATCH(P->dim, PairWD, c, P, a);
}
