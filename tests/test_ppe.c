/* The ISPH pressure equation of the hydrostatic tank on its initial regular lattice:
 *  - the assembled matrix is symmetric (so CG applies), each row has its diagonal and strictly
 *    increasing columns (the rows are written straight into PETSc's arrays, csr.h);
 *  - the preconditioner's matrix without the far pairs (-ppe_pc_qmax 1.6) is symmetric, has fewer
 *    entries, and the same row sums as the PPE (the pairs left out are lumped into the diagonal);
 *  - at fluid rows far from the surface and the walls, the Eq. 22 Laplacian of the quadratic
 *    f = x^2 + 2 y^2 matches div(grad f / rho) = 6 / rho0 within 0.5 %: on a regular lattice the
 *    operator is exact for quadratics up to the kernel's lattice-sum error (the second moment of
 *    the cubic spline summed over the lattice at h = 1.3 dx, 0.02 %); a wrong coefficient or
 *    density would be off by tens of per cent.  Run on 1 or 2 ranks. */
#include <sphfsi/sim.h>
#include <sphfsi/isph.h>
#include <sphfsi/kernel.h>

int main(int argc, char **argv)
{
  Sim        sim;
  PPE        ppe;
  Vec        f, Lf;
  PetscBool  sym;
  PetscReal  worst = 0, nrm;
  PetscInt   nin = 0;
  const PetscScalar *y;
  PetscScalar       *ff;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-case", "hydrostatic"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid", "isph"));
  PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_ppe"));
  PetscCall(PetscOptionsSetValue(NULL, "-ppe_pc_qmax", "1.6"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  sim->dt = 1e-3;
  PetscCall(ISPHPressureEquation(sim));
  ppe = sim->isph->ppe;
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
  PetscCall(MatIsSymmetric(ppe->A, 1e-12 * nrm, &sym));
  PetscCheck(sym, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The PPE matrix is not symmetric");
  { /* the preconditioner's matrix */
    Vec       sa, sp;
    MatInfo   ia, ip;
    PetscReal d;
    PetscCheck(ppe->Ap, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "-ppe_pc_qmax 1.6 built no preconditioner matrix");
    PetscCall(MatIsSymmetric(ppe->Ap, 1e-12 * nrm, &sym));
    PetscCheck(sym, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The preconditioner's matrix is not symmetric");
    PetscCall(MatGetInfo(ppe->A, MAT_GLOBAL_SUM, &ia));
    PetscCall(MatGetInfo(ppe->Ap, MAT_GLOBAL_SUM, &ip));
    PetscCheck(ip.nz_used < 0.8 * ia.nz_used, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The preconditioner's matrix has %g entries, the PPE %g: no far pair left out", ip.nz_used, ia.nz_used);
    PetscCall(MatCreateVecs(ppe->A, &sa, &sp));
    PetscCall(MatGetRowSum(ppe->A, sa));
    PetscCall(MatGetRowSum(ppe->Ap, sp));
    PetscCall(VecAXPY(sp, -1.0, sa));
    PetscCall(VecNorm(sp, NORM_INFINITY, &d));
    PetscCheck(d <= 1e-12 * nrm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Row sums of the preconditioner's matrix differ from the PPE's by %g (norm %g)", (double)d, (double)nrm);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ppe: preconditioner matrix (q = 1.6) symmetric, %.0f of %.0f entries, row sums equal within %.1e of the norm\n", ip.nz_used, ia.nz_used, (double)(d / nrm)));
    PetscCall(VecDestroy(&sa));
    PetscCall(VecDestroy(&sp));
  }
  /* A f = -V_a L_a(f) at rows whose neighbours are all unknowns (interior, no Dirichlet neighbour) */
  PetscCall(MatCreateVecs(ppe->A, &f, &Lf));
  {
    Particles        P = sim->P;
    const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M);
    const PetscReal  H = 0.1, W = 0.1, margin = 3 * SPH_H_FACTOR * sim->dx;
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
      PetscReal        L, exact = 6.0 / sim->fl.rho0;
      if (!KindIsFluid(P->kind[a]) || xa[0] < margin || xa[0] > W - margin || xa[1] < margin || xa[1] > H - 2 * margin) continue;
      L     = -y[r] / (m[a] / sim->fl.rho0);
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
