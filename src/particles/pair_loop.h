/* Pair-loop drivers: the walk over one owned particle's pairs in a neighbour list, written once for
 * the loops that gather a pair term over them.  A term is a small function of one pair that adds to
 * the sums its context holds; the driver calls it for each pair in the list's order.  Driver and
 * term are always inlined (SPH_INLINE) into the loop over the particles, so the compiler still sees
 * one loop with the term's expressions as they were written, and the sums keep their order.
 *
 * Every pair loop of the code gathers: owned particle a sums over its own pairs (each pair is seen
 * from both ends, no a < b loop), in the order that cells.h fixes, so the sums agree whatever the
 * number of ranks.  The drivers are machinery: a term reads the pair, never the list.
 *   SPHPairs    F_ab of the pairs (any list: the main one, the solid's);
 *   SPHPairsW   F_ab and W_ab, W from CellsPairW (recomputed where the main list keeps none);
 *   SPHPairsSum a term that gives each pair's contribution instead of adding it, for the hot loops:
 *               the pairs are evaluated in a loop the compiler vectorises, then summed in order. */
#pragma once
#include "particles/cells.h"
#include "base/dim.h"

/* One pair (a, b) of a list, as a driver hands it to a term. */
typedef struct {
  PetscInt  b; /* the neighbour, owned or ghost */
  PetscInt  k; /* the pair's index in the list: per-pair arrays of that list (a solid's f0) */
  PetscReal F; /* F_ab = (dW/dr) / r, so that grad_a W_ab = F_ab (x_a - x_b) */
  PetscReal W; /* W_ab (SPHPairsW; 0 from SPHPairs) */
} SPHPair;

/* A term: adds pair p of owned particle a to what ctx gathers, in D (a constant) dimensions. */
typedef void (*SPHPairTerm)(void *ctx, PetscInt a, SPHPair p, const PetscInt D);

/* term(ctx, a, p, D) for each pair p of owned particle a in list C. */
SPH_INLINE void SPHPairs(Cells C, PetscInt a, SPHPairTerm term, void *ctx, const PetscInt D)
{
  for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
    SPHPair p = {C->nbr[k], k, C->f[k], 0};
    term(ctx, a, p, D);
  }
}

/* The same with W_ab when with_w (else as SPHPairs: no kernel evaluation where the term reads no W). */
SPH_INLINE void SPHPairsW(Cells C, Particles P, PetscInt a, PetscBool with_w, SPHPairTerm term, void *ctx, const PetscInt D)
{
  const PetscReal *w;
  PetscInt         s;
  if (!with_w) {
    SPHPairs(C, a, term, ctx, D);
    return;
  }
  w = CellsPairW(C, P, a);
  s = C->nstart[a];
  for (PetscInt k = s; k < C->nstart[a + 1]; k++) {
    SPHPair p = {C->nbr[k], k, C->f[k], w[k - s]};
    term(ctx, a, p, D);
  }
}

/* A term that gives pair p's contribution to the nout sums of owned particle a in out[0 .. nout)
 * instead of adding it (SPHPairsSum).  It reads ctx and the pair only, so the pairs are independent. */
typedef void (*SPHPairValue)(const void *ctx, PetscInt a, SPHPair p, PetscReal *out, const PetscInt D);

#define SPH_PAIR_SUM_MAX 4 /* most sums an SPHPairValue term gives */

/* sum[o] += the term's out[o] over the pairs of owned particle a in list C: the same sums, in the same
 * order, as a term adding out to them in SPHPairs.  Two loops: the pairs' values into scratch (nout
 * rows of C->max_nbr), a loop whose iterations are independent, so the compiler vectorises it over
 * the pairs (gathering b's fields; -fopt-info-vec), then the sums in the list's order. */
SPH_INLINE void SPHPairsSum(Cells C, PetscInt a, SPHPairValue term, const void *ctx, const PetscInt nout, PetscReal *restrict scratch, PetscReal *sum, const PetscInt D)
{
  const PetscInt   k0 = C->nstart[a], nk = C->nstart[a + 1] - k0, cap = C->max_nbr;
  const PetscInt  *nbr = C->nbr + k0;
  const PetscReal *f   = C->f + k0;
#pragma GCC ivdep
  for (PetscInt j = 0; j < nk; j++) {
    PetscReal out[SPH_PAIR_SUM_MAX];
    SPHPair   p = {nbr[j], k0 + j, f[j], 0};
    term(ctx, a, p, out, D);
    for (PetscInt o = 0; o < nout; o++) scratch[o * cap + j] = out[o];
  }
  for (PetscInt j = 0; j < nk; j++)
    for (PetscInt o = 0; o < nout; o++) sum[o] += scratch[o * cap + j];
}
