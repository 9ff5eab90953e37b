/* Per-particle and per-pair terms of the hypo-elastic solid (section 2.4). */
#pragma once
#include "base/dim.h"
#include "base/material.h"

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

/* Eq. 40 in 3D: the same implicit update for the symmetric S (xx, xy, xz, yy, yz, zz) with the
 * spin W = (g - g^T) / 2 of the velocity gradient g (row-major 3 x 3) and D = (g + g^T) / 2:
 * S' - dt (W S' - S' W) = S + dt 2 G (D - tr(D)/3 I), a 6 x 6 linear system solved by
 * elimination with partial pivoting (it is I plus O(dt |W|), so always solvable). */
static inline void JaumannUpdate3(PetscReal G, PetscReal dt, const PetscReal g[9], PetscReal S[6])
{
  static const PetscInt sym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  PetscReal             W[3][3], A[6][7], tr3 = (g[0] + g[4] + g[8]) / 3.0;
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt j = 0; j < 3; j++) W[i][j] = 0.5 * (g[3 * i + j] - g[3 * j + i]);
  for (PetscInt m = 0; m < 6; m++) { /* column m: the operator on the unit symmetric tensor of component m */
    PetscReal E[3][3] = {{0}};
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) E[i][j] = sym[i][j] == m;
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = i; j < 3; j++) {
        PetscReal c = 0;
        for (PetscInt k = 0; k < 3; k++) c += W[i][k] * E[k][j] - E[i][k] * W[k][j];
        A[sym[i][j]][m] = E[i][j] - dt * c;
      }
  }
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt j = i; j < 3; j++) A[sym[i][j]][6] = S[sym[i][j]] + dt * 2.0 * G * (0.5 * (g[3 * i + j] + g[3 * j + i]) - (i == j ? tr3 : 0));
  for (PetscInt c = 0; c < 6; c++) {
    PetscInt piv = c;
    for (PetscInt i = c + 1; i < 6; i++) if (PetscAbsReal(A[i][c]) > PetscAbsReal(A[piv][c])) piv = i;
    for (PetscInt j = 0; j < 7; j++) { PetscReal t = A[c][j]; A[c][j] = A[piv][j]; A[piv][j] = t; }
    for (PetscInt i = c + 1; i < 6; i++) {
      PetscReal r = A[i][c] / A[c][c];
      for (PetscInt j = c; j < 7; j++) A[i][j] -= r * A[c][j];
    }
  }
  for (PetscInt i = 5; i >= 0; i--) {
    PetscReal t = A[i][6];
    for (PetscInt j = i + 1; j < 6; j++) t -= A[i][j] * S[j];
    S[i] = t / A[i][i];
  }
}

/* Eigenvalues lam and unit eigenvectors (columns of V, row-major) of the symmetric 3 x 3 M (xx, xy,
 * xz, yy, yz, zz) by cyclic Jacobi rotations. */
