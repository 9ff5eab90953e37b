#include "fluid/ppe.h"
#include "base/options_used.h"
#include "base/dim.h"
#include "particles/pair_loop.h"
#include "fluid/fluid_terms.h"
#include "base/kernel.h"
#include "fluid/boundary.h"

PetscErrorCode PPECreate(MPI_Comm comm, PPE *ppe)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(ppe));
  (*ppe)->comm = comm;
  PetscCall(KSPCreate(comm, &(*ppe)->ksp));
  PetscCall(KSPSetOptionsPrefix((*ppe)->ksp, "ppe_")); /* -ppe_ksp_rtol, -ppe_pc_type, ...: the other scheme never sees them */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* BoomerAMG's settings for the pressure equation where the options give none (those of the case
 * files that measured them, docs/performance.md items 3, 6 and 17): HMIS coarsening, ext+i
 * interpolation with at most 4 entries a row and one level of aggressive coarsening (a cheaper
 * set-up for more iterations), Gauss-Seidel forward on the way down and backward on the way up (a
 * symmetric V-cycle at half the smoothing), each level's transpose kept.  hypre's defaults (Falgout,
 * classical) cost 1.7x the run: Taylor-Green ISPH at L/100 (Wendland, 2 h = 4 dx), 2 ranks, 20.7 s
 * against 12.5 s with the same errors to 2 digits.  Only once the PC is known to be BoomerAMG, so that
 * no option is left unread under another preconditioner. */
static PetscErrorCode PPEBoomerAMGDefaults(PC pc)
{
#if defined(PETSC_HAVE_HYPRE)
  const char *prefix, *type, *defaults[][2] = {
    {"coarsen_type", "HMIS"}, {"interp_type", "ext+i"}, {"P_max", "4"}, {"agg_nl", "1"}, {"relax_type_down", "SOR/Jacobi"}, {"relax_type_up", "backward-SOR/Jacobi"}, {"keeptranspose", "1"},
  };
  PetscBool hypre, boomeramg, given, all, any = PETSC_FALSE;
  char      name[128];
#endif
  PetscFunctionBeginUser;
#if defined(PETSC_HAVE_HYPRE)
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hypre));
  if (!hypre) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PCHYPREGetType(pc, &type));
  PetscCall(PetscStrcmp(type, "boomeramg", &boomeramg));
  if (!boomeramg) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_hypre_boomeramg_relax_type_all", prefix ? prefix : ""));
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &all)); /* a smoother for all sweeps: none set down and up */
  for (size_t k = 0; k < sizeof(defaults) / sizeof(defaults[0]); k++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_hypre_boomeramg_%s", prefix ? prefix : "", defaults[k][0]));
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &given));
    if (given || (all && !strncmp(defaults[k][0], "relax_type_", 11))) continue;
    PetscCall(PetscOptionsSetValue(NULL, name, defaults[k][1]));
    any = PETSC_TRUE;
  }
  if (any) PetscCall(PCSetFromOptions(pc));
