/* Plane Poiseuille flow started from rest (Morris, Fox & Zhu 1997): a channel of height
 * Hc between fixed walls at y = 0 and y = Hc, periodic in x, driven by a body force F in x.
 * Steady profile u(y) = F / (2 nu) y (Hc - y), u_max = F Hc^2 / (8 nu), Re = u_max Hc / nu.
 * Defaults: Hc = 1 mm, nu = 1e-6 m^2/s, Re = 0.0125, i.e. F = 1e-4 m/s^2, u_max = 1.25e-5 m/s. */
#include <sphfsi.h>

typedef struct {
  PetscReal Hc, Lc, Re, nu;
  PetscInt  nx, ny, rows;
  Series    uc_ref;                 /* analytic u_center at each probe (same particles) */
  PetscReal uc_last, l2_last, t_last;
} Poiseuille;

static PetscErrorCode Create(Sim sim)
{
  Poiseuille *c;
  PetscReal   F;
  PetscInt    nmin = (PetscInt)PetscCeilReal(3 * 2 * SimKernelHFactor(sim)); /* the periodic grid needs >= 3 cells of 2 h */
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->uc_ref));
  PetscCall(SceneKeepReal(sim, &c->uc_last));
  PetscCall(SceneKeepReal(sim, &c->l2_last));
  PetscCall(SceneKeepReal(sim, &c->t_last));
  c->Hc = 1e-3; c->Re = 0.0125; c->nu = 1e-6;
  c->rows = SimKernelRows(sim); /* wall rows covering the kernel support 2h */
  PetscOptionsBegin(SimComm(sim), NULL, "Scene poiseuille: body-force driven channel flow from rest (Morris et al. 1997); nu = 1e-6 m^2/s (mu = rho0 nu), F = 8 nu^2 Re / Hc^3 (Re 0.0125, Hc 1 mm: F = 1e-4 m/s^2, u_max = 1.25e-5 m/s)", "");
  PetscCall(OptReal("-channel_height", "Channel height Hc between the walls (m)", "", c->Hc, &c->Hc, NULL));
  PetscCall(OptReal("-re", "Reynolds number u_max Hc / nu; sets the body force F = 8 nu^2 Re / Hc^3", "", c->Re, &c->Re, NULL));
  PetscOptionsEnd();
  PetscCheck(c->Hc > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-channel_height %g must be > 0", (double)c->Hc);
  PetscCheck(c->Re > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-re %g must be > 0", (double)c->Re);
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->Hc / 20));
  /* the fluid rows (j + 1/2) dx must fill the channel exactly: dx = Hc / ny */
  c->ny = RoundToInt(c->Hc / SimSpacing(sim));
  PetscCheck(c->ny >= 4, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves fewer than 4 particle rows across the channel height %g: choose -dx <= %g", (double)SimSpacing(sim), (double)c->Hc, (double)(c->Hc / 4));
  if (PetscAbsReal(SimSpacing(sim) - c->Hc / c->ny) > 1e-12 * c->Hc) PetscCall(PetscInfo(NULL, "poiseuille: -dx %g rounded to %g = Hc / %" PetscInt_FMT "\n", (double)SimSpacing(sim), (double)(c->Hc / c->ny), c->ny));
  PetscCall(SimSetSpacing(sim, c->Hc / c->ny));
  /* periodic length Lc = nx dx (a whole number of lattice columns): Hc / 2, or the grid's minimum */
  c->nx = PetscMax(RoundToInt(0.5 * c->Hc / SimSpacing(sim)), nmin);
  c->Lc = c->nx * SimSpacing(sim);
  F     = 8 * c->nu * c->nu * c->Re / (c->Hc * c->Hc * c->Hc);
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 2 * c->Hc * c->Hc / c->nu)); /* transient ~ exp(-pi^2 nu t / Hc^2): 3e-9 left */
  PetscCall(SimSetConfined(sim, PETSC_TRUE)); /* no free surface */
  PetscCall(SimSetPeriodic(sim, 0, PETSC_TRUE));
  PetscCall(SimSetPeriodic(sim, 1, PETSC_FALSE));
  PetscCall(SimSetDomain(sim, 0, 0, c->Lc));
  PetscCall(SimSetDomain(sim, 1, -(c->rows + 0.5) * SimSpacing(sim), c->Hc + (c->rows + 0.5) * SimSpacing(sim)));
  PetscCall(SimSetGravity(sim, F, 0, SimGravity(sim)[2]));
  SimFluidMaterial(sim)->mu       = SimFluidMaterial(sim)->rho0 * c->nu;
  PetscCall(SimSetReferenceSpeed(sim, F * c->Hc * c->Hc / (8 * c->nu)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Poiseuille *c  = (Poiseuille *)SimSceneContext(sim);
  PetscReal   dx = SimSpacing(sim);
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dx, 0.5 * dx, c->nx, c->ny, dx, SimFluidMaterial(sim)->rho0));
  /* straight walls over the whole period, below y = 0 and above y = Hc: first row wall, then dummy */
  for (PetscInt k = 0; k < c->rows; k++) {
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, 0.5 * dx, -(k + 0.5) * dx, c->nx, 1, dx, SimFluidMaterial(sim)->rho0));
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, 0.5 * dx, c->Hc + (k + 0.5) * dx, c->nx, 1, dx, SimFluidMaterial(sim)->rho0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Transient solution from rest (Morris et al. 1997, Eq. 21, with the sign of the steady part
 * corrected so that the flow goes along +F):
 *   u(y, t) = F / (2 nu) y (Hc - y) - sum_{n odd} 4 F Hc^2 / (nu pi^3 n^3) sin(n pi y / Hc) exp(-n^2 pi^2 nu t / Hc^2). */
