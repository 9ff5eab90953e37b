/* The total-Lagrangian solid's hyper-elastic laws (solid_terms.h, -solid_law): for neo-Hookean and
 * St Venant-Kirchhoff, in 2D (plane strain) and 3D,
 *  - the first Piola-Kirchhoff stress F S is the derivative of the energy W(F) (central differences,
 *    at a finite strain with a large rotation): the forces, minus the gradient of the discrete energy,
 *    are the law's;
 *  - objectivity: W and S unchanged by a rotation Q F;
 *  - plane strain: the 3D law at F_zz = 1 gives the 2D one's energy, in-plane S and Cauchy stress;
 *  - both laws are Hooke's law with lambda = K - 2 G / 3, mu = G at small strain (they differ by
 *    O(strain^2));
 *  - St Venant-Kirchhoff against its closed form in a plane-strain uniaxial stretch: S = lambda
 *    tr(E) I + 2 mu E, sigma = F S F^T / J, sigma_zz = lambda tr(E) / J;
 *  - an inverted F (J <= 0) is returned as such with S untouched, for the run guard. */
#include "solid/solid_terms.h"

static const PetscReal K = 2.0e6 + 1.0e6 / 3, G = 0.5e6; /* Turek-Hron: lambda 2e6, mu 0.5e6 */

/* F = R(theta) U for a symmetric stretch U (row-major D x D); in 3D the rotation is about z. */
static void Deformation(PetscInt D, PetscReal theta, const PetscReal *U, PetscReal *F)
{
  PetscReal R[9] = {PetscCosReal(theta), -PetscSinReal(theta), 0, PetscSinReal(theta), PetscCosReal(theta), 0, 0, 0, 1};
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt j = 0; j < D; j++) {
      F[D * i + j] = 0;
      for (PetscInt k = 0; k < D; k++) F[D * i + j] += R[3 * i + k] * U[D * k + j];
    }
}

static PetscReal MaxAbs(const PetscReal *a, PetscInt n)
{
  PetscReal m = 0;
  for (PetscInt i = 0; i < n; i++) m = PetscMax(m, PetscAbsReal(a[i]));
  return m;
}

