/* The ISPH pressure equation of the hydrostatic tank on its initial regular lattice:
 *  - the assembled matrix is symmetric (so CG applies), each row has its diagonal and strictly
 *    increasing columns (the rows are written straight into PETSc's arrays, csr.h);
 *  - the preconditioner's matrix without the far pairs (-ppe_pc_qmax 1.6) is symmetric, has fewer
 *    entries, and the same row sums as the PPE (the pairs left out are lumped into the diagonal);
 *    built in hypre's format (-ppe_mat_hypre) it has hypre's layout and equals the AIJ one;
 *  - at fluid rows far from the surface and the walls, the Eq. 22 Laplacian of the quadratic
 *    f = x^2 + 2 y^2 matches div(grad f / rho) = 6 / rho0 within 0.5 %: on a regular lattice the
 *    operator is exact for quadratics up to the kernel's lattice-sum error (the second moment of
 *    the cubic spline summed over the lattice at h = 1.3 dx, 0.02 %); a wrong coefficient or
 *    density would be off by tens of per cent.  Run on 1 or 2 ranks. */
#include "run/sim.h"
#include <sphfsi.h>
#include "fluid/isph.h"
#include "base/kernel.h"
#include <petscmathypre.h>

/* An AIJ copy of M (converted from hypre's format) */
static PetscErrorCode ToAIJ(Mat M, Mat *B)
{
  PetscBool hyp;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)M, MATHYPRE, &hyp));
  if (hyp) PetscCall(MatConvert(M, MATAIJ, MAT_INITIAL_MATRIX, B));
  else PetscCall(MatDuplicate(M, MAT_COPY_VALUES, B));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |M - M^T| <= 1e-12 nrm, from the entries (MatIsSymmetric would trust the MAT_SYMMETRIC flag) */