static PetscReal Exact(PetscReal F, PetscReal nu, PetscReal Hc, PetscReal y, PetscReal t)
{
  PetscReal u = F / (2 * nu) * y * (Hc - y), a = PETSC_PI * PETSC_PI * nu * t / (Hc * Hc), c = 4 * F * Hc * Hc / (nu * PETSC_PI * PETSC_PI * PETSC_PI);
  if (t <= 0) return 0; /* the series sums to the steady profile exactly at t = 0 */
  for (PetscInt n = 1;; n += 2) {
    PetscReal e = PetscExpReal(-n * n * a) / (n * n * n);
    u -= c * e * PetscSinReal(n * PETSC_PI * y / Hc);
    if (e < 1e-16) break;
  }
  return u;
}

/* u_center: mean x-velocity of the fluid particles within 0.75 dx of y = Hc / 2 (the two middle rows
 * at +-dx/2 for an even number of rows, the middle row for an odd one); its reference is the
 * analytic u averaged over the same particles.  l2_vel_err: sqrt(sum ((u - u_exact)^2 + v^2) /
 * sum u_exact^2) over all fluid particles, u_exact from the transient series above. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Poiseuille *c = (Poiseuille *)SimSceneContext(sim);
  const PetscReal *x, *v;
  const PetscInt  *kind;
  PetscReal        s[5] = {0, 0, 0, 0, 0}, nu = SimFluidMaterial(sim)->mu / SimFluidMaterial(sim)->rho0, F = SimGravity(sim)[0];
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal y = x[2 * a + 1], ue, du;
    if (!KindIsFluid(kind[a])) continue;
    ue = Exact(F, nu, c->Hc, y, SimTime(sim));
    du = v[2 * a] - ue;
    s[0] += du * du + v[2 * a + 1] * v[2 * a + 1];
    s[1] += ue * ue;
    if (PetscAbsReal(y - 0.5 * c->Hc) < 0.75 * SimSpacing(sim)) { s[2] += v[2 * a]; s[3] += ue; s[4] += 1; }
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 5, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = s[4] > 0 ? s[2] / s[4] : 0;
  vals[1] = s[1] > 0 ? PetscSqrtReal(s[0] / s[1]) : 0;
  PetscCall(SeriesAppend(&c->uc_ref, SimTime(sim), s[4] > 0 ? s[3] / s[4] : 0));
  c->uc_last = vals[0];
  c->l2_last = vals[1];
  c->t_last  = SimTime(sim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* At the final time: u_center against the analytic value, and the profile's L2 error. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Poiseuille *c = (Poiseuille *)SimSceneContext(sim);
  PetscReal   vals[2], ref, nu = SimFluidMaterial(sim)->mu / SimFluidMaterial(sim)->rho0, umax;
  PetscFunctionBeginUser;
  if (c->t_last != SimTime(sim)) PetscCall(Probe(sim, vals)); /* the last probe row may predate t_end */
  ref  = c->uc_ref.y[c->uc_ref.n - 1];
  umax = SimGravity(sim)[0] * c->Hc * c->Hc / (8 * nu);
  if (f)
    fprintf(f, "\"u_center_rel_err_final\": %.6g, \"u_center_final\": %.9g, \"u_center_exact\": %.9g, \"u_max_steady\": %.9g, \"l2_vel_err_final\": %.6g, \"t_final\": %.9g, \"re\": %.6g, \"reference\": \"Morris et al. 1997 Eq. 21 (transient series)\"",
            (double)(ref != 0 ? PetscAbsReal(c->uc_last - ref) / PetscAbsReal(ref) : 0), (double)c->uc_last, (double)ref, (double)umax, (double)c->l2_last, (double)SimTime(sim), (double)(umax * c->Hc / nu));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Poiseuille *c = (Poiseuille *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->uc_ref));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps ScenePoiseuille = {
  .name = "poiseuille", .help = "body-force driven channel flow from rest (Morris et al. 1997)",
  .create = Create, .populate = Populate,
  .nprobes = 2, .probe_names = {"u_center", "l2_vel_err"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