static inline void Sym3Eigen(const PetscReal M[6], PetscReal lam[3], PetscReal V[9])
{
  PetscReal A[3][3] = {{M[0], M[1], M[2]}, {M[1], M[3], M[4]}, {M[2], M[4], M[5]}};
  for (PetscInt i = 0; i < 9; i++) V[i] = (i % 4 == 0);
  for (PetscInt sweep = 0; sweep < 30; sweep++) {
    PetscReal off = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2], scale = A[0][0] * A[0][0] + A[1][1] * A[1][1] + A[2][2] * A[2][2];
    if (off <= 1e-30 * scale || off == 0) break;
    for (PetscInt p = 0; p < 2; p++)
      for (PetscInt q = p + 1; q < 3; q++) {
        PetscReal th, t, c, s;
        if (A[p][q] == 0) continue;
        th = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
        t  = (th >= 0 ? 1.0 : -1.0) / (PetscAbsReal(th) + PetscSqrtReal(th * th + 1.0));
        c  = 1.0 / PetscSqrtReal(t * t + 1.0); s = t * c;
        for (PetscInt k = 0; k < 3; k++) { /* A <- A J, then J^T A; V <- V J */
          PetscReal akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq; A[k][q] = s * akp + c * akq;
        }
        for (PetscInt k = 0; k < 3; k++) {
          PetscReal apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk; A[q][k] = s * apk + c * aqk;
        }
        for (PetscInt k = 0; k < 3; k++) {
          PetscReal vkp = V[3 * k + p], vkq = V[3 * k + q];
          V[3 * k + p] = c * vkp - s * vkq; V[3 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  for (PetscInt i = 0; i < 3; i++) lam[i] = A[i][i];
}

/* Eqs. 25-34 in 3D: the principal frame of sigma = -P I + S by its eigenvectors n_i; each tensile
 * principal stress gets -e sigma_i / rho^2, and R = sum_i r_i n_i (x) n_i (xx, xy, xz, yy, yz, zz). */
static inline void ArtificialStress3(PetscReal e, const PetscReal sigma[6], PetscReal rho, PetscReal R[6])
{
  static const PetscInt row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
  PetscReal             lam[3], V[9], r[3];
  Sym3Eigen(sigma, lam, V);
  for (PetscInt i = 0; i < 3; i++) r[i] = lam[i] > 0 ? -e * lam[i] / (rho * rho) : 0.0;
  for (PetscInt m = 0; m < 6; m++) R[m] = r[0] * V[3 * row[m]] * V[3 * col[m]] + r[1] * V[3 * row[m] + 1] * V[3 * col[m] + 1] + r[2] * V[3 * row[m] + 2] * V[3 * col[m] + 2];
}

/* Total-Lagrangian solid (solid_total.c).  Compressible neo-Hookean material in plane strain
 * (F_zz = 1): second Piola-Kirchhoff stress S = G (I - C^-1) + lambda ln J C^-1, C = F^T F,
 * lambda = K - 2 G / 3, which is Hooke's law with the same K and G at small strain.  F and the
 * result row-major 2x2; returns J = det F (<= 0: the particle is inverted, S untouched).  The
 * default law; -solid_law selects between it and St Venant-Kirchhoff (SolidLawPK2D below). */
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

/* The same material in 3D: F and S row-major 3 x 3; returns J = det F (<= 0: S untouched). */
static inline PetscReal NeoHookean3PK2(PetscReal K, PetscReal G, const PetscReal F[9], PetscReal S[9])
{
  static const PetscInt row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
  PetscReal             C[6], Ci[6], J, iJ2, l;
  J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
  if (J <= 0) return J;
  for (PetscInt m = 0; m < 6; m++) C[m] = F[row[m]] * F[col[m]] + F[3 + row[m]] * F[3 + col[m]] + F[6 + row[m]] * F[6 + col[m]]; /* C = F^T F */
  iJ2   = 1.0 / (J * J); /* det C = J^2; C^-1 = cofactors / det C */
  Ci[0] = (C[3] * C[5] - C[4] * C[4]) * iJ2; Ci[1] = (C[2] * C[4] - C[1] * C[5]) * iJ2; Ci[2] = (C[1] * C[4] - C[2] * C[3]) * iJ2;
  Ci[3] = (C[0] * C[5] - C[2] * C[2]) * iJ2; Ci[4] = (C[1] * C[2] - C[0] * C[4]) * iJ2; Ci[5] = (C[0] * C[3] - C[1] * C[1]) * iJ2;
  l = (K - 2.0 * G / 3.0) * PetscLogReal(J);
  for (PetscInt m = 0; m < 6; m++) {
    PetscReal v = (row[m] == col[m] ? G : 0.0) + (l - G) * Ci[m];
    S[3 * row[m] + col[m]] = S[3 * col[m] + row[m]] = v;
  }
  return J;
}

static inline PetscReal NeoHookean3Energy(PetscReal K, PetscReal G, const PetscReal F[9])
{
  PetscReal J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]), lj = J > 0 ? PetscLogReal(J) : 0, trC = 0;
  for (PetscInt i = 0; i < 9; i++) trC += F[i] * F[i];
  return 0.5 * G * (trC - 3) - G * lj + 0.5 * (K - 2.0 * G / 3.0) * lj * lj;
}

/* sigma = F S F^T / J as pressure and deviator (xx, xy, xz, yy, yz, zz). */
static inline void NeoHookean3Cauchy(const PetscReal F[9], const PetscReal S[9], PetscReal *p, PetscReal dev[6])
{
  static const PetscInt row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
  PetscReal             P[9], J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt j = 0; j < 3; j++) P[3 * i + j] = F[3 * i] * S[j] + F[3 * i + 1] * S[3 + j] + F[3 * i + 2] * S[6 + j];
  for (PetscInt m = 0; m < 6; m++) dev[m] = (P[3 * row[m]] * F[3 * col[m]] + P[3 * row[m] + 1] * F[3 * col[m] + 1] + P[3 * row[m] + 2] * F[3 * col[m] + 2]) / J;
  *p = -(dev[0] + dev[3] + dev[5]) / 3;
  dev[0] += *p; dev[3] += *p; dev[5] += *p;
}