static PetscErrorCode CheckSymmetric(Mat M, PetscReal nrm, const char *what)
{
  Mat       T;
  PetscReal d;
  PetscFunctionBeginUser;
  PetscCall(MatTranspose(M, MAT_INITIAL_MATRIX, &T));
  PetscCall(MatAXPY(T, -1.0, M, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatNorm(T, NORM_INFINITY, &d));
  PetscCheck(d <= 1e-12 * nrm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s is not symmetric: |M - M^T| = %g, |M| = %g", what, (double)d, (double)nrm);
  PetscCall(MatDestroy(&T));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* hypre's ParCSR layout: each row's diagonal entry first, off-diagonal columns through an increasing map */
static PetscErrorCode CheckHypreLayout(Mat M)
{
  hypre_ParCSRMatrix *H;
  hypre_CSRMatrix    *D, *O;
  PetscBool           hyp;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)M, MATHYPRE, &hyp));
  PetscCheck(hyp, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "With BoomerAMG the preconditioner's matrix should be MATHYPRE (-ppe_mat_hypre)");
  PetscCall(MatHYPREGetParCSR(M, &H));
  D = hypre_ParCSRMatrixDiag(H);
  O = hypre_ParCSRMatrixOffd(H);
  for (HYPRE_Int r = 0; r < hypre_CSRMatrixNumRows(D); r++) PetscCheck(hypre_CSRMatrixJ(D)[hypre_CSRMatrixI(D)[r]] == r, PETSC_COMM_SELF, PETSC_ERR_PLIB, "hypre row %d does not start with its diagonal", (int)r);
  for (HYPRE_Int k = 1; k < hypre_CSRMatrixNumCols(O); k++) PetscCheck(hypre_ParCSRMatrixColMapOffd(H)[k] > hypre_ParCSRMatrixColMapOffd(H)[k - 1], PETSC_COMM_SELF, PETSC_ERR_PLIB, "hypre's off-diagonal column map is not increasing");
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim        sim;
  PPE        ppe;
  Vec        f, Lf;
  PetscReal  worst = 0, nrm;
  PetscInt   nin = 0;
  const PetscScalar *y;
  PetscScalar       *ff;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));

  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsSetValue(NULL, "-case", "hydrostatic"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid", "isph"));
  PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_ppe"));
  PetscCall(PetscOptionsSetValue(NULL, "-ppe_pc_qmax", "1.6"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  sim->phys.dt = 1e-3;
  PetscCall(ISPHPressureEquation(&sim->phys));
  ppe = sim->phys.isph->ppe;
  for (PetscInt r = ppe->rstart; r < ppe->rstart + ppe->nrow; r++) {
    const PetscInt *cols;
    PetscInt        nc;
    PetscBool       diag = PETSC_FALSE;
    PetscCall(MatGetRow(ppe->A, r, &nc, &cols, NULL));
    for (PetscInt k = 0; k < nc; k++) {
      PetscCheck(k == 0 || cols[k] > cols[k - 1], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Row %" PetscInt_FMT ": columns not strictly increasing", r);
      diag = (PetscBool)(diag || cols[k] == r);
    }
    PetscCall(MatRestoreRow(ppe->A, r, &nc, &cols, NULL));
    PetscCheck(diag, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Row %" PetscInt_FMT " has no diagonal entry", r);
  }
  PetscCall(MatNorm(ppe->A, NORM_INFINITY, &nrm));
  PetscCall(CheckSymmetric(ppe->A, nrm, "The PPE matrix"));
  { /* the preconditioner's matrix */
    Vec       sa, sp;
    MatInfo   ia, ip;
    PetscReal d;
    Mat       Bp, Bh;
    PetscCheck(ppe->Ap, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "-ppe_pc_qmax 1.6 built no preconditioner matrix");
    PetscCall(ToAIJ(ppe->Ap, &Bh));
    PetscCall(CheckSymmetric(Bh, nrm, "The preconditioner's matrix"));
    PetscCall(MatGetInfo(ppe->A, MAT_GLOBAL_SUM, &ia));
    PetscCall(MatGetInfo(Bh, MAT_GLOBAL_SUM, &ip));
    PetscCheck(ip.nz_used < 0.8 * ia.nz_used, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The preconditioner's matrix has %g entries, the PPE %g: no far pair left out", ip.nz_used, ia.nz_used);
    PetscCall(MatCreateVecs(ppe->A, &sa, &sp));
    PetscCall(MatGetRowSum(ppe->A, sa));
    PetscCall(MatGetRowSum(Bh, sp));
    PetscCall(VecAXPY(sp, -1.0, sa));
    PetscCall(VecNorm(sp, NORM_INFINITY, &d));
    PetscCheck(d <= 1e-12 * nrm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Row sums of the preconditioner's matrix differ from the PPE's by %g (norm %g)", (double)d, (double)nrm);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ppe: preconditioner matrix (q = 1.6) symmetric, %.0f of %.0f entries, row sums equal within %.1e of the norm\n", ip.nz_used, ia.nz_used, (double)(d / nrm)));
    PetscCall(VecDestroy(&sa));
    PetscCall(VecDestroy(&sp));
    /* in hypre's format (-ppe_mat_hypre, the default with BoomerAMG): hypre's layout, and the same
     * matrix as the AIJ one assembled without it */
    PetscCall(CheckHypreLayout(ppe->Ap));
    ppe->mat_hypre = PETSC_FALSE;
    PetscCall(ISPHPressureEquation(&sim->phys));
    PetscCall(MatDuplicate(ppe->Ap, MAT_COPY_VALUES, &Bp));
    PetscCall(MatAXPY(Bh, -1.0, Bp, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatNorm(Bh, NORM_INFINITY, &d));
    PetscCheck(d == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The preconditioner's matrix in hypre's format differs from the AIJ one by %g", (double)d);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ppe: preconditioner matrix in hypre's format: diagonal first, sorted column map, equal to the AIJ one\n"));
    PetscCall(MatDestroy(&Bp));
    PetscCall(MatDestroy(&Bh));
  }
  /* A f = -V_a L_a(f) at rows whose neighbours are all unknowns (interior, no Dirichlet neighbour) */
  PetscCall(MatCreateVecs(ppe->A, &f, &Lf));
  {
    Particles        P = sim->P;
    const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M);
    const PetscReal  H = 0.1, W = 0.1, margin = 3 * sim->phys.kernel.h_factor * sim->phys.dx;
    PetscCall(VecGetArrayWrite(f, &ff));
    for (PetscInt r = 0; r < ppe->nrow; r++) {
      const PetscReal *xa = x + 2 * ppe->rowpart[r];
      ff[r] = xa[0] * xa[0] + 2 * xa[1] * xa[1];
    }
    PetscCall(VecRestoreArrayWrite(f, &ff));
    PetscCall(MatMult(ppe->A, f, Lf));
    PetscCall(VecGetArrayRead(Lf, &y));
    for (PetscInt r = 0; r < ppe->nrow; r++) {
      PetscInt         a  = ppe->rowpart[r];
      const PetscReal *xa = x + 2 * a;
      PetscReal        L, exact = 6.0 / sim->phys.fl.rho0;
      if (!KindIsFluid(P->kind[a]) || xa[0] < margin || xa[0] > W - margin || xa[1] < margin || xa[1] > H - 2 * margin) continue;
      L     = -y[r] / (m[a] / sim->phys.fl.rho0);
      worst = PetscMax(worst, PetscAbsReal(L - exact) / exact);
      nin++;
    }
    PetscCall(VecRestoreArrayRead(Lf, &y));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nin, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ppe: %" PetscInt_FMT " rows, symmetric, sorted rows with diagonals; Eq. 22 Laplacian of x^2 + 2y^2 at %" PetscInt_FMT " interior rows within %.3f %% of exact (bound 0.5 %%)\n", ppe->nrow_global, nin, (double)(100 * worst)));
  PetscCheck(nin > 50, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Too few interior rows (%" PetscInt_FMT ")", nin);
  PetscCheck(worst < 0.005, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Laplacian off by %g %%", (double)(100 * worst));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&Lf));
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