#endif
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPESetFromOptions(PPE ppe, PetscBool symmetric)
{
  PC pc;
  PetscFunctionBeginUser;
  ppe->symmetric = symmetric;
  PetscCall(KSPSetType(ppe->ksp, symmetric ? KSPCG : KSPGMRES));
  PetscCall(KSPGetPC(ppe->ksp, &pc));
#if defined(PETSC_HAVE_HYPRE)
  PetscCall(PCSetType(pc, PCHYPRE));
  PetscCall(PCHYPRESetType(pc, "boomeramg"));
#else
  PetscCall(PCSetType(pc, PCGAMG));
#endif
  PetscCall(KSPSetTolerances(ppe->ksp, PPE_RTOL_DEFAULT, 1e-50, PETSC_DEFAULT, 200));
  PetscCall(KSPSetInitialGuessNonzero(ppe->ksp, PETSC_TRUE)); /* last step's pressure */
  ppe->mat_hypre     = PETSC_TRUE;
  ppe->wall_approach = PETSC_TRUE;
  ppe->wall_clip     = PETSC_TRUE; /* a wall never pulls fluid; a clipped one leaves the corrected gradient's fit (isph.c) */
  PetscOptionsBegin(ppe->comm, "ppe_", "Pressure Poisson equation", "PPE");
  PetscCall(OptReal("-pc_qmax", "Build the preconditioner from the PPE without the pairs beyond r = q h (their weight goes to the diagonal); 0: from the PPE itself", "", ppe->pc_qmax, &ppe->pc_qmax, NULL));
  PetscCall(OptBool("-wall_approach", "Fixed walls stop the fluid that approaches them: their pressure rows take the projection's Neumann condition dP/dn = rho (v* - v*_wall) . n / dt for approaching fluid neighbours (not only rho g . n)", "", ppe->wall_approach, &ppe->wall_approach, NULL));
  PetscCall(OptBool("-wall_clip", "Clip a wall's pressure above the water line (its hydrostatic extrapolation is negative there) at min(0, its fluid's mean pressure), so that a wall never pulls fluid; a clipped wall particle is left out of the corrected gradient's plane fit; solids are always clipped", "", ppe->wall_clip, &ppe->wall_clip, NULL));
  PetscCall(OptBool("-mat_hypre", "With a hypre preconditioner: build the matrix it reads (the PPE, or the sparser one of -ppe_pc_qmax) in hypre's ParCSR format, sharing our arrays, instead of a PETSc AIJ matrix that hypre copies at every set-up", "", ppe->mat_hypre, &ppe->mat_hypre, NULL));
  PetscOptionsEnd();
  PetscCheck(ppe->pc_qmax >= 0, ppe->comm, PETSC_ERR_ARG_OUTOFRANGE, "-ppe_pc_qmax %g must be >= 0 (0: the preconditioner sees the whole matrix)", (double)ppe->pc_qmax);
  PetscCall(KSPSetFromOptions(ppe->ksp));
  PetscCall(PPEBoomerAMGDefaults(pc));
  { /* a direct solve (-ppe_ksp_type preonly -ppe_pc_type lu) takes no initial guess */
    PetscBool preonly;
    PetscCall(PetscObjectTypeCompare((PetscObject)ppe->ksp, KSPPREONLY, &preonly));
    if (preonly) PetscCall(KSPSetInitialGuessNonzero(ppe->ksp, PETSC_FALSE));
  }
  { /* -ppe_mat_hypre applies to a hypre preconditioner where hypre can share our arrays */
    PetscBool hypre;
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hypre));
    ppe->mat_hypre = (PetscBool)(ppe->mat_hypre && hypre && SplitCSRSharesWithHypre());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPEView(PPE ppe, PetscViewer v)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "Pressure Poisson equation (Eq. 22, 48):\n"));
  if (ppe->pc_qmax > 0) PetscCall(PetscViewerASCIIPrintf(v, "  preconditioner built without the fluid pairs beyond r = %g h (lumped into the diagonal)\n", (double)ppe->pc_qmax));
  if (ppe->mat_hypre) PetscCall(PetscViewerASCIIPrintf(v, "  the preconditioner's matrix built in hypre's format (-ppe_mat_hypre)\n"));
  PetscCall(PetscViewerASCIIPrintf(v, "  walls' rows: %s (-ppe_wall_approach)\n", ppe->wall_approach ? "rho0 (g + approach speed / dt) . n" : "rho0 g . n"));
  PetscCall(PetscViewerASCIIPrintf(v, "  walls' pressure above the water line %s (-ppe_wall_clip)\n", ppe->wall_clip ? "clipped" : "extrapolated, not clipped"));
  PetscCall(PetscViewerASCIIPushTab(v));
  PetscCall(KSPView(ppe->ksp, v));
  PetscCall(PetscViewerASCIIPopTab(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPEDestroy(PPE *ppe)
{
  PetscFunctionBeginUser;
  if (!*ppe) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPDestroy(&(*ppe)->ksp));
  PetscCall(MatDestroy(&(*ppe)->A));
  PetscCall(MatDestroy(&(*ppe)->Ap));
  PetscCall(SplitCSRDestroy(&(*ppe)->csr));
  PetscCall(SplitCSRDestroy(&(*ppe)->csrp));
  PetscCall(VecDestroy(&(*ppe)->x));
  PetscCall(VecDestroy(&(*ppe)->b));
  PetscCall(MatNullSpaceDestroy(&(*ppe)->nullsp));
  PetscCall(PetscFree2((*ppe)->rowpart, (*ppe)->hyd));
  PetscCall(PetscFree4((*ppe)->cols, (*ppe)->vals, (*ppe)->colsp, (*ppe)->valsp));
  PetscCall(PetscFree(*ppe));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Owned wall/dummy and solid particles take part only when some fluid particle is within reach. */
static PetscBool HasFluidNeighbour(Cells C, Particles P, PetscInt a)
{
  for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++)
    if (KindIsFluid(P->kind[C->nbr[k]])) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode PPENumber(PPE ppe, Physics *ph)
{
  Particles     P = ph->P;
  PetscReal    *row = PField(P, FIELD_ROW), *fs = PField(P, FIELD_FS);
  PetscInt      n = 0, cnt[3], nd = 0;
  const FieldId refresh[] = {FIELD_ROW};

  PetscFunctionBeginUser;
  if (P->n > ppe->cap_rows) {
    PetscCall(PetscFree2(ppe->rowpart, ppe->hyd));
    ppe->cap_rows = (PetscInt)(1.2 * P->n) + 16;
    PetscCall(PetscMalloc2(ppe->cap_rows, &ppe->rowpart, ppe->cap_rows, &ppe->hyd));
  }
  for (PetscInt a = 0; a < P->n; a++) {
    PetscBool r = KindIsFluid(P->kind[a]) || (KindIsBoundary(P->kind[a]) && HasFluidNeighbour(ph->cells, P, a));
    row[a]      = -1;
    if (!r) continue;
    ppe->rowpart[n++] = a;
    if (fs[a] > 0) nd++;
  }
  ppe->nrow = n;
  if (ph->decomp->log_stats) PetscCall(DecompLogRows(ph->decomp, n, ph->step));
  PetscCallMPI(MPI_Scan(&n, &ppe->rstart, 1, MPIU_INT, MPI_SUM, ppe->comm));
  ppe->rstart -= n;
  cnt[0] = n; cnt[1] = nd; cnt[2] = n == 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 3, MPIU_INT, MPI_SUM, ppe->comm));
  ppe->nrow_global = cnt[0]; ppe->ndirichlet_global = cnt[1]; ppe->nempty = cnt[2];
  for (PetscInt r = 0; r < n; r++) row[ppe->rowpart[r]] = (PetscReal)(ppe->rstart + r);
  PetscCall(HaloRefresh(ph->halo, P, 1, refresh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef enum { NBR_SKIP, NBR_KNOWN, NBR_UNKNOWN } NbrRole;

/* What neighbour b is in row a's equation: an unknown (column), a known pressure (free surface:
 * 0; the pinned row, ppe.h: 0), or absent: a wall or solid sees only fluid (its row is the implicit
 * form of the Adami extrapolation), a wall or solid outside every fluid particle's reach, a
 * periodic image of a. */
static inline NbrRole Role(Particles P, const PetscReal *row, const PetscReal *fs, PetscInt pin, PetscInt a, PetscInt b)
{
  if (KindIsBoundary(P->kind[a]) && !KindIsFluid(P->kind[b])) return NBR_SKIP;
  if (row[b] < 0) return NBR_SKIP;
  if (fs[b] > 0) return NBR_KNOWN;
  if (row[b] == row[a]) return NBR_SKIP;
  if (row[b] == (PetscReal)pin) return NBR_KNOWN;
  return NBR_UNKNOWN;
}

static inline PetscBool IsDirichlet(const PetscReal *fs, PetscInt a) { return (PetscBool)(fs[a] > 0); }

/* Whether pair k of a, with b, enters the preconditioner's matrix: a pair of fluid particles when
 * r <= pc_qmax h_ab, i.e. |F_ab| >= |F(pc_qmax h_ab)| (|F| falls with r), fa being that bound for
 * h_a; every pair with a wall (the outer wall layers reach the fluid only through far pairs).
 * Symmetric in a, b. */
static inline PetscBool InPC(PPE ppe, Particles P, Cells C, const PetscReal *h, PetscInt a, PetscInt k, PetscReal fa)
{
  PetscInt b = C->nbr[k];
  if (h[b] != h[a]) {
    PetscReal hab = PairH(h[a], h[b]);
    fa = KernelF(C->kernel, ppe->pc_qmax * hab, hab);
  }
  return (PetscBool)((PetscAbsReal(C->f[k]) >= PetscAbsReal(fa)) | !KindIsFluid(P->kind[a]) | !KindIsFluid(P->kind[b]));
}

/* pc: the matrix the preconditioner is built from; with hypre's, in hypre's format (-ppe_mat_hypre).
 * Not while a rank owns no row: PETSc 3.18's MatCreateFromParCSR gives such a rank one local row
 * (unless it is the last), which the solve then refuses ("Preconditioner number of local rows 1 does
 * not equal input vector size 0"); hypre then copies the AIJ matrix: the same run bit for bit
 * (csr_hypre.c, DiagonalFirst). */
static PetscErrorCode CreateMatrix(PPE ppe, SplitCSR *S, PetscBool pc, Mat *A)
{
  PetscFunctionBeginUser;
  if (pc && ppe->mat_hypre && !ppe->nempty) PetscCall(SplitCSRCreateHypreMat(S, ppe->comm, ppe->nrow_global, A));
  else PetscCall(SplitCSRCreateMat(S, ppe->comm, ppe->nrow_global, A));
  PetscCall(MatSetOption(*A, MAT_SYMMETRIC, ppe->symmetric));
  PetscCall(MatSetOption(*A, MAT_SYMMETRY_ETERNAL, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A new matrix for this step's rows (the rows are appended in PPEAssemble). */
static PetscErrorCode Reset(PPE ppe, Physics *ph)
{
  PetscFunctionBeginUser;
  /* The neighbour graph changes every step, so does the pattern: reset the KSP (it keeps its type
   * and options).  A multigrid PC keeps its levels through a reset, and they no longer fit:
   * rebuild it from its type and options.  Our vectors stay while the local row count does. */
  PetscCall(KSPReset(ppe->ksp));
  {
    PC        pc;
    PCType    type;
    PetscBool mg;
    PetscCall(KSPGetPC(ppe->ksp, &pc));
    PetscCall(PCGetType(pc, &type));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &mg, PCGAMG, PCMG, PCML, ""));
    if (mg) {
      char name[64];
      PetscCall(PetscStrncpy(name, type, sizeof(name)));
      PetscCall(PCSetType(pc, PCNONE));
      PetscCall(PCSetType(pc, name));
      PetscCall(PCSetFromOptions(pc));
    }
  }
  { /* creating vectors is collective: every rank decides alike */
    PetscInt m = -1, changed;
    if (ppe->x) PetscCall(VecGetLocalSize(ppe->x, &m));
    changed = m != ppe->nrow;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_INT, MPI_MAX, ppe->comm));
    if (changed) {
      PetscCall(VecDestroy(&ppe->x));
      PetscCall(VecDestroy(&ppe->b));
    }
  }
  PetscCall(MatDestroy(&ppe->A)); /* before its arrays may move */
  PetscCall(MatDestroy(&ppe->Ap));
  { /* a row has at most its particle's pairs and the diagonal */
    PetscInt bound = ph->cells->nstart[ph->P->n] + ppe->nrow;
    PetscCall(SplitCSRBegin(&ppe->csr, ppe->nrow, ppe->rstart, bound));
    if (ppe->pc_qmax > 0) PetscCall(SplitCSRBegin(&ppe->csrp, ppe->nrow, ppe->rstart, bound));
  }
  if (ph->cells->max_nbr + 1 > ppe->cap_cols) {
    PetscCall(PetscFree4(ppe->cols, ppe->vals, ppe->colsp, ppe->valsp));
    ppe->cap_cols = 2 * ph->cells->max_nbr + 16;
    PetscCall(PetscMalloc4(ppe->cap_cols, &ppe->cols, ppe->cap_cols, &ppe->vals, ppe->cap_cols, &ppe->colsp, ppe->cap_cols, &ppe->valsp));
  }
  if (!ppe->x) {
    PetscCall(VecCreate(ppe->comm, &ppe->x));
    PetscCall(VecSetSizes(ppe->x, ppe->nrow, ppe->nrow_global));
    PetscCall(VecSetFromOptions(ppe->x));
    PetscCall(VecDuplicate(ppe->x, &ppe->b));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Row of a solid particle that moves (ISPH + solid, -fsi_implicit): Adami's extrapolation with the
 * particle's acceleration a_s, sum_f c (P_f - P_s) + rho0 (g - a_s) . sum_f c r_sf = 0, where
 * a_s = a_last + A(P) - A(P_last): the particle's mean acceleration over the last fluid step
 * (none with -fsi_mean_acc 0), changed by what the change of the fluid's pressure does to it (A:
 * the reverse of the fluid's pair pressure forces over its mass, solid.c; linear in P_f and P_s,
 * taken implicitly).  A Robin condition in the manner of Fernandez et al. 2013: the pressure knows
 * that the solid gives way, so the fluid's added mass enters the solve.  A solid held at rest
 * during the solve (as a wall) makes the staggered coupling amplify by M_added / m_solid each step,
 * which blows up for the rubber gate (about 10); in equilibrium both agree.  Returns the
 * right-hand side; fills cols/vals. */
SPH_INLINE PetscReal MovingSolidRow(PPE ppe, Physics *ph, PetscInt a, PetscReal va, PetscInt *nc, const PetscInt D)
{
  Particles        P = ph->P;
  Cells            C = ph->cells;
  const PetscReal *row = PField(P, FIELD_ROW), *fs = PField(P, FIELD_FS), *x = PField(P, FIELD_X), *am = PField(P, FIELD_AMEAN);
  const PetscReal *rho = PField(P, FIELD_RHO), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *fv = PField(P, FIELD_FVIEW), *p = PField(P, FIELD_P);
  const PetscReal  rho0 = ph->fl.rho0;
  PetscReal        ma, ra, pa, R[3] = {0, 0, 0}, diag = 0, ediag = 0, kappa, rhs_last = 0, gam[3];
  PetscInt         n = 1;

  FluidView(fv, P->kind[a], a, m, rho, p, &ma, &ra, &pa);
  { /* the fluid's pair forces scale with its view of the mass; the response with the particle's
     * effective mass over the step, m + dt^2 k / 4 (Newmark's, with k ~ (K + 4G/3) dx the stiffness
     * of its bonds): a free particle when the step is short, held by the solid when it is long
     * against the solid's own waves (a stiff plate under water barely moves in a step).  With
     * -fsi_row_stiffness w the bonds enter as w dt^2 k / 4.  A row's inertia m_e well above the
     * solid's real one m_s makes the staggered coupling amplify (one mass under an added mass M_a,
     * with the last acceleration in the row: a factor M_a (m_s - m_e) / (m_s (m_e + M_a)) a step,
     * below -1 once m_e > 2 m_s at a large M_a).  A flag as dense as the water (Turek-Hron FSI3,
     * 3 ms steps) had m_e = 6.4 m against its column's share of 2 m: its lift changed sign every step,
     * growing 1.2x a step (measured); at m_e = 2 m and m it stayed calm.  w = 0 (m_e = m) cannot
     * exceed the real inertia. */
    const SolidMaterial *sm = &ph->sl;
    PetscReal            k = (sm->K + 4.0 * sm->G / 3.0) * h[a] / ph->kernel.h_factor;
    if (D == 3) k *= h[a] / ph->kernel.h_factor; /* the 2D k is per unit depth and was measured so; a 3D particle is a layer dx deep (a slab repeats the 2D run) */
    kappa = ma / (m[a] + ppe->row_stiffness * 0.25 * ph->dt * ph->dt * k);
  }
  for (PetscInt pass = 0; pass < 2; pass++)
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      NbrRole   role = Role(P, row, fs, ppe->pin, a, b);
      PetscReal d[3], c, e;
      if (role == NBR_SKIP) continue;
      VSub(x + D * a, x + D * b, d, D);
      c = PPECoefficient(m[b], ra, rho[b], C->f[k], VDot(d, d, D), PairH(h[a], h[b]), ph->fl.eta, ph->fl.lap_kappa);
      if (!pass) {
        for (PetscInt i = 0; i < D; i++) R[i] += c * d[i];
        continue;
      }
      e = rho0 * kappa * m[b] * C->f[k] * VDot(R, d, D); /* -rho0 R . A(P) = sum_f e (P_f / rho_f^2 + P_s / rho_s^2) */
      diag += c; ediag += e;
      rhs_last += e * (role == NBR_KNOWN ? 0 : p[b]) / (rho[b] * rho[b]);
      if (role == NBR_KNOWN) continue;
      ppe->cols[n] = (PetscInt)row[b]; ppe->vals[n++] = va * (c + e / (rho[b] * rho[b]));
    }
  rhs_last += ediag * pa / (ra * ra); /* -rho0 R . A(P_last) */
  ppe->vals[0] = diag != 0 ? va * (-diag + ediag / (ra * ra)) : va / (rho0 * h[a] * h[a]);
  *nc          = n;
  for (PetscInt i = 0; i < D; i++) gam[i] = ph->g[i] - (am ? am[D * a + i] : 0); /* -fsi_mean_acc 0: no field */
  return -va * (rho0 * VDot(gam, R, D) - rhs_last);
}

/* What a wall particle gathers in one pass over its pairs: over its wall and dummy neighbours b,
 * sum V_b F_ab (x_a - x_b) (V_b grad_a W_ab, towards the walls' volume), sum V_b |F_ab| r_ab (its size
 * on an even support) and, for a dummy, the nearest first-row neighbour with a normal; over its
 * fluid neighbours f, sum W_af (x_f - x_a) (towards its fluid). */
typedef struct {
  Particles        P;
  const PetscReal *x, *m, *wn;
  PetscReal        rho0, g[3], gabs, r2min, nf[3];
  PetscInt         nearest;
} WallGeometrySum;

SPH_INLINE void WallGeometryPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  WallGeometrySum *s = (WallGeometrySum *)ctx;
  PetscInt         b = p.b;
  PetscReal        d[3], r2, vb = s->m[b] / s->rho0;
  if (KindIsFluid(s->P->kind[b])) {
    for (PetscInt i = 0; i < D; i++) s->nf[i] += p.W * (s->x[D * b + i] - s->x[D * a + i]);
    return;
  }
  if (!KindIsWall(s->P->kind[b])) return;
  VSub(s->x + D * a, s->x + D * b, d, D);
  r2 = VDot(d, d, D);
  for (PetscInt i = 0; i < D; i++) s->g[i] += vb * p.F * d[i];
  s->gabs += vb * PetscAbsReal(p.F) * PetscSqrtReal(r2);
  if (s->wn && s->P->kind[b] == KIND_WALL && VDot(s->wn + D * b, s->wn + D * b, D) > 0 && r2 < s->r2min) {
    s->r2min   = r2;
    s->nearest = b;
  }
}

/* Each fixed wall particle's unit normal into the fluid, from the walls' geometry, into FIELD_WNORMAL
 * for the approach term (WallApproach): a first-row particle's is the direction away from the walls'
 * volume around it, -sum V_b grad_a W_ab over its wall and dummy neighbours (a flat wall's normal, a
 * corner's bisector), where that sum is at least a fifth of its size on an even support and on the
 * fluid's side; a dummy takes the nearest first-row particle's (refreshed at the ghosts).  Where
 * neither holds (a wall one particle thick), the direction of its fluid, the kernel-weighted centre
 * of its fluid neighbours.  Only the rows of the pressure equation need it.  With the direction of
 * its fluid instead, a floor under a thin layer running along it took the fluid behind it for its
 * side: the layer's speed along the floor counted as approach, and the floor's pressure rose to
 * 3.7-6.0 rho g H under a layer 0.13 H deep (the Lobovsky dam break at H/40; docs/impact.md,
 * tests/check_lobovsky.sh). */
SPH_INLINE PetscErrorCode WallNormalsD(PPE ppe, Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *row = PField(P, FIELD_ROW), *x = PField(P, FIELD_X), *m = PField(P, FIELD_M);
  PetscReal       *wn      = PField(P, FIELD_WNORMAL);
  const FieldId    field[] = {FIELD_WNORMAL};

  PetscFunctionBeginUser;
  for (PetscInt pass = 0; pass < 2; pass++) { /* first-row particles, then (after the halo) dummies */
    for (PetscInt a = 0; a < P->n; a++) {
      PetscReal *n = wn + D * a, gn, nn;
      if (pass == 0)
        for (PetscInt i = 0; i < D; i++) n[i] = 0;
      if (row[a] < 0 || P->kind[a] != (pass == 0 ? KIND_WALL : KIND_DUMMY)) continue;
      WallGeometrySum s = {.P = P, .x = x, .m = m, .wn = pass ? wn : NULL, .rho0 = ph->fl.rho0, .r2min = PETSC_MAX_REAL, .nearest = -1};
      SPHPairsW(ph->cells, P, a, PETSC_TRUE, WallGeometryPair, &s, D);
      gn = PetscSqrtReal(VDot(s.g, s.g, D));
      nn = PetscSqrtReal(VDot(s.nf, s.nf, D));
      if (pass == 1 && s.nearest >= 0)
        for (PetscInt i = 0; i < D; i++) n[i] = wn[D * s.nearest + i];
      else if (pass == 0 && gn > 0.2 * s.gabs && -VDot(s.g, s.nf, D) > 0)
        for (PetscInt i = 0; i < D; i++) n[i] = -s.g[i] / gn;
      else if (nn > 0)
        for (PetscInt i = 0; i < D; i++) n[i] = s.nf[i] / nn;
    }
    if (pass == 0) PetscCall(HaloRefresh(ph->halo, P, 1, field));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The wall's share of the projection's Neumann condition dP/dn = rho (v* - v*_wall) . n / dt for a
 * fluid neighbour f approaching wall particle w (times dt / rho0): its approach speed along the
 * wall's normal n (FIELD_WNORMAL; a solid's rows take none) times its distance from the wall along
 * n, (x_f - x_w) = -d.  Walls at rest take v* = dt g like the fluid, so the difference is the
 * fluid's own velocity.  One-sided: fluid moving away from a wall is not pulled back. */
SPH_INLINE PetscReal WallApproach(const PetscReal vf[], const PetscReal vw[], const PetscReal n[], const PetscReal d[], const PetscInt D)
{
  PetscReal dv[3], un, dn;
  VSub(vf, vw, dv, D);
  un = -VDot(dv, n, D);
  dn = -VDot(d, n, D);
  return PetscMax(un, 0) * PetscMax(dn, 0);
}

/* The rows of this rank (Eq. 22 with the free-surface, wall and solid rows of ppe.h) in D dimensions. */
SPH_INLINE PetscErrorCode AssembleRowsD(PPE ppe, Physics *ph, const PetscReal *src, PetscScalar *bb, const PetscInt D)
{
  Particles        P = ph->P;
  Cells            C = ph->cells;
  const PetscReal *row = PField(P, FIELD_ROW), *fs = PField(P, FIELD_FS), *x = PField(P, FIELD_X);
  const PetscReal *rho = PField(P, FIELD_RHO), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *fv = PField(P, FIELD_FVIEW);
  const PetscReal  rho0 = ph->fl.rho0;
  const PetscBool  sparse = (PetscBool)(ppe->pc_qmax > 0);
  const PetscReal *vs = PField(P, FIELD_VSTAR), *wn = PField(P, FIELD_WNORMAL);

  PetscFunctionBeginUser;
  for (PetscInt r = 0; r < ppe->nrow; r++) {
    PetscInt  a = ppe->rowpart[r], ga = ppe->rstart + r, nc = 1;
    PetscReal ma, ra, pa, va, diag = 0, hyd = 0, lumped = 0, fa = sparse ? KernelF(&ph->kernel, ppe->pc_qmax * h[a], h[a]) : 0;
    PetscInt  ncp = 1;
    PetscBool wall = KindIsBoundary(P->kind[a]), dir = (PetscBool)(IsDirichlet(fs, a) || ga == ppe->pin);
    PetscBool approach = (PetscBool)(ppe->wall_approach && KindIsWall(P->kind[a])); /* fixed walls; a solid's rows keep rho0 g . n */
    const PetscReal *nw = approach ? wn + D * a : NULL;
    FluidView(fv, P->kind[a], a, m, rho, NULL, &ma, &ra, &pa);
    va = ma / rho0;
    if (!ppe->symmetric && P->kind[a] == KIND_SOLID) {
      ppe->cols[0] = ga;
      ppe->hyd[r]  = 0;
      bb[r]        = MovingSolidRow(ppe, ph, a, va, &nc, D);
      PetscCall(SplitCSRAppendRow(&ppe->csr, nc, ppe->cols, ppe->vals));
      if (sparse) PetscCall(SplitCSRAppendRow(&ppe->csrp, nc, ppe->cols, ppe->vals));
      continue;
    }
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      NbrRole   role = Role(P, row, fs, ppe->pin, a, b);
      PetscReal d[3], r2, c, mb, rb, pb;
      if (role == NBR_SKIP) continue;
      FluidView(fv, P->kind[b], b, m, rho, NULL, &mb, &rb, &pb);
      VSub(x + D * a, x + D * b, d, D);
      r2 = VDot(d, d, D);
      c  = PPECoefficient(mb, ra, rb, C->f[k], r2, PairH(h[a], h[b]), ph->fl.eta, ph->fl.lap_kappa);
      diag += c;
      if (wall) hyd += c * rho0 * VDot(ph->g, d, D); /* L_a(rho0 g . r) */
      if (approach) hyd += c * rho0 * WallApproach(vs + D * b, vs + D * a, nw, d, D) / ph->dt;
      if (dir || role == NBR_KNOWN) continue; /* free surface: P = 0 */
      ppe->cols[nc] = (PetscInt)row[b]; ppe->vals[nc++] = va * c;
      if (!sparse) continue;
      { /* without a branch: whether a pair is kept is unpredictable */
        PetscInt keep = InPC(ppe, P, C, h, a, k, fa);
        ppe->colsp[ncp] = (PetscInt)row[b]; ppe->valsp[ncp] = va * c;
        ncp += keep;
        lumped += (1 - keep) * c; /* left out of Ap and off its diagonal: the row sum stays */
      }
    }
    ppe->cols[0] = ga;
    ppe->vals[0] = -va * diag;
    ppe->colsp[0] = ga;
    ppe->hyd[r]  = wall && diag != 0 ? hyd / diag : 0; /* P_a = mean_c(P_f) + hyd[r] */
    if (diag == 0) ppe->vals[0] = va / (rho0 * h[a] * h[a]); /* isolated free-surface particle */
    if (dir) nc = ncp = 1;
    bb[r] = IsDirichlet(fs, a) ? 0 : -va * (wall ? hyd : src[a]); /* the pinned row's own: PPEAssemble */
    /* Ap's diagonal: without the pairs left out; a row whose pairs were all far keeps A's */
    ppe->valsp[0] = dir || PetscAbsReal(diag - lumped) <= 1e-9 * PetscAbsReal(diag) ? ppe->vals[0] : -va * (diag - lumped);
    PetscCall(SplitCSRAppendRow(&ppe->csr, nc, ppe->cols, ppe->vals));
    if (sparse) PetscCall(SplitCSRAppendRow(&ppe->csrp, ncp, ppe->colsp, ppe->valsp));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPEAssemble(PPE ppe, Physics *ph, const PetscReal *src)
{
  const PetscBool  sparse = (PetscBool)(ppe->pc_qmax > 0);
  PetscScalar     *bb;

  PetscFunctionBeginUser;
  ppe->pin = ppe->ndirichlet_global ? -1 : 0; /* no free surface: P = 0 at global row 0 (ppe.h) */
  PetscCall(Reset(ppe, ph));
  if (ppe->wall_approach) PetscCall(SPH_DIM_DISPATCH(ph->dim, WallNormalsD, ppe, ph));
  PetscCall(VecGetArrayWrite(ppe->b, &bb));
  PetscCall(SPH_DIM_DISPATCH(ph->dim, AssembleRowsD, ppe, ph, src, bb));
  PetscCall(VecRestoreArrayWrite(ppe->b, &bb));
  PetscCall(CreateMatrix(ppe, &ppe->csr, (PetscBool)!sparse, &ppe->A));
  if (sparse) PetscCall(CreateMatrix(ppe, &ppe->csrp, PETSC_TRUE, &ppe->Ap));
  if (ppe->pin >= 0) { /* no free surface: P is defined up to a constant; a right-hand side with a
                        * zero sum makes the pinned row's dropped equation hold as well.  The sum
                        * takes that row's own right-hand side, set to 0 (P = 0) only after it: zeroed
                        * before, the other rows missed its share and the pinned row kept minus the
                        * mean (P != 0 there, though the other rows take it as 0); the answer then
                        * depended on which particle is global row 0, and 1 and 2 ranks differed by
                        * 9e-4 (Taylor-Green, dx 0.01) */
    if (!ppe->nullsp) PetscCall(MatNullSpaceCreate(ppe->comm, PETSC_TRUE, 0, NULL, &ppe->nullsp));
    PetscCall(MatNullSpaceRemove(ppe->nullsp, ppe->b));
    if (ppe->pin >= ppe->rstart && ppe->pin < ppe->rstart + ppe->nrow) {
      PetscCall(VecGetArray(ppe->b, &bb));
      bb[ppe->pin - ppe->rstart] = 0;
      PetscCall(VecRestoreArray(ppe->b, &bb));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPESolve(PPE ppe, Physics *ph)
{
  Particles          P = ph->P;
  PetscReal         *p = PField(P, FIELD_P), *fv = PField(P, FIELD_FVIEW), *fs = PField(P, FIELD_FS);
  PetscScalar       *xx;
  PetscInt           its;
  PetscReal          mean0 = 0;
  KSPConvergedReason reason;
  const FieldId      refresh[] = {FIELD_P, FIELD_FS, FIELD_FVIEW};

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayWrite(ppe->x, &xx));
  for (PetscInt r = 0; r < ppe->nrow; r++) {
    PetscInt a = ppe->rowpart[r];
    xx[r]      = KindIsSolid(P->kind[a]) ? fv[3 * a] : p[a];
  }
  PetscCall(VecRestoreArrayWrite(ppe->x, &xx));
  PetscCall(KSPSetOperators(ppe->ksp, ppe->A, ppe->Ap ? ppe->Ap : ppe->A));
  if (ppe->pin >= 0) { /* the last pressure less its value at the pinned row (P = 0 there); the mean to restore */
    PetscReal    s[2] = {0, 0};
    PetscInt     N;
    const PetscScalar *xr;
    PetscCall(VecGetArrayRead(ppe->x, &xr));
    for (PetscInt r = 0; r < ppe->nrow; r++) s[0] += xr[r];
    if (ppe->pin >= ppe->rstart && ppe->pin < ppe->rstart + ppe->nrow) s[1] = xr[ppe->pin - ppe->rstart];
    PetscCall(VecRestoreArrayRead(ppe->x, &xr));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPIU_SUM, ppe->comm));
    PetscCall(VecGetSize(ppe->x, &N));
    mean0 = s[0] / N;
    PetscCall(VecShift(ppe->x, -s[1]));
  }
  PetscCall(KSPSolve(ppe->ksp, ppe->b, ppe->x));
  if (ppe->pin >= 0) { /* the pressure keeps the mean of the last one, as a solve on the null space's complement */
    PetscScalar s;
    PetscInt    N;
    PetscCall(VecSum(ppe->x, &s));
    PetscCall(VecGetSize(ppe->x, &N));
    PetscCall(VecShift(ppe->x, mean0 - s / N));
  }
  PetscCall(KSPGetConvergedReason(ppe->ksp, &reason));
  PetscCall(KSPGetIterationNumber(ppe->ksp, &its));
  PetscCheck(reason >= 0, ppe->comm, PETSC_ERR_NOT_CONVERGED, "The pressure Poisson solve did not converge at step %" PetscInt_FMT " (t = %g): KSP reason %s after %" PetscInt_FMT " iterations. Try a smaller -dt/-cfl, a larger -ppe_ksp_max_it, or another -ppe_ksp_type/-ppe_pc_type", ph->step, (double)ph->t, KSPConvergedReasons[reason], its);
  ppe->nsolve++;
  ppe->its_last = its;
  ppe->its_sum += its;
  ppe->its_max = PetscMax(ppe->its_max, its);
  for (PetscInt a = 0; a < P->n; a++) { /* walls and solids out of reach of the fluid */
    if (KindIsWall(P->kind[a])) p[a] = 0;
    if (fv && KindIsSolid(P->kind[a])) fv[3 * a] = 0;
  }
  PetscCall(VecGetArrayRead(ppe->x, (const PetscScalar **)&xx));
  for (PetscInt r = 0; r < ppe->nrow; r++) {
    PetscInt a = ppe->rowpart[r];
    /* a wall above the water line extrapolates a negative pressure that would pull fluid onto it:
     * clip that, but not below the fluid's own (mean) pressure, which the solve balanced; a moving
     * solid's pressure is what its motion needs */
    PetscReal pw = PetscMax(xx[r], PetscMin(xx[r] - ppe->hyd[r], 0.0));
    if (P->kind[a] == KIND_SOLID && !ppe->symmetric) fv[3 * a] = xx[r];
    else if (KindIsSolid(P->kind[a])) fv[3 * a] = pw;
    else if (KindIsWall(P->kind[a]) && ppe->wall_clip) {
      p[a]  = pw;
      fs[a] = pw != xx[r] ? 1.0 : 0.0; /* a dry wall: the corrected gradient leaves it out (isph.c) */
    } else p[a] = xx[r];
  }
  PetscCall(VecRestoreArrayRead(ppe->x, (const PetscScalar **)&xx));
  PetscCall(HaloRefresh(ph->halo, P, fv ? 3 : 2, refresh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PPEFaultHint(PPE ppe)
{
  PetscReal rtol;
  PetscFunctionBeginUser;
  PetscCall(KSPGetTolerances(ppe->ksp, &rtol, NULL, NULL, NULL));
  if (rtol > PPE_RTOL_DEFAULT) PetscCall(PetscPrintf(ppe->comm, "sphfsi: the pressure equation was solved to -ppe_ksp_rtol %g, looser than the default %g: try the default first (docs/convergence.md)\n", (double)rtol, (double)PPE_RTOL_DEFAULT));
  PetscFunctionReturn(PETSC_SUCCESS);
}
