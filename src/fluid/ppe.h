/* The pressure Poisson equation of ISPH (Eqs. 22, 48) as a PETSc Mat, solved with KSP.
 * Rows: owned fluid particles and owned wall/dummy particles that have a fluid neighbour.
 *   fluid row a:        L_a(P) = src_a                     (src from isph.c: Eq. 13 or density)
 *   free-surface row a: P_a = 0                            (Dirichlet, section 2.5)
 *   wall row a:         L_a(P) = L_a(rho0 g . r) + approach (Neumann dP/dn = rho0 (g + v_n / dt) . n, ppe.c)
 * with L_a(P) = sum_b c_ab (P_a - P_b) (Eq. 22); a solid particle next to fluid has a wall row too
 * (its pressure goes to its fluid view, boundary.h); a wall row sums over fluid neighbours only (the
 * implicit form of the Adami extrapolation) and its solved pressure is clipped at min(0, the
 * c-weighted mean of its fluid's pressure): above the water line the hydrostatic part makes it
 * negative and would pull fluid onto the wall, but fluid in tension keeps its walls (clipped to 0,
 * they left it a force the solve had not balanced: the pressure next to the wall then flipped sign
 * and grew each step until particles went through the wall).  Each row is multiplied by -V_a = -m_a/rho0,
 * which makes the matrix symmetric positive (semi)definite: CG applies.  Free-surface columns are
 * eliminated (their P is 0), which keeps the symmetry.  Without any Dirichlet row (periodic or
 * closed domains) P is defined up to a constant: the right-hand side is made to sum to zero and
 * global row 0 is pinned (P = 0 there, its column eliminated like a free-surface one), so that the
 * matrix is definite; the solve starts from the last pressure less its value there, and the
 * solution is shifted back to the last pressure's mean.  Not a null space attached to a singular
 * matrix: BoomerAMG's coarsest level (a few rows) is then singular too, its Gaussian elimination
 * divides by a round-off pivot, and the V-cycle amplifies the constant by ~1e22, so that CG's
 * (r, B r) takes the sign of round-off once the residual is small (DIVERGED_INDEFINITE_PC). */
#pragma once
#include "physics/physics.h"
#include "base/csr.h"
#include <petscksp.h>

#define PPE_RTOL_DEFAULT 1e-4 /* -ppe_ksp_rtol: Taylor-Green, the still tank, the gate and the a/100 dam break unchanged from 1e-8 (docs/convergence.md) */

typedef struct _p_PPE *PPE;
struct _p_PPE {
  MPI_Comm     comm;
  KSP          ksp;
  Mat          A, Ap;                           /* the operator; the matrix the preconditioner is built from (A itself when pc_qmax = 0) */
  SplitCSR     csr, csrp;                       /* their arrays */
  Vec          x, b;
  MatNullSpace nullsp;
  PetscInt     nrow, rstart, nrow_global, ndirichlet_global;
  PetscInt     nempty;                          /* ranks that own no row this step (CreateMatrix) */
  PetscInt     pin;                             /* global row pinned to P = 0 when there is no Dirichlet row (no free surface); -1: none */
  PetscInt    *rowpart, cap_rows;               /* per local row: owned particle */
  PetscReal    pc_qmax;                         /* Ap leaves out pairs with r / h_ab > pc_qmax (0: Ap = A) */
  PetscReal   *hyd;                             /* per local wall row: hydrostatic part of its P, L_a(rho0 g . r) / sum_b c_ab */
  PetscBool    symmetric;                       /* no implicit solid rows (ppe.c): CG applies */
  PetscReal    row_stiffness;                   /* implicit solid rows: weight of the bonds in a row's inertia (-fsi_row_stiffness, MovingSolidRow) */
  PetscBool    wall_approach;                   /* wall rows also stop approaching fluid (ppe.c, WallApproach) */
  PetscBool    wall_clip;                       /* clip the walls' pressure above the water line and flag them dry in FIELD_FS (PPESolve) */
  PetscBool    mat_hypre;                       /* the matrix the preconditioner reads built in hypre's format (csr.h): -ppe_mat_hypre with a hypre PC that can share our arrays */
  PetscInt    *cols, *colsp, cap_cols;
  PetscScalar *vals, *valsp;
  /* statistics */
  PetscInt  nsolve, its_last, its_max;
  PetscReal its_sum;
};

PetscErrorCode PPECreate(MPI_Comm comm, PPE *ppe);
/* KSP defaults CG + hypre BoomerAMG (GAMG when PETSc lacks hypre), GMRES when the matrix is not
 * symmetric (implicit solid rows), then the user's options. */
PetscErrorCode PPESetFromOptions(PPE ppe, PetscBool symmetric);
PetscErrorCode PPEView(PPE ppe, PetscViewer v);
PetscErrorCode PPEDestroy(PPE *ppe);
/* Give every row its global number (FIELD_ROW, ghosts refreshed).  Needs FIELD_FS and FIELD_RHO
 * of ghosts current. */
PetscErrorCode PPENumber(PPE ppe, Physics *ph);
/* Assemble the matrix and right-hand side; src[a] for owned fluid rows. */
PetscErrorCode PPEAssemble(PPE ppe, Physics *ph, const PetscReal *src);
/* Solve with the current pressure as initial guess; pressure of owned rows set, ghosts refreshed.
 * A solver failure is an error that names the KSP reason. */
PetscErrorCode PPESolve(PPE ppe, Physics *ph);
/* After a fault: say so when the solve was looser than the default tolerance (collective). */
PetscErrorCode PPEFaultHint(PPE ppe);