/* The material in D dimensions: plane strain in 2D, the full law in 3D. */
SPH_INLINE PetscReal NeoHookeanPK2D(PetscReal K, PetscReal G, const PetscReal *F, PetscReal *S, const PetscInt D) { return D == 2 ? NeoHookeanPK2(K, G, F, S) : NeoHookean3PK2(K, G, F, S); }
SPH_INLINE PetscReal NeoHookeanEnergyD(PetscReal K, PetscReal G, const PetscReal *F, const PetscInt D) { return D == 2 ? NeoHookeanEnergy(K, G, F) : NeoHookean3Energy(K, G, F); }
SPH_INLINE void      NeoHookeanCauchyD(PetscReal K, PetscReal G, const PetscReal *F, const PetscReal *S, PetscReal *p, PetscReal *dev, const PetscInt D)
{
  if (D == 2) NeoHookeanCauchy(K, G, F, S, p, dev);
  else NeoHookean3Cauchy(F, S, p, dev);
}

/* St Venant-Kirchhoff (the Turek-Hron benchmark's solid): S = lambda tr(E) I + 2 mu E with the
 * Green-Lagrange strain E = (F^T F - I) / 2, lambda = K - 2 G / 3, mu = G (Hooke's law in E, so the
 * same small-strain moduli as the neo-Hookean law), energy W = lambda / 2 tr(E)^2 + mu E : E.  Plane
 * strain in 2D: F_zz = 1, E_zz = 0, S_zz = lambda tr(E).  Returns J = det F; J <= 0 (inverted, where
 * this law is not even stable) leaves S untouched, as the neo-Hookean law does, for the run guard. */
static inline PetscReal StVenantKirchhoffPK2(PetscReal K, PetscReal G, const PetscReal F[4], PetscReal S[4])
{
  PetscReal J = F[0] * F[3] - F[1] * F[2], l = K - 2.0 * G / 3.0, E[3], tr;
  if (J <= 0) return J;
  E[0] = 0.5 * (F[0] * F[0] + F[2] * F[2] - 1); E[1] = 0.5 * (F[0] * F[1] + F[2] * F[3]); E[2] = 0.5 * (F[1] * F[1] + F[3] * F[3] - 1); /* xx, xy, yy */
  tr   = E[0] + E[2];
  S[0] = l * tr + 2 * G * E[0];
  S[1] = S[2] = 2 * G * E[1];
  S[3] = l * tr + 2 * G * E[2];
  return J;
}

static inline PetscReal StVenantKirchhoffEnergy(PetscReal K, PetscReal G, const PetscReal F[4])
{
  PetscReal l = K - 2.0 * G / 3.0, exx = 0.5 * (F[0] * F[0] + F[2] * F[2] - 1), exy = 0.5 * (F[0] * F[1] + F[2] * F[3]), eyy = 0.5 * (F[1] * F[1] + F[3] * F[3] - 1), tr = exx + eyy;
  return 0.5 * l * tr * tr + G * (exx * exx + 2 * exy * exy + eyy * eyy);
}

/* Its Cauchy stress as pressure and deviator (xx, xy, yy), as NeoHookeanCauchy: sigma = F S F^T / J,
 * sigma_zz = S_zz / J = lambda tr(E) / J in plane strain. */
static inline void StVenantKirchhoffCauchy(PetscReal K, PetscReal G, const PetscReal F[4], const PetscReal S[4], PetscReal *p, PetscReal dev[3])
{
  PetscReal J = F[0] * F[3] - F[1] * F[2], P[4], sxx, sxy, syy, szz, tr = 0.5 * (F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] - 2);
  P[0] = F[0] * S[0] + F[1] * S[2]; P[1] = F[0] * S[1] + F[1] * S[3];
  P[2] = F[2] * S[0] + F[3] * S[2]; P[3] = F[2] * S[1] + F[3] * S[3];
  sxx = (P[0] * F[0] + P[1] * F[1]) / J; sxy = (P[0] * F[2] + P[1] * F[3]) / J; syy = (P[2] * F[2] + P[3] * F[3]) / J;
  szz = (K - 2.0 * G / 3.0) * tr / J;
  *p     = -(sxx + syy + szz) / 3;
  dev[0] = sxx + *p; dev[1] = sxy; dev[2] = syy + *p;
}

