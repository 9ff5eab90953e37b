/* Smoothing kernels, all of support radius 2h, in 2D and 3D:
 *   cubic        the cubic B-spline, Eq. 12 (the paper's, with h = 1.3 dx);
 *   wendland_c2  Wendland C2 (Dehnen & Aly 2012, Table 1): free of the pairing instability at any
 *                number of neighbours, so its discretisation error falls as h/dx grows;
 *   wendland_c4  Wendland C4: smoother, for larger h/dx.
 * With q = r / (2h) the Wendland kernels are sigma (1 - q)^4 (1 + 4q) and
 * sigma (1 - q)^6 (1 + 6q + 35/3 q^2).  For particles of different sizes the pair uses
 * h_ab = sqrt(h_a h_b) (section 3.3).  A run has one kernel and one h / dx (-kernel, -h_factor),
 * held by the simulation and handed to the modules that evaluate W. */
#pragma once
#include "base/base.h"
#include "base/dim.h" /* SPH_INLINE */

typedef enum { KERNEL_CUBIC = 0, KERNEL_WENDLAND_C2, KERNEL_WENDLAND_C4 } KernelType;
extern const char *const KernelTypes[];

#define SPH_H_FACTOR 1.3 /* the paper's h = 1.3 dx: the default of -h_factor (but Wendland C2's) */
#define SPH_H_FACTOR_WENDLAND_C2 1.4 /* the square lattice under pressure is stable (tools/lattice_stability.py) */

typedef struct {
  KernelType type;
  PetscInt   dim;      /* 2 or 3: the normalisation */
  PetscReal  h_factor; /* h / dx of particles made by the scenes */
  PetscReal  num, den; /* normalisation sigma(h) = num / (den pi h^dim) */
} SPHKernel;

static inline void KernelInit(SPHKernel *K, KernelType t, PetscInt dim, PetscReal h_factor)
{
  static const PetscReal num[3][2] = {{10.0, 1.0}, {7.0, 21.0}, {9.0, 495.0}}, den[3][2] = {{7.0, 1.0}, {4.0, 16.0}, {4.0, 256.0}};
  K->type = t; K->dim = dim; K->h_factor = h_factor;
  K->num = num[t][dim == 3]; K->den = den[t][dim == 3];
}

/* -h_factor's default for a kernel */
static inline PetscReal KernelDefaultHFactor(KernelType t) { return t == KERNEL_WENDLAND_C2 ? SPH_H_FACTOR_WENDLAND_C2 : SPH_H_FACTOR; }

/* The normalisation sigma(h); for the cubic spline in 2D the paper's 10 / (7 pi h^2) */
static inline PetscReal KernelSigma(const SPHKernel *K, PetscReal h) { return K->dim == 3 ? K->num / (K->den * PETSC_PI * h * h * h) : K->num / (K->den * PETSC_PI * h * h); }

/* The kernels, written once: W and F = (dW/dr) / r at R = r / h from the normalisations sw = sigma(h)
 * and sf = sw / h^2 (zero for R >= 2; F finite at R -> 0).  For the Wendland kernels, with q = R / 2,
 * dW/dq = -20 q (1-q)^3 sigma and -56/3 q (1 + 5q) (1-q)^5 sigma.  The terms evaluate it through
 * KernelW and KernelF (R = r / h); the neighbour list with R = r (1 / h) and the normalisations of
 * each particle computed once (cells.c), through KernelShapeList and KernelShapePair below. */
SPH_INLINE void KernelShape(const KernelType t, PetscReal R, PetscReal sw, PetscReal sf, PetscReal *w, PetscReal *f)
{
  *w = *f = 0.0;
  if (R >= 2.0) return;
  switch (t) {
  case KERNEL_CUBIC:
    if (R < 1.0) {
      *w = sw * (1.0 - 1.5 * R * R + 0.75 * R * R * R);
      *f = sf * (-3.0 + 2.25 * R);
    } else {
      PetscReal u = 2.0 - R;
      *w = sw * 0.25 * u * u * u;
      *f = -0.75 * sf * u * u / R;
    }
    break;
  case KERNEL_WENDLAND_C2: {
    PetscReal q = 0.5 * R, u = 1.0 - q, u2 = u * u;
    *w = sw * u2 * u2 * (1.0 + 4.0 * q);
    *f = -5.0 * sf * u * u * u;
  } break;
  case KERNEL_WENDLAND_C4: {
    PetscReal q = 0.5 * R, u = 1.0 - q, u2 = u * u, u3 = u * u * u;
    *w = sw * u3 * u3 * (1.0 + 6.0 * q + 35.0 / 3.0 * q * q);
    *f = -14.0 / 3.0 * sf * (1.0 + 5.0 * q) * u2 * u2 * u;
  } break;
  }
}

