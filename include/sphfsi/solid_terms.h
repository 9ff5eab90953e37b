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