/* P = F S against dW/dF by central differences (relative to |P|), and W, S under a rotation. */
static PetscErrorCode CheckLaw(SolidLaw law, PetscInt D)
{
  const PetscReal U2[4] = {1.12, 0.07, 0.07, 0.93}, U3[9] = {1.12, 0.07, -0.03, 0.07, 0.93, 0.05, -0.03, 0.05, 1.04};
  const PetscReal *U = D == 2 ? U2 : U3, eps = 1e-6;
  PetscReal        F[9], S[9], P[9], dW[9], W0, FQ[9], SQ[9], err = 0, errQ, errW;
  PetscFunctionBeginUser;
  Deformation(D, 0.9, U, F); /* a rotation of 52 degrees */
  PetscCheck(SolidLawPK2D(law, K, G, F, S, D) > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "J <= 0 for a valid F");
  W0 = SolidLawEnergyD(law, K, G, F, D);
  for (PetscInt i = 0; i < D; i++)
    for (PetscInt j = 0; j < D; j++) {
      PetscReal Fp[9], Fm[9];
      P[D * i + j] = 0;
      for (PetscInt k = 0; k < D; k++) P[D * i + j] += F[D * i + k] * S[D * k + j];
      for (PetscInt k = 0; k < D * D; k++) Fp[k] = Fm[k] = F[k];
      Fp[D * i + j] += eps; Fm[D * i + j] -= eps;
      dW[D * i + j] = (SolidLawEnergyD(law, K, G, Fp, D) - SolidLawEnergyD(law, K, G, Fm, D)) / (2 * eps);
    }
  for (PetscInt k = 0; k < D * D; k++) err = PetscMax(err, PetscAbsReal(P[k] - dW[k]));
  err /= MaxAbs(P, D * D);
  Deformation(D, 0.0, U, FQ); /* the same stretch unrotated: W and S must not change */
  PetscCheck(SolidLawPK2D(law, K, G, FQ, SQ, D) > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "J <= 0 for a valid F");
  errW = PetscAbsReal(SolidLawEnergyD(law, K, G, FQ, D) - W0) / W0;
  for (PetscInt k = 0; k < D * D; k++) SQ[k] -= S[k];
  errQ = MaxAbs(SQ, D * D) / MaxAbs(S, D * D);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %dD: |F S - dW/dF| / |P| %.1e, rotation: |dW| / W %.1e, |dS| / |S| %.1e\n", law == SOLID_LAW_ST_VENANT_KIRCHHOFF ? "st_venant_kirchhoff" : "neo_hookean", (int)D, (double)err, (double)errW, (double)errQ));
  PetscCheck(err < 1e-6, PETSC_COMM_SELF, PETSC_ERR_PLIB, "F S is not the derivative of the energy");
  PetscCheck(errW < 1e-12 && errQ < 1e-12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The law is not objective");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The 3D law at F_zz = 1 is the 2D (plane-strain) one. */
static PetscErrorCode CheckPlaneStrain(SolidLaw law)
{
  const PetscReal U[4] = {1.12, 0.07, 0.07, 0.93};
  PetscReal       F2[4], F3[9] = {0}, S2[4], S3[9], p2, p3, d2[3], d3[6], e = 0;
  PetscFunctionBeginUser;
  Deformation(2, 0.4, U, F2);
  F3[0] = F2[0]; F3[1] = F2[1]; F3[3] = F2[2]; F3[4] = F2[3]; F3[8] = 1;
  PetscCheck(SolidLawPK2D(law, K, G, F2, S2, 2) > 0 && SolidLawPK2D(law, K, G, F3, S3, 3) > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "J <= 0 for a valid F");
  SolidLawCauchyD(law, K, G, F2, S2, &p2, d2, 2);
  SolidLawCauchyD(law, K, G, F3, S3, &p3, d3, 3);
  e = PetscMax(e, PetscAbsReal(SolidLawEnergyD(law, K, G, F2, 2) - SolidLawEnergyD(law, K, G, F3, 3)) / SolidLawEnergyD(law, K, G, F2, 2));
  e = PetscMax(e, (PetscAbsReal(S2[0] - S3[0]) + PetscAbsReal(S2[1] - S3[1]) + PetscAbsReal(S2[3] - S3[4])) / MaxAbs(S2, 4));
  e = PetscMax(e, (PetscAbsReal(p2 - p3) + PetscAbsReal(d2[0] - d3[0]) + PetscAbsReal(d2[1] - d3[1]) + PetscAbsReal(d2[2] - d3[3])) / MaxAbs(S2, 4));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: 2D plane strain against 3D at F_zz = 1: %.1e\n", law == SOLID_LAW_ST_VENANT_KIRCHHOFF ? "st_venant_kirchhoff" : "neo_hookean", (double)e));
  PetscCheck(e < 1e-12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The 2D law is not the plane-strain 3D one");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Both laws are Hooke's at small strain; St Venant-Kirchhoff's closed form in a uniaxial stretch. */
static PetscErrorCode CheckHookeAndStretch(void)
{
  const PetscReal l = K - 2 * G / 3, e = 1e-5, U[4] = {1 + e, 0.3 * e, 0.3 * e, 1 - 0.5 * e}, a = 0.3;
  PetscReal       Sn[4], Ss[4], d = 0, F[4] = {1 + a, 0, 0, 1}, S[4], p, dev[3], Exx = a + 0.5 * a * a, sxx, syy, szz, pe, err = 0;
  PetscFunctionBeginUser;
  (void)SolidLawPK2D(SOLID_LAW_NEO_HOOKEAN, K, G, U, Sn, 2);
  (void)SolidLawPK2D(SOLID_LAW_ST_VENANT_KIRCHHOFF, K, G, U, Ss, 2);
  for (PetscInt k = 0; k < 4; k++) d = PetscMax(d, PetscAbsReal(Sn[k] - Ss[k]));
  d /= MaxAbs(Ss, 4);
  (void)SolidLawPK2D(SOLID_LAW_ST_VENANT_KIRCHHOFF, K, G, F, S, 2);
  SolidLawCauchyD(SOLID_LAW_ST_VENANT_KIRCHHOFF, K, G, F, S, &p, dev, 2);
  sxx = (1 + a) * (l + 2 * G) * Exx; /* F S F^T / J, J = 1 + a */
  syy = l * Exx / (1 + a);
  szz = l * Exx / (1 + a);
  pe  = -(sxx + syy + szz) / 3;
  err = PetscMax(PetscAbsReal(S[0] - (l + 2 * G) * Exx), PetscAbsReal(S[3] - l * Exx));
  err = PetscMax(err, PetscMax(PetscAbsReal(p - pe), PetscAbsReal(dev[0] - (sxx + pe))));
  err = PetscMax(err, PetscMax(PetscAbsReal(dev[2] - (syy + pe)), PetscAbsReal(dev[1])));
  err /= (l + 2 * G) * Exx;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "small strain %g: |S_svk - S_nh| / |S| %.1e; St Venant-Kirchhoff uniaxial stretch 1.3 against its closed form %.1e\n", (double)e, (double)d, (double)err));
  PetscCheck(d < 1e-4, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The laws differ at small strain by more than O(strain)");
  PetscCheck(err < 1e-12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "St Venant-Kirchhoff's stress is not its closed form");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* An inverted particle: J <= 0 returned, S untouched (the run guard then stops on the NaN). */
static PetscErrorCode CheckInverted(void)
{
  const PetscReal F2[4] = {-1, 0, 0, 1}, F3[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  PetscReal       S[9];
  PetscFunctionBeginUser;
  for (PetscInt law = 0; law < 2; law++)
    for (PetscInt D = 2; D <= 3; D++) {
      for (PetscInt k = 0; k < 9; k++) S[k] = 7;
      PetscCheck(SolidLawPK2D((SolidLaw)law, K, G, D == 2 ? F2 : F3, S, D) <= 0 && MaxAbs(S, 9) == 7, PETSC_COMM_SELF, PETSC_ERR_PLIB, "An inverted F is not reported");
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (PetscInt law = 0; law < 2; law++) {
    PetscCall(CheckLaw((SolidLaw)law, 2));
    PetscCall(CheckLaw((SolidLaw)law, 3));
    PetscCall(CheckPlaneStrain((SolidLaw)law));
  }
  PetscCall(CheckHookeAndStretch());
  PetscCall(CheckInverted());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_solid_law: ok\n"));
  PetscCall(PetscFinalize());
  return 0;
}