/* The same kernel without branches, for the neighbour list's loop over a particle's pairs (with t a
 * constant there, the loop vectorises: cells.c).  Its products are grouped as the list's have always
 * been, not as in KernelShape: the cubic's outer ring (2 - R)^2 first, the Wendland kernels' powers of
 * (1 - q) as u^3 u and u^5 u.  The two differ in the last bits (same R: the cubic's outer ring in 15 %
 * of the values, the Wendland kernels' in about half, by at most 3.4 eps relative; test_kernel
 * bounds it), and one grouping for both would change every run's results at round-off, so both are kept
 * (docs/performance.md). */
SPH_INLINE void KernelShapeList(const KernelType t, PetscReal R, PetscReal sw, PetscReal sf, PetscReal *w, PetscReal *f)
{
  switch (t) {
  case KERNEL_CUBIC: {
    PetscReal u = 2.0 - R, uu = u * u;
    PetscReal win = sw * (1.0 - 1.5 * R * R + 0.75 * R * R * R), fin = sf * (-3.0 + 2.25 * R);
    PetscReal wout = sw * 0.25 * uu * u, fout = -0.75 * sf * uu / (R > 0 ? R : 1.0);
    *w = R < 1.0 ? win : (R < 2.0 ? wout : 0.0);
    *f = R < 1.0 ? fin : (R < 2.0 ? fout : 0.0);
  } break;
  case KERNEL_WENDLAND_C2: {
    PetscReal q = 0.5 * R, u = q < 1.0 ? 1.0 - q : 0.0, u3 = u * u * u;
    *w = sw * u3 * u * (1.0 + 4.0 * q);
    *f = -5.0 * sf * u3;
  } break;
  case KERNEL_WENDLAND_C4: {
    PetscReal q = 0.5 * R, u = q < 1.0 ? 1.0 - q : 0.0, u2 = u * u, u5 = u2 * u2 * u;
    *w = sw * u5 * u * (1.0 + 6.0 * q + 35.0 / 3.0 * q * q);
    *f = -14.0 / 3.0 * sf * (1.0 + 5.0 * q) * u5;
  } break;
  default: *w = *f = 0.0;
  }
}

/* One pair of the neighbour list evaluated on its own (a pair of two smoothing lengths, or of a
 * particle that has one): the grouping these pairs have always had, KernelShape's for the cubic
 * spline and KernelShapeList's for the Wendland kernels, zero from R = 2. */
SPH_INLINE void KernelShapePair(const KernelType t, PetscReal R, PetscReal sw, PetscReal sf, PetscReal *w, PetscReal *f)
{
  if (R >= 2.0) *w = *f = 0.0;
  else if (t == KERNEL_CUBIC) KernelShape(t, R, sw, sf, w, f);
  else KernelShapeList(t, R, sw, sf, w, f);
}

/* W(r, h) */
static inline PetscReal KernelW(const SPHKernel *K, PetscReal r, PetscReal h)
{
  PetscReal R = r / h, s = KernelSigma(K, h), w, f;
  if (R >= 2.0) return 0.0; /* (before reading K->type: the terms' loops over far particles) */
  KernelShape(K->type, R, s, s / (h * h), &w, &f);
  return w;
}

/* F_ab = (dW/dr) / r, so that grad_a W_ab = F_ab (x_a - x_b) */
static inline PetscReal KernelF(const SPHKernel *K, PetscReal r, PetscReal h)
{
  PetscReal R = r / h, s = KernelSigma(K, h), w, f;
  if (R >= 2.0) return 0.0;
  KernelShape(K->type, R, s, s / (h * h), &w, &f);
  return f;
}

/* dW/dr(r, h); the gradient is grad_a W_ab = dW/dr * (x_a - x_b) / r, Eq. 15 */
static inline PetscReal KernelDW(const SPHKernel *K, PetscReal r, PetscReal h) { return KernelF(K, r, h) * r; }

static inline PetscReal PairH(PetscReal ha, PetscReal hb) { return ha == hb ? ha : PetscSqrtReal(ha * hb); }

/* Sums over one particle's neighbours on a full square (3D: cubic) lattice of spacing 1
 * (h = h_factor), the interior values that normalise the operators built on them:
 *   LATTICE_W:         sum W, the summation density (Eq. 17) per rho0;
 *   LATTICE_DIVR:      -sum F r^2, div r (d in the continuum);
 *   LATTICE_LAPLACIAN: -sum F r^4 / (r^2 + eta^2 h^2): the Laplacian of Eqs. 16 and 22 applied to
 *     |x|^2 is 2 / rho times this against the exact 2 d / rho, so d over it normalises them (the
 *     cubic spline at 1.3 dx in 2D: +1.05 % with eta = 0, -0.02 % with the paper's eta = 0.1 h;
 *     Wendland C2 at 2 dx: -0.08 % and -1.5 %).  eta is read only for this sum. */
