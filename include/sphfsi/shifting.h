/* Fickian particle shifting shared by the ISPH and WCSPH schemes: dr = -A h |v| dt grad C
 * (Skillen et al. 2013), at most 0.1 h per step, none on the free surface and next to it (a fluid
 * neighbour on it).  grad C = sum_b V_b grad_a W_ab is the concentration gradient.  Lind et al.
 * (2012) keep the tangential part next to the surface; with the normal taken from the particle's
 * own grad C, as here, that part is zero. */
#pragma once
#include <sphfsi/kernel.h>

typedef enum { SHIFT_BULK, SHIFT_NEAR_SURFACE, SHIFT_SURFACE } ShiftZone;

/* WCSPH: the free surface where div r (normalised to 2 in the bulk) < 1.5; on a square lattice the
 * surface row has 1.27, the row below 1.88 and the next 2.0 (the kernel's support is 2.6 dx). */
#define SHIFT_DIVR_SURFACE 1.5

/* The shifting velocity dr/dt of a particle with smoothing length h, velocity v and concentration
 * gradient (cx, cy) over a step dt; adds it to xs[0..1]. */
static inline void ShiftVelocity(PetscReal A, ShiftZone zone, PetscReal h, const PetscReal v[2], PetscReal dt, PetscReal cx, PetscReal cy, PetscReal xs[2])
{
  PetscReal speed = PetscSqrtReal(v[0] * v[0] + v[1] * v[1]), D = A * h * speed * dt, dxs = -D * cx, dys = -D * cy, len;
  if (A <= 0 || zone != SHIFT_BULK || dt <= 0) return;
  len = PetscSqrtReal(dxs * dxs + dys * dys);
  if (len > 0.1 * h) { dxs *= 0.1 * h / len; dys *= 0.1 * h / len; }
  xs[0] += dxs / dt; xs[1] += dys / dt;
}
