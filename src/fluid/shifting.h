/* Fickian particle shifting shared by the ISPH and WCSPH schemes: dr = -A h |v| dt grad C
 * (Skillen et al. 2013), with -fluid_shift_ceiling A h |v| dt at most dmax h^2 (KernelShiftCeiling:
 * beyond it the shift overshoots the lattice's short modes each step, an oscillation from step to
 * step that ISPH's forces on a body carry at A = 5 and CFL 0.25), at most 0.1 h per step, none on
 * the free surface and next to it (a fluid neighbour on it).  grad C = sum_b V_b grad_a W_ab is
 * the concentration gradient.  Lind et al. (2012) keep the tangential part next to the surface;
 * with the normal taken from the particle's own grad C, as here, that part is zero. */
#pragma once
#include "base/kernel.h"
#include "base/dim.h"

typedef enum { SHIFT_BULK, SHIFT_NEAR_SURFACE, SHIFT_SURFACE } ShiftZone;

/* WCSPH: the free surface where div r, normalised to 2 in the bulk (in 2D and 3D), is below 1.5; on
 * a square lattice the surface row has 1.27, the row below 1.88 and the next 2.0 (the kernel's
 * support is 2.6 dx). */
#define SHIFT_DIVR_SURFACE 1.5

/* The shifting velocity dr/dt of a particle with smoothing length h, velocity v and concentration
 * gradient c over a step dt, in dim dimensions, its speed taken at least vmin (-fluid_shift_speed),
 * the coefficient at most dmax h^2 (dmax 0: no ceiling); adds it to xs. */
static inline void ShiftVelocity(PetscReal A, PetscReal dmax, PetscReal vmin, ShiftZone zone, PetscReal h, const PetscReal v[], PetscReal dt, const PetscReal c[], PetscReal xs[], const PetscInt dim)
{
  PetscReal speed = PetscMax(PetscSqrtReal(VDot(v, v, dim)), vmin), D = A * h * speed * dt, ds[3], len;
  if (A <= 0 || zone != SHIFT_BULK || dt <= 0) return;
  if (dmax > 0) D = PetscMin(D, dmax * h * h);
  for (PetscInt i = 0; i < dim; i++) ds[i] = -D * c[i];
  len = PetscSqrtReal(VDot(ds, ds, dim));
  if (len > 0.1 * h)
    for (PetscInt i = 0; i < dim; i++) ds[i] *= 0.1 * h / len;
  for (PetscInt i = 0; i < dim; i++) xs[i] += ds[i] / dt;
}

/* The shifted particle carries its velocity to a new place: corrected to first order there,
 * v += dr . grad v (Xu et al. 2009, Lind et al. 2012), with grad v = G M^-1 from the fluid
 * neighbours, G = sum V_b (v_b - v_a) (x) grad_a W and M = sum V_b (x_b - x_a) (x) grad_a W (the
 * kernel-gradient correction, so that the gradient of a linear field is exact on any arrangement).
 * Accumulate pair by pair with ShiftGradAdd, then apply with ShiftCorrectVelocity. */
typedef struct {
  PetscReal M[6]; /* symmetric: 2D xx, xy, yy; 3D xx, xy, xz, yy, yz, zz */
  PetscReal G[9]; /* row-major D x D: G[i][j] = sum V (v_b - v_a)_i (grad_a W)_j */
} ShiftGrad;

/* pair with volume V, F = (dW/dr) / r, d = x_a - x_b, dv = v_a - v_b, in D dimensions */
static inline void ShiftGradAdd(ShiftGrad *s, PetscReal V, PetscReal F, const PetscReal d[], const PetscReal dv[], const PetscInt D)
{
  PetscReal c = V * F;
  SymOuterSubtract(s->M, c, d, D);
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt j = 0; j < D; j++) s->G[D * i + j] -= c * dv[i] * d[j];
}

/* v += dr . grad v for the shift dr = dt * (shift velocity); none where M cannot be inverted. */
static inline void ShiftCorrectVelocity(const ShiftGrad *s, const PetscReal dr[], PetscReal v[], const PetscInt D)
{
  PetscReal w[3];
  if (dr[0] == 0 && dr[1] == 0 && (D == 2 || dr[2] == 0)) return;
  if (D == 2) {
    PetscReal det = s->M[0] * s->M[2] - s->M[1] * s->M[1];
    if (!(det > 1e-6 * (s->M[0] * s->M[0] + s->M[2] * s->M[2]))) return;
    /* w = M^-1 dr (M symmetric), then dv_i = sum_k G[i][k] w_k */
    w[0] = (s->M[2] * dr[0] - s->M[1] * dr[1]) / det;
    w[1] = (-s->M[1] * dr[0] + s->M[0] * dr[1]) / det;
    v[0] += s->G[0] * w[0] + s->G[1] * w[1];
    v[1] += s->G[2] * w[0] + s->G[3] * w[1];
  } else {
    if (!SymSolveConditioned(s->M, dr, 0, w, 3)) return;
    for (PetscInt i = 0; i < 3; i++) v[i] += s->G[3 * i] * w[0] + s->G[3 * i + 1] * w[1] + s->G[3 * i + 2] * w[2];
  }
}