typedef enum { LATTICE_W, LATTICE_DIVR, LATTICE_LAPLACIAN } LatticeSum;
static inline PetscReal KernelLatticeSum(const SPHKernel *K, LatticeSum which, PetscReal eta)
{
  PetscReal s = 0, h = K->h_factor;
  PetscInt  n = (PetscInt)PetscCeilReal(2.0 * h), nz = K->dim == 3 ? n : 0;
  for (PetscInt k = -nz; k <= nz; k++)
    for (PetscInt j = -n; j <= n; j++)
      for (PetscInt i = -n; i <= n; i++) {
        PetscReal r2 = (PetscReal)(i * i + j * j + k * k), r = PetscSqrtReal(r2);
        switch (which) {
        case LATTICE_W: s += KernelW(K, r, h); break;
        case LATTICE_DIVR: s += -KernelF(K, r, h) * r * r; break;
        case LATTICE_LAPLACIAN: if (r2 > 0) s -= KernelF(K, r, h) * r2 * r2 / (r2 + eta * eta * h * h); break;
        }
      }
  return s;
}

/* The largest diffusion coefficient D (in units of h^2) that Fickian shifting, dr = -D grad C with
 * grad C = sum_b V_b grad_a W_ab, can take without reversing any displacement mode of the lattice:
 * linearised, a mode of wave vector k changes by (I - D M(k)) each step, with
 * M(k) = sum_b V_b grad grad W(r_b) (1 - cos k . r_b); this returns 1 / (h^2 times the largest
 * eigenvalue of M over k in [0, pi]^dim, on a grid of pi/16).  Past it the modes near the largest
 * overshoot each step (a particle-scale oscillation that alternates from step to step), past twice
 * it they grow.  The largest is a mode of about 5 dx, not the checkerboard (which the cubic spline at
 * 1.3 dx hardly sees).  Cubic spline at 1.3 dx: 0.427 h^2 in 2D; test_kernel checks it against the
 * modes' response measured on the displaced lattice.  grad grad W = F I + r dF/dr n n, dF/dr by a
 * central difference (once, at set-up). */
static inline PetscReal KernelShiftCeiling(const SPHKernel *K)
{
  const PetscReal h = K->h_factor, dr = 1e-6 * h, dk = PETSC_PI / 16;
  const PetscInt  n = (PetscInt)PetscCeilReal(2.0 * h), D = K->dim, nz = D == 3 ? n : 0, nk = D == 3 ? 17 * 17 * 17 : 17 * 17;
  PetscReal       lmax = 0;
  for (PetscInt m = 1; m < nk; m++) { /* k = dk (m mod 17, m/17 mod 17, m/289): every mode but k = 0 */
    PetscReal kv[3] = {dk * (m % 17), dk * ((m / 17) % 17), dk * (m / 289)}, M[6] = {0, 0, 0, 0, 0, 0}, lo, hi;
    for (PetscInt c = -nz; c <= nz; c++)
      for (PetscInt j = -n; j <= n; j++)
        for (PetscInt i = -n; i <= n; i++) {
          PetscReal x[3] = {(PetscReal)i, (PetscReal)j, (PetscReal)c}, r = PetscSqrtReal(VDot(x, x, D)), F, dF, wgt;
          if (r == 0 || r >= 2.0 * h) continue;
          F   = KernelF(K, r, h);
          dF  = (KernelF(K, r + dr, h) - KernelF(K, r - dr, h)) / (2.0 * dr);
          wgt = 1.0 - PetscCosReal(VDot(kv, x, D));
          SymOuterSubtract(M, -wgt * dF / r, x, D); /* + wgt (dF / r) x (x) x */
          M[0] += wgt * F;
          if (D == 2) M[2] += wgt * F;
          else { M[3] += wgt * F; M[5] += wgt * F; }
        }
    SymEigenRange(M, &lo, &hi, D);
    lmax = PetscMax(lmax, hi);
  }
  return lmax > 0 ? 1.0 / (lmax * h * h) : PETSC_MAX_REAL;
}

/* Rows of wall particles that cover the kernel's support from the wall's face: ceil(2 h / dx) */
static inline PetscInt KernelSupportRows(const SPHKernel *K) { return (PetscInt)PetscCeilReal(2.0 * K->h_factor - 1e-9); }
