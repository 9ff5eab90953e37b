/* Taylor-Green vortices in a doubly periodic square of side L: the decaying solution of the
 * Navier-Stokes equations
 *   u = U e^{-b t} sin(k x) cos(k y),  v = -U e^{-b t} cos(k x) sin(k y),
 *   p = rho0 U^2 / 4 e^{-2 b t} (cos(2 k x) + cos(2 k y)),   k = 2 pi / L,  b = 2 nu k^2 = 8 pi^2 nu / L^2,
 * so the kinetic energy decays as e^{-2 b t} = e^{-16 pi^2 nu t / L^2}.  (The form u = -U cos(kx) sin(ky),
 * v = U sin(kx) cos(ky) is this field shifted by L/4 in x and y; its pressure has the opposite sign.)
 * With -dim 3 the same field fills a triply periodic cube of side L, uniform in z (w = 0): still an
 * exact solution, which checks the 3D operators and the periodic images in every direction. */
#include <sphfsi.h>

typedef struct {
  PetscReal L, U, Re;
  PetscReal p0;     /* a uniform pressure added to the exact field (the continuum's flow ignores it) */
  PetscReal E0;     /* kinetic energy of the initial particle state */
  PetscReal e_last; /* last probed kinetic energy and velocity error, and their time */
  PetscReal l2_last, t_last;
} TaylorGreen;