/* The same in 3D: F and S row-major 3 x 3; returns J = det F (<= 0: S untouched). */
static inline PetscReal StVenantKirchhoff3PK2(PetscReal K, PetscReal G, const PetscReal F[9], PetscReal S[9])
{
  static const PetscInt row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
  PetscReal             E[6], J, l = K - 2.0 * G / 3.0, tr;
  J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
  if (J <= 0) return J;
  for (PetscInt m = 0; m < 6; m++) E[m] = 0.5 * (F[row[m]] * F[col[m]] + F[3 + row[m]] * F[3 + col[m]] + F[6 + row[m]] * F[6 + col[m]] - (row[m] == col[m])); /* (F^T F - I) / 2 */
  tr = E[0] + E[3] + E[5];
  for (PetscInt m = 0; m < 6; m++) S[3 * row[m] + col[m]] = S[3 * col[m] + row[m]] = (row[m] == col[m] ? l * tr : 0.0) + 2 * G * E[m];
  return J;
}

static inline PetscReal StVenantKirchhoff3Energy(PetscReal K, PetscReal G, const PetscReal F[9])
{
  static const PetscInt row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
  PetscReal             E[6], tr, ee = 0;
  for (PetscInt m = 0; m < 6; m++) E[m] = 0.5 * (F[row[m]] * F[col[m]] + F[3 + row[m]] * F[3 + col[m]] + F[6 + row[m]] * F[6 + col[m]] - (row[m] == col[m]));
  tr = E[0] + E[3] + E[5];
  for (PetscInt m = 0; m < 6; m++) ee += (row[m] == col[m] ? 1 : 2) * E[m] * E[m]; /* E : E */
  return 0.5 * (K - 2.0 * G / 3.0) * tr * tr + G * ee;
}

/* The total-Lagrangian solid's law (-solid_law), chosen where the stress, energy and Cauchy stress
 * of a particle are needed (solid_total.c): one selector, so every law takes the same path through
 * the fits, the cell quadrature (Hooke's tensor, the same for both at small strain), the forces and
 * the output.  The 3D Cauchy stress F S F^T / J holds for any law. */
SPH_INLINE PetscReal SolidLawPK2D(SolidLaw law, PetscReal K, PetscReal G, const PetscReal *F, PetscReal *S, const PetscInt D)
{
  if (law == SOLID_LAW_ST_VENANT_KIRCHHOFF) return D == 2 ? StVenantKirchhoffPK2(K, G, F, S) : StVenantKirchhoff3PK2(K, G, F, S);
  return NeoHookeanPK2D(K, G, F, S, D);
}
SPH_INLINE PetscReal SolidLawEnergyD(SolidLaw law, PetscReal K, PetscReal G, const PetscReal *F, const PetscInt D)
{
  if (law == SOLID_LAW_ST_VENANT_KIRCHHOFF) return D == 2 ? StVenantKirchhoffEnergy(K, G, F) : StVenantKirchhoff3Energy(K, G, F);
  return NeoHookeanEnergyD(K, G, F, D);
}
SPH_INLINE void SolidLawCauchyD(SolidLaw law, PetscReal K, PetscReal G, const PetscReal *F, const PetscReal *S, PetscReal *p, PetscReal *dev, const PetscInt D)
{
  if (law == SOLID_LAW_ST_VENANT_KIRCHHOFF && D == 2) StVenantKirchhoffCauchy(K, G, F, S, p, dev);
  else NeoHookeanCauchyD(K, G, F, S, p, dev, D);
}

