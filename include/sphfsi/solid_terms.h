/* Per-particle and per-pair terms of the hypo-elastic solid (section 2.4). */
#pragma once
#include <sphfsi/base.h>

/* Eqs. 25-34 (Monaghan 2000; Gray, Monaghan & Swift 2001): artificial stress R (xx, xy, yy) of a
 * particle of total stress sigma = -P I + S.  In the principal frame (Eq. 29) a tensile principal
 * stress gets R = -e sigma / rho^2; rotated back by Eqs. 32-34.  Eq. 28 is printed with +2sc; the
 * rotation that keeps the trace needs -2sc (Gray et al. 2001, Eq. 4.10). */
static inline void ArtificialStress(PetscReal e, PetscReal sxx, PetscReal sxy, PetscReal syy, PetscReal rho, PetscReal R[3])
{
  PetscReal th = 0.5 * PetscAtan2Real(2.0 * sxy, sxx - syy), c = PetscCosReal(th), s = PetscSinReal(th);
  PetscReal c2 = c * c, s2 = s * s, cs = c * s;
  PetscReal pxx = c2 * sxx + 2.0 * cs * sxy + s2 * syy, pyy = s2 * sxx - 2.0 * cs * sxy + c2 * syy;
  PetscReal rxx = pxx > 0 ? -e * pxx / (rho * rho) : 0.0, ryy = pyy > 0 ? -e * pyy / (rho * rho) : 0.0;
  R[0] = c2 * rxx + s2 * ryy;
  R[1] = cs * (rxx - ryy);
  R[2] = s2 * rxx + c2 * ryy;
}

/* Eq. 40: S^{n+1} = S^n + dt [2 G (D - tr(D)/3 I) + S^{n+1} W^T + W S^{n+1}] with the spin
 * W_xy = -W_yx = w (Eqs. 38-39), solved in closed form for S^{n+1} (xx, xy, yy).  The rotation is
 * implicit as the paper writes it; a rigid rotation (D = 0) leaves S = 0 unchanged. */
static inline void JaumannUpdate(PetscReal G, PetscReal dt, PetscReal Dxx, PetscReal Dxy, PetscReal Dyy, PetscReal w, PetscReal S[3])
{
  PetscReal tr3 = (Dxx + Dyy) / 3.0, a = w * dt;
  PetscReal rxx = S[0] + dt * 2.0 * G * (Dxx - tr3), rxy = S[1] + dt * 2.0 * G * Dxy, ryy = S[2] + dt * 2.0 * G * (Dyy - tr3);
  /* Sxx' = rxx + 2a Sxy',  Syy' = ryy - 2a Sxy',  Sxy' = rxy + a (Syy' - Sxx') */
  PetscReal sxy = (rxy + a * (ryy - rxx)) / (1.0 + 4.0 * a * a);
  S[0] = rxx + 2.0 * a * sxy;
  S[1] = sxy;
  S[2] = ryy - 2.0 * a * sxy;
}

/* Total-Lagrangian solid (solid_total.c).  Compressible neo-Hookean material in plane strain
 * (F_zz = 1): second Piola-Kirchhoff stress S = G (I - C^-1) + lambda ln J C^-1, C = F^T F,
 * lambda = K - 2 G / 3, which is Hooke's law with the same K and G at small strain.  F and the
 * result row-major 2x2; returns J = det F (<= 0: the particle is inverted, S untouched). */
static inline PetscReal NeoHookeanPK2(PetscReal K, PetscReal G, const PetscReal F[4], PetscReal S[4])
{
  PetscReal J = F[0] * F[3] - F[1] * F[2], C[3], detC, Ci[3], l;
  if (J <= 0) return J;
  C[0] = F[0] * F[0] + F[2] * F[2]; C[1] = F[0] * F[1] + F[2] * F[3]; C[2] = F[1] * F[1] + F[3] * F[3]; /* xx, xy, yy */
  detC = J * J;
  Ci[0] = C[2] / detC; Ci[1] = -C[1] / detC; Ci[2] = C[0] / detC;
  l    = (K - 2.0 * G / 3.0) * PetscLogReal(J);
  S[0] = G * (1 - Ci[0]) + l * Ci[0];
  S[1] = S[2] = (l - G) * Ci[1];
  S[3] = G * (1 - Ci[2]) + l * Ci[2];
  return J;
}

/* Its stored energy per reference volume, G/2 (tr C - 3) - G ln J + lambda/2 (ln J)^2 with C_zz = 1. */
static inline PetscReal NeoHookeanEnergy(PetscReal K, PetscReal G, const PetscReal F[4])
{
  PetscReal J = F[0] * F[3] - F[1] * F[2], lj = J > 0 ? PetscLogReal(J) : 0, trC = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] + 1;
  return 0.5 * G * (trC - 3) - G * lj + 0.5 * (K - 2.0 * G / 3.0) * lj * lj;
}

/* Cauchy stress of it, sigma = P F^T / J with P = F S, as pressure and deviator (xx, xy, yy) for
 * the output fields; sigma_zz = lambda ln J / J in plane strain. */
static inline void NeoHookeanCauchy(PetscReal K, PetscReal G, const PetscReal F[4], const PetscReal S[4], PetscReal *p, PetscReal dev[3])
{
  PetscReal J = F[0] * F[3] - F[1] * F[2], P[4], sxx, sxy, syy, szz;
  P[0] = F[0] * S[0] + F[1] * S[2]; P[1] = F[0] * S[1] + F[1] * S[3];
  P[2] = F[2] * S[0] + F[3] * S[2]; P[3] = F[2] * S[1] + F[3] * S[3];
  sxx = (P[0] * F[0] + P[1] * F[1]) / J; sxy = (P[0] * F[2] + P[1] * F[3]) / J; syy = (P[2] * F[2] + P[3] * F[3]) / J;
  szz = (K - 2.0 * G / 3.0) * PetscLogReal(J) / J;
  *p     = -(sxx + syy + szz) / 3;
  dev[0] = sxx + *p; dev[1] = sxy; dev[2] = syy + *p;
}