static PetscErrorCode Create(Sim sim)
{
  TaylorGreen *c;
  PetscInt     n;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepReal(sim, &c->e_last));
  PetscCall(SceneKeepReal(sim, &c->l2_last));
  PetscCall(SceneKeepReal(sim, &c->t_last));
  c->L = 1.0; c->U = 1.0; c->Re = 100;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene taylor_green: decaying vortices in a periodic unit square (L = 1 m, U = 1 m/s)", "");
  PetscCall(OptReal("-re", "Reynolds number U L / nu; sets mu = rho0 U L / Re (a later -fluid_mu overrides)", "", c->Re, &c->Re, NULL));
  PetscCall(OptReal("-taylor_green_p0", "A uniform pressure (Pa) added to the initial field: the continuum ignores it, SPH's pressure term does not (its effect measures the particles' disorder)", "", c->p0, &c->p0, NULL));
  {
    PetscInt dim = SimDim(sim);
    PetscCall(OptInt("-dim", "Dimension: 2, or 3 for the same vortices in a periodic cube (uniform in z)", "", dim, &dim, NULL));
    PetscCall(SimSetDim(sim, dim));
  }
  PetscOptionsEnd();
  PetscCheck(SimDim(sim) == 2 || SimDim(sim) == 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dim %" PetscInt_FMT " must be 2 or 3", SimDim(sim));
  PetscCheck(c->Re > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-re %g must be > 0", (double)c->Re);
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->L / 50));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 1.0));
  /* the lattice must tile the period exactly: dx = L / n */
  n = RoundToInt(c->L / SimSpacing(sim));
  PetscCheck(n >= 8, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves fewer than 8 particles across the %g m period: choose -dx <= %g", (double)SimSpacing(sim), (double)c->L, (double)(c->L / 8));
  if (PetscAbsReal(SimSpacing(sim) - c->L / n) > 1e-12 * c->L) PetscCall(PetscInfo(NULL, "taylor_green: -dx %g rounded to %g = L / %" PetscInt_FMT "\n", (double)SimSpacing(sim), (double)(c->L / n), n));
  PetscCall(SimSetSpacing(sim, c->L / n));
  PetscCall(SimSetConfined(sim, PETSC_TRUE)); /* no free surface */
  for (PetscInt d = 0; d < SimDim(sim); d++) {
    PetscCall(SimSetPeriodic(sim, d, PETSC_TRUE));
    PetscCall(SimSetDomain(sim, d, 0, c->L));
  }
  PetscCall(SimSetGravity(sim, 0, 0, SimDim(sim) == 3 ? 0 : SimGravity(sim)[2]));
  SimFluidMaterial(sim)->mu = SimFluidMaterial(sim)->rho0 * c->U * c->L / c->Re;
  PetscCall(SimSetReferenceSpeed(sim, c->U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Exact velocity at (x, y, t) */
static inline void Exact(const TaylorGreen *c, PetscReal nu, PetscReal t, const PetscReal *x, PetscReal ve[2])
{
  PetscReal k = 2 * PETSC_PI / c->L, A = c->U * PetscExpReal(-2 * nu * k * k * t);
  ve[0] = A * PetscSinReal(k * x[0]) * PetscCosReal(k * x[1]);
  ve[1] = -A * PetscCosReal(k * x[0]) * PetscSinReal(k * x[1]);
}

static PetscErrorCode Populate(Sim sim)
{
  TaylorGreen *c = (TaylorGreen *)SimSceneContext(sim);
  PetscReal   *x, *v, *p, *rho, *m, dx = SimSpacing(sim), k = 2 * PETSC_PI / c->L, E = 0;
  PetscInt     n = RoundToInt(c->L / dx), D = SimDim(sim), np;
  PetscFunctionBeginUser;
  const PetscReal rho_level = c->p0 != 0 ? EOSDensity(SimFluidMaterial(sim), c->p0) : SimFluidMaterial(sim)->rho0; /* the particles' masses: the lattice at the level's density */
  if (D == 3) PetscCall(SceneAddBlock(sim, KIND_FLUID, (PetscReal[]){0.5 * dx, 0.5 * dx, 0.5 * dx}, (PetscInt[]){n, n, n}, dx, rho_level));
  else PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dx, 0.5 * dx, n, n, dx, rho_level));
  PetscCall(SimGetLocalSize(sim, &np));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  PetscCall(SimGetField(sim, "p", NULL, &p));
  PetscCall(SimGetField(sim, "rho", NULL, &rho));
  PetscCall(SimGetField(sim, "m", NULL, &m));
  for (PetscInt a = 0; a < np; a++) {
    Exact(c, 0, 0, &x[D * a], &v[D * a]); /* w = 0 in 3D */
    /* exact pressure at t = 0, density through the EOS (Eq. 20) */
    p[a]   = 0.25 * SimFluidMaterial(sim)->rho0 * c->U * c->U * (PetscCosReal(2 * k * x[D * a]) + PetscCosReal(2 * k * x[D * a + 1])) + c->p0;
    rho[a] = EOSDensity(SimFluidMaterial(sim), p[a]);
    E += 0.5 * m[a] * (v[D * a] * v[D * a] + v[D * a + 1] * v[D * a + 1]);
  }
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCall(SimRestoreField(sim, "p", NULL, &p));
  PetscCall(SimRestoreField(sim, "rho", NULL, &rho));
  PetscCall(SimRestoreField(sim, "m", NULL, &m));
  PetscCall(MPIU_Allreduce(&E, &c->E0, 1, MPIU_REAL, MPI_SUM, SimComm(sim)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* e_kin = 1/2 sum m |v|^2 over fluid; l2_vel_err = sqrt(sum |v - v_exact|^2 / sum |v_exact|^2),
 * v_exact at the particles' current positions and time. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  TaylorGreen *c = (TaylorGreen *)SimSceneContext(sim);
  const PetscReal *x, *v, *m;
  const PetscInt  *kind;
  PetscReal        s[3] = {0, 0, 0}, nu = SimFluidMaterial(sim)->mu / SimFluidMaterial(sim)->rho0;
  PetscInt         D = SimDim(sim), n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  PetscCall(SimGetField(sim, "m", NULL, &m));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal ve[2], ex, ey;
    if (!KindIsFluid(kind[a])) continue;
    Exact(c, nu, SimTime(sim), &x[D * a], ve);
    ex = v[D * a] - ve[0]; ey = v[D * a + 1] - ve[1];
    s[0] += 0.5 * m[a] * (v[D * a] * v[D * a] + v[D * a + 1] * v[D * a + 1]);
    s[1] += ex * ex + ey * ey;
    if (D == 3) { /* w: exactly 0 */
      s[0] += 0.5 * m[a] * v[D * a + 2] * v[D * a + 2];
      s[1] += v[D * a + 2] * v[D * a + 2];
    }
    s[2] += ve[0] * ve[0] + ve[1] * ve[1];
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCall(SimRestoreField(sim, "m", NULL, &m));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 3, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0]    = s[0];
  vals[1]    = s[2] > 0 ? PetscSqrtReal(s[1] / s[2]) : 0;
  c->e_last  = vals[0];
  c->l2_last = vals[1];
  c->t_last  = SimTime(sim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* At the final time: E(t)/E(0) against e^{-16 pi^2 nu t / L^2}, and the velocity error. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  TaylorGreen *c = (TaylorGreen *)SimSceneContext(sim);
  PetscReal    vals[2], nu = SimFluidMaterial(sim)->mu / SimFluidMaterial(sim)->rho0, ratio, exact;
  PetscFunctionBeginUser;
  if (c->t_last != SimTime(sim)) PetscCall(Probe(sim, vals)); /* the last probe row may predate t_end */
  ratio = c->e_last / c->E0;
  exact = PetscExpReal(-16 * PETSC_PI * PETSC_PI * nu * SimTime(sim) / (c->L * c->L));
  if (f)
    fprintf(f, "\"e_kin_rel_err_final\": %.6g, \"e_kin_ratio_final\": %.9g, \"e_kin_ratio_exact\": %.9g, \"l2_vel_err_final\": %.6g, \"t_final\": %.9g, \"re\": %.6g, \"reference\": \"Taylor-Green analytic decay\"",
            (double)(PetscAbsReal(ratio - exact) / exact), (double)ratio, (double)exact, (double)c->l2_last, (double)SimTime(sim), (double)(c->U * c->L / nu));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  void *c = SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneTaylorGreen = {
  .name = "taylor_green", .help = "decaying Taylor-Green vortices in a periodic unit square (-dim 3: a periodic cube)",
  .create = Create, .populate = Populate,
  .nprobes = 2, .probe_names = {"e_kin", "l2_vel_err"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