/* Index of the pair (j, k) in a symmetric tensor's upper triangle (dim.h's order). */
SPH_INLINE PetscInt SymIndex(PetscInt j, PetscInt k, const PetscInt D)
{
  static const PetscInt s3[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return D == 2 ? j + k : s3[j][k];
}

/* Second-order quadrature of a particle's cell (side dx) for the strain energy, which one point
 * per particle integrates only to first order: int_cell W = V [W + dx^2 / 24 sum_k W_kk] with,
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

/* The same in 3D: Dd (3 x 6, row-major) holds h x_i,jk in dim.h's symmetric order (XX, XY, XZ, YY,
 * YZ, ZZ).  Written for any D; the 2D instance above is kept as it was, since the compiler
 * contracts this loop form's sums differently and 2D results must not change. */
static inline PetscReal CellQuadrature3(PetscReal K, PetscReal G, PetscReal kappa, PetscReal h, const PetscReal *F, const PetscReal *Dd, PetscReal *dF, PetscReal *dD)
{
  const PetscInt D = 3;
  const PetscInt NS = D * (D + 1) / 2;
  PetscReal      l = K - 2.0 * G / 3.0, W = 0, ih = 1.0 / h;
  for (PetscInt k = 0; k < D; k++) {
    PetscReal Gm[9], E[9], S[9], tr = 0, w; /* Gamma_k = dF/dX_k, row-major */
    for (PetscInt i = 0; i < D; i++)
      for (PetscInt j = 0; j < D; j++) Gm[D * i + j] = Dd[NS * i + SymIndex(j, k, D)] * ih;
    for (PetscInt j = 0; j < D; j++)
      for (PetscInt q = j; q < D; q++) {
        PetscReal t = F[j] * Gm[q]; /* (F^T Gamma)_jq, symmetrised off the diagonal */
        for (PetscInt i = 1; i < D; i++) t += F[D * i + j] * Gm[D * i + q];
        if (q != j) {
          for (PetscInt i = 0; i < D; i++) t += F[D * i + q] * Gm[D * i + j];
          t *= 0.5;
        }
        E[D * j + q] = E[D * q + j] = t;
      }
    for (PetscInt j = 0; j < D; j++) tr += E[D * j + j];
    for (PetscInt j = 0; j < D; j++)
      for (PetscInt q = 0; q < D; q++) S[D * j + q] = j == q ? l * tr + 2 * G * E[D * j + q] : 2 * G * E[D * j + q];
    w = E[0] * S[0] + 2 * E[1] * S[1] + 2 * E[2] * S[2] + E[4] * S[4] + 2 * E[5] * S[5] + E[8] * S[8]; /* E : S */
    W += kappa * w;
    if (!dF) continue;
    /* dW/dF += 2 kappa Gamma S;  dW/dGamma = 2 kappa F S, into Dd by Gamma's layout */
    for (PetscInt i = 0; i < D; i++)
      for (PetscInt j = 0; j < D; j++) {
        PetscReal gs = Gm[D * i] * S[j], fs = F[D * i] * S[j];
        for (PetscInt m = 1; m < D; m++) { gs += Gm[D * i + m] * S[D * m + j]; fs += F[D * i + m] * S[D * m + j]; }
        dF[D * i + j] += 2 * kappa * gs;
        dD[NS * i + SymIndex(j, k, D)] += 2 * kappa * fs * ih;
      }
  }
  return W;
}

/* The quadrature in D dimensions. */
SPH_INLINE PetscReal CellQuadratureD(PetscReal K, PetscReal G, PetscReal kappa, PetscReal h, const PetscReal *F, const PetscReal *Dd, PetscReal *dF, PetscReal *dD, const PetscInt D)
{
  return D == 2 ? CellQuadrature(K, G, kappa, h, F, Dd, dF, dD) : CellQuadrature3(K, G, kappa, h, F, Dd, dF, dD);
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
SPH_INLINE void HourglassAcc(PetscReal coef, const PetscReal *Fa, const PetscReal *Fb, const PetscReal *X, const PetscReal *x, PetscReal *acc, const PetscInt D)
{
  for (PetscInt i = 0; i < D; i++) {
    PetscReal s = (Fa[D * i] + Fb[D * i]) * X[0] + (Fa[D * i + 1] + Fb[D * i + 1]) * X[1];
    if (D == 3) s += (Fa[D * i + 2] + Fb[D * i + 2]) * X[2];
    acc[i] -= coef * (s - 2 * x[i]);
  }
}

/* Its energy per unit reference volume of a from one bond, zeta G / 2 w |F_a X - x|^2 (`coef` =
 * zeta G w / 2). */
SPH_INLINE PetscReal HourglassEnergy(PetscReal coef, const PetscReal *Fa, const PetscReal *X, const PetscReal *x, const PetscInt D)
{
  PetscReal e[3];
  for (PetscInt i = 0; i < D; i++) e[i] = VDot(Fa + D * i, X, D) - x[i];
  return coef * VDot(e, e, D);
}