/* Second-order quadrature of a particle's cell (side dx) for the strain energy, which one point
 * per particle integrates only to first order: int_cell W = V [W + dx^2 / 24 (W_XX + W_YY)] with,
 * for the strain E = (F^T F - I) / 2 of small magnitude, W_kk = E_k : C : E_k, E_k = sym(F^T dF/dX_k),
 * C Hooke's tensor (lambda = K - 2 G / 3, G).  A bent plate of n particles across stores
 * (1 - 1 / n^2) of its bending energy at one point per particle; this adds the missing part.
 * D (2 x 3, row-major) holds h x_i,XX, h x_i,XY, h x_i,YY; kappa = dx^2 / 24.  Returns the energy
 * density; with dF and dD adds its derivatives by F and D. */
static inline PetscReal CellQuadrature(PetscReal K, PetscReal G, PetscReal kappa, PetscReal h, const PetscReal F[4], const PetscReal D[6], PetscReal *dF, PetscReal *dD)
{
  PetscReal l = K - 2.0 * G / 3.0, W = 0, ih = 1.0 / h;
  for (PetscInt k = 0; k < 2; k++) {
    PetscReal Gm[4], E[4], S[4], tr; /* Gamma_k = dF/dX_k, row-major */
    Gm[0] = D[k] * ih; Gm[1] = D[k + 1] * ih; Gm[2] = D[3 + k] * ih; Gm[3] = D[3 + k + 1] * ih;
    E[0] = F[0] * Gm[0] + F[2] * Gm[2];                                               /* (F^T Gamma)_xx */
    E[3] = F[1] * Gm[1] + F[3] * Gm[3];                                               /* yy */
    E[1] = E[2] = 0.5 * (F[0] * Gm[1] + F[2] * Gm[3] + F[1] * Gm[0] + F[3] * Gm[2]); /* sym xy */
    tr   = E[0] + E[3];
    S[0] = l * tr + 2 * G * E[0]; S[1] = S[2] = 2 * G * E[1]; S[3] = l * tr + 2 * G * E[3];
    W += kappa * (E[0] * S[0] + 2 * E[1] * S[1] + E[3] * S[3]);
    if (!dF) continue;
    /* dW/dF += 2 kappa Gamma S;  dW/dGamma = 2 kappa F S, into D by Gamma's layout */
    dF[0] += 2 * kappa * (Gm[0] * S[0] + Gm[1] * S[2]); dF[1] += 2 * kappa * (Gm[0] * S[1] + Gm[1] * S[3]);
    dF[2] += 2 * kappa * (Gm[2] * S[0] + Gm[3] * S[2]); dF[3] += 2 * kappa * (Gm[2] * S[1] + Gm[3] * S[3]);
    dD[k] += 2 * kappa * (F[0] * S[0] + F[1] * S[2]) * ih;     dD[k + 1] += 2 * kappa * (F[0] * S[1] + F[1] * S[3]) * ih;
    dD[3 + k] += 2 * kappa * (F[2] * S[0] + F[3] * S[2]) * ih; dD[3 + k + 1] += 2 * kappa * (F[2] * S[1] + F[3] * S[3]) * ih;
  }
  return W;
}

/* Hourglass control of total-Lagrangian SPH as a potential.  The corrected F_a is the weighted
 * least-squares fit of the bonds, x_ab ~ F_a X_ab with weights w_ab = -V_b F0_ab (X = X_b - X_a,
 * x = x_b - x_a), so the energy of what no affine map explains,
 *   E_hg = zeta G / 2 sum_a V_a sum_b w_ab |F_a X_ab - x_ab|^2,
 * is stationary in F and its force needs no derivative of F (the envelope theorem): on a,
 *   acc_a = -zeta G / rho0 sum_b V_b (-F0_ab) [(F_a + F_b) X_ab - 2 x_ab].
 * Pair-antisymmetric, zero for every affine motion, invariant under rotation (so energy and both
 * momenta are conserved), and O((dx / L)^2) against the strain energy of a smooth field.  It is
 * close to Ganzenmueller's (2015) hourglass force, which projects the same error on the bond and
 * is not the gradient of an energy.  `coef` = zeta G V_b (-F0_ab) / rho0. */
static inline void HourglassAcc(PetscReal coef, const PetscReal Fa[4], const PetscReal Fb[4], const PetscReal X[2], const PetscReal x[2], PetscReal acc[2])
{
  acc[0] -= coef * ((Fa[0] + Fb[0]) * X[0] + (Fa[1] + Fb[1]) * X[1] - 2 * x[0]);
  acc[1] -= coef * ((Fa[2] + Fb[2]) * X[0] + (Fa[3] + Fb[3]) * X[1] - 2 * x[1]);
}

/* Its energy per unit reference volume of a from one bond, zeta G / 2 w |F_a X - x|^2 (`coef` =
 * zeta G w / 2). */
static inline PetscReal HourglassEnergy(PetscReal coef, const PetscReal Fa[4], const PetscReal X[2], const PetscReal x[2])
{
  PetscReal ex = Fa[0] * X[0] + Fa[1] * X[1] - x[0], ey = Fa[2] * X[0] + Fa[3] * X[1] - x[1];
  return coef * (ex * ex + ey * ey);
}
