/* Fickian particle shifting shared by the ISPH and WCSPH schemes: dr = -A h |v| dt grad C
 * (Skillen et al. 2013), at most 0.1 h per step, none on the free surface and next to it (a fluid
 * neighbour on it).  grad C = sum_b V_b grad_a W_ab is the concentration gradient.  Lind et al.
 * (2012) keep the tangential part next to the surface; with the normal taken from the particle's
 * own grad C, as here, that part is zero. */
#pragma once
#include <sphfsi/kernel.h>
#include <sphfsi/dim.h>

typedef enum { SHIFT_BULK, SHIFT_NEAR_SURFACE, SHIFT_SURFACE } ShiftZone;

/* WCSPH: the free surface where div r, normalised to 2 in the bulk (in 2D and 3D), is below 1.5; on
 * a square lattice the surface row has 1.27, the row below 1.88 and the next 2.0 (the kernel's
 * support is 2.6 dx). */
#define SHIFT_DIVR_SURFACE 1.5

/* The shifting velocity dr/dt of a particle with smoothing length h, velocity v and concentration
 * gradient c over a step dt, in dim dimensions; adds it to xs. */
static inline void ShiftVelocity(PetscReal A, ShiftZone zone, PetscReal h, const PetscReal v[], PetscReal dt, const PetscReal c[], PetscReal xs[], const PetscInt dim)
{
  PetscReal speed = PetscSqrtReal(VDot(v, v, dim)), D = A * h * speed * dt, ds[3], len;
  if (A <= 0 || zone != SHIFT_BULK || dt <= 0) return;
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
  PetscReal M[3]; /* xx, xy, yy (symmetric) */
  PetscReal G[4]; /* row-major: G[i][j] = sum V (v_b - v_a)_i (grad_a W)_j */
} ShiftGrad;

/* pair with volume V, F = (dW/dr) / r, d = x_a - x_b, dv = v_a - v_b */
static inline void ShiftGradAdd(ShiftGrad *s, PetscReal V, PetscReal F, PetscReal dx, PetscReal dy, PetscReal dvx, PetscReal dvy)
{
  PetscReal c = V * F;
  s->M[0] -= c * dx * dx; s->M[1] -= c * dx * dy; s->M[2] -= c * dy * dy;
  s->G[0] -= c * dvx * dx; s->G[1] -= c * dvx * dy; s->G[2] -= c * dvy * dx; s->G[3] -= c * dvy * dy;
}

/* v += dr . grad v for the shift dr = dt * (shift velocity); none where M cannot be inverted. */
static inline void ShiftCorrectVelocity(const ShiftGrad *s, PetscReal drx, PetscReal dry, PetscReal v[2])
{
  PetscReal det = s->M[0] * s->M[2] - s->M[1] * s->M[1], ix, iy, jx, jy;
  if (!(det > 1e-6 * (s->M[0] * s->M[0] + s->M[2] * s->M[2])) || (drx == 0 && dry == 0)) return;
  /* w = M^-1 dr (M symmetric), then dv_i = sum_k G[i][k] w_k */
  ix = (s->M[2] * drx - s->M[1] * dry) / det;
  iy = (-s->M[1] * drx + s->M[0] * dry) / det;
  jx = s->G[0] * ix + s->G[1] * iy;
  jy = s->G[2] * ix + s->G[3] * iy;
  v[0] += jx; v[1] += jy;
}
