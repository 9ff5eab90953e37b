/* Oscillating plate (paper section 3.2; Gray, Monaghan & Swift 2001): a plate of length L and
 * thickness H, clamped at x < 0 and free at x = L, no gravity, started with the velocity of its
 * first bending mode (Eqs. 52-53, kL = 1.875).  Reference: thin-plate (plane-strain
 * Euler-Bernoulli) period and amplitude, omega^2 = E' H^2 k^4 / (12 rho), E' = E / (1 - nu^2),
 * E = 9 K G / (3 K + G), nu = (3 K - 2 G) / (2 (3 K + G)), A = V_f c0 / omega.
 * -dim 3: a cantilever beam of square section H x H (-plate_width), bending in y, with free sides:
 * Euler-Bernoulli with E' = E.  The clamp's face (x = 0, the root of the beam theory) is where the
 * total-Lagrangian solid's clamp face points sit; the beam's own correction, Timoshenko's shear
 * and rotary inertia (+0.6 % on the period at L = 10 H), is reported beside it. */
#include <sphfsi.h>

typedef struct {
  PetscReal L, H, W, vf, kL; /* W: the width in z (3D) */
  PetscBool periodic;         /* 3D: periodic in z, a slab of the plate in plane strain */
  PetscInt  ny, nx, nclamp;
  Series    tip;            /* tip_y history for the period and amplitude */
  PetscReal e0, de_max;     /* initial total energy and the largest relative drift */
} Plate;

static PetscErrorCode Create(Sim sim)
{
  Plate    *c;
  PetscBool ny_set;
  PetscReal ymax;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->tip));
  PetscCall(SceneKeepReal(sim, &c->e0));
  PetscCall(SceneKeepReal(sim, &c->de_max));
  c->L = 0.2; c->H = 0.02; c->vf = 0.01; c->kL = 1.875104069; c->ny = 10; c->nclamp = 4;
  SimSolidMaterial(sim)->rho0 = 1000; SimSolidMaterial(sim)->K = 3.25e6; SimSolidMaterial(sim)->G = 7.15e5; /* Gray et al. 2001; G = 7.15e5 (the paper's 7.15e6 is a misprint) */
  PetscOptionsBegin(SimComm(sim), NULL, "Scene oscillating_plate: clamped elastic plate in its first bending mode (Gray et al. 2001)", "");
  PetscCall(OptReal("-plate_length", "Plate length L outside the clamp (m)", "", c->L, &c->L, NULL));
  PetscCall(OptReal("-plate_thickness", "Plate thickness H (m)", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-plate_vf", "Initial tip speed over the sound speed, V_f = v0L of Eq. 52", "", c->vf, &c->vf, NULL));
  PetscCall(OptInt("-plate_ny", "Particles across the thickness (sets dx = H / ny unless -dx is given)", "", c->ny, &c->ny, &ny_set));
  PetscCall(OptInt("-clamp_columns", "Columns of clamp particles at x < 0", "", c->nclamp, &c->nclamp, NULL));
  {
    PetscInt dim = SimDim(sim);
    PetscCall(OptInt("-dim", "Dimension: 2 (a plate in plane strain), or 3 for a beam of section H x -plate_width", "", dim, &dim, NULL));
    PetscCall(SimSetDim(sim, dim));
  }
  c->W = c->H;
  if (SimDim(sim) == 3) PetscCall(OptReal("-plate_width", "3D: the beam's width in z (m; default: its thickness, a square section)", "", c->W, &c->W, NULL));
  if (SimDim(sim) == 3) PetscCall(OptBool("-plate_periodic", "3D: periodic across the width (a slab of the plate in plane strain, the 2D case's reference)", "", c->periodic, &c->periodic, NULL));
  PetscOptionsEnd();
  PetscCheck(SimDim(sim) == 2 || SimDim(sim) == 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dim %" PetscInt_FMT " must be 2 or 3", SimDim(sim));
  PetscCheck(c->L > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-plate_length %g must be > 0", (double)c->L);
  PetscCheck(c->H > 0 && c->H < c->L, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-plate_thickness %g must be > 0 and less than the length %g", (double)c->H, (double)c->L);
  PetscCheck(c->vf >= 0 && c->vf < 0.1, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-plate_vf %g must be in [0, 0.1) (small deflections)", (double)c->vf);
  PetscCheck(c->nclamp >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_columns %" PetscInt_FMT " must be >= 3 (the clamp must fill the kernel support)", c->nclamp);
  PetscCheck(!(ny_set && SimSpacing(sim) > 0), SimComm(sim), PETSC_ERR_ARG_INCOMP, "Give -plate_ny or -dx, not both");
  if (SimSpacing(sim) > 0) c->ny = RoundToInt(c->H / SimSpacing(sim));
  PetscCheck(c->ny >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The plate needs >= 3 particles across its thickness (-plate_ny %" PetscInt_FMT " or -dx <= %g)", c->ny, (double)(c->H / 3));
  PetscCall(SimSetSpacing(sim, c->H / c->ny));
  c->nx          = RoundToInt(c->L / SimSpacing(sim));
  PetscCall(SimSetMedia(sim, PETSC_FALSE, PETSC_TRUE));
  PetscCall(SimSetGravity(sim, 0, 0, 0));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 0.8)); /* about 3 analytic periods */
  /* the tip sweeps |y| < ~A = V_f L c0 / (omega L) ~ 0.12 L at V_f = 0.01 */
  PetscCall(SimSetDomain(sim, 0, -(c->nclamp + 2) * SimSpacing(sim), c->L + 0.1 * c->L));
  ymax = 0.5 * c->H + 0.15 * c->L + 50 * c->vf * c->L;
  if (c->vf == 0) ymax = c->L + c->H; /* a static load (-gravity) may bend it far: room for any bend of the plate */
  PetscCall(SimSetDomain(sim, 1, -ymax, ymax));
  if (SimDim(sim) == 3) {
    PetscCheck(c->W >= 3 * SimSpacing(sim) * (1 - 1e-9), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-plate_width %g must hold >= 3 particles (dx %g)", (double)c->W, (double)SimSpacing(sim));
    PetscReal zmax = 0.5 * c->W + 0.1 * c->L; /* bending is in y: z moves only by Poisson's ratio */
    if (c->periodic) zmax = 0.5 * RoundToInt(c->W / SimSpacing(sim)) * SimSpacing(sim);
    PetscCall(SimSetDomain(sim, 2, -zmax, zmax));
    if (c->periodic) PetscCall(SimSetPeriodic(sim, 2, PETSC_TRUE));
  }
  PetscCall(SimEnableField(sim, "x0"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Eq. 53 */
static PetscReal Mode(PetscReal k, PetscReal L, PetscReal x)
{
  PetscReal kL = k * L, kx = k * x;
  return (PetscCosReal(kL) + PetscCoshReal(kL)) * (PetscCoshReal(kx) - PetscCosReal(kx)) + (PetscSinReal(kL) - PetscSinhReal(kL)) * (PetscSinhReal(kx) - PetscSinReal(kx));
}

static PetscErrorCode Populate(Sim sim)
{
  Plate     *c  = (Plate *)SimSceneContext(sim);
  PetscReal  dx = SimSpacing(sim), y0 = -0.5 * c->H + 0.5 * dx, k = c->kL / c->L, fL = Mode(k, c->L, c->L);
  PetscInt   n0, n1, D = SimDim(sim), nz = RoundToInt(c->W / dx);
  PetscReal *x, *v, z0 = -0.5 * nz * dx + 0.5 * dx;
  PetscFunctionBeginUser;
  PetscCall(SceneAddBlock(sim, KIND_CLAMP, (PetscReal[]){-(c->nclamp - 0.5) * dx, y0, z0}, (PetscInt[]){c->nclamp, c->ny, nz}, dx, SimSolidMaterial(sim)->rho0));
  PetscCall(SimGetLocalSize(sim, &n0));
  PetscCall(SceneAddBlock(sim, KIND_SOLID, (PetscReal[]){0.5 * dx, y0, z0}, (PetscInt[]){c->nx, c->ny, nz}, dx, SimSolidMaterial(sim)->rho0));
  PetscCall(SimGetLocalSize(sim, &n1));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  for (PetscInt a = n0; a < n1; a++) v[D * a + 1] = c->vf * SimSolidMaterial(sim)->c0 * Mode(k, c->L, x[D * a]) / fL; /* Eq. 52 */
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* tip_y: mean vertical displacement of the last column (its mid-point by symmetry); energies. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Plate     *c = (Plate *)SimSceneContext(sim);
  const PetscReal *x, *x0;
  const PetscInt  *kind;
  PetscReal        s[2] = {0, 0}, e;
  PetscInt         D = SimDim(sim), n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "x0", NULL, &x0));
  for (PetscInt a = 0; a < n; a++)
    if (kind[a] == KIND_SOLID && x0[D * a] > (c->nx - 1) * SimSpacing(sim)) { s[0] += x[D * a + 1] - x0[D * a + 1]; s[1] += 1; }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = s[1] > 0 ? s[0] / s[1] : 0;
  PetscCall(SimSolidEnergy(sim, &vals[1], &vals[2]));
  e = vals[1] + vals[2];
  if (SimStep(sim) == 0) c->e0 = e;
  else if (c->e0 > 0) c->de_max = PetscMax(c->de_max, PetscAbsReal(e - c->e0) / c->e0);
  PetscCall(SeriesAppend(&c->tip, SimTime(sim), vals[0]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Period from the zero crossings of tip_y (linear interpolation), amplitude = first extremum. */
static void Analyse(const Series *s, PetscReal *T, PetscReal *A, PetscReal *A_last, PetscInt *ncross)
{
  PetscReal t_first = 0, t_last = 0, peak = 0;
  PetscInt  n = 0, npeak = 0;
  *A = *A_last = 0;
  for (PetscInt i = 1; i < s->n; i++) {
    PetscReal y0 = s->y[i - 1], y1 = s->y[i];
    peak = PetscMax(peak, PetscAbsReal(y1));
    if ((y0 < 0 && y1 >= 0) || (y0 > 0 && y1 <= 0)) {
      PetscReal tc = s->t[i - 1] + (s->t[i] - s->t[i - 1]) * y0 / (y0 - y1);
      if (!n) t_first = tc;
      t_last = tc;
      n++;
      if (!npeak++) *A = peak;
      *A_last = peak;
      peak    = 0;
    }
  }
  *ncross = n;
  *T      = n >= 2 ? 2 * (t_last - t_first) / (n - 1) : 0;
}

static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Plate          *c = (Plate *)SimSceneContext(sim);
  const SolidMaterial *m = SimSolidMaterial(sim);
  PetscReal       E = 9 * m->K * m->G / (3 * m->K + m->G), nu = (3 * m->K - 2 * m->G) / (2 * (3 * m->K + m->G)), k = c->kL / c->L;
  PetscReal       Ep = SimDim(sim) == 3 && !c->periodic ? E : E / (1 - nu * nu); /* a beam with free sides; a plate in plane strain */
  PetscReal       omega = PetscSqrtReal(Ep * c->H * c->H * PetscPowReal(k, 4) / (12 * m->rho0));
  PetscReal       Ta = 2 * PETSC_PI / omega, Aa = c->vf * m->c0 / omega, T, A, A_last, ek, es;
  /* Timoshenko's first-order correction for shear (kappa_s = 5/6) and rotary inertia of a slender
   * beam, omega_T / omega = 1 - (k r)^2 / 2 (1 + E' / (kappa_s G)), r^2 = H^2 / 12, exact to that
   * order for a simply supported beam and taken with the mode's wavenumber k for the cantilever */
  PetscReal       Tt = Ta / (1 - 0.5 * c->kL * c->kL * c->H * c->H / (12 * c->L * c->L) * (1 + Ep / (5.0 / 6.0 * m->G)));
  PetscInt        ncross;
  PetscFunctionBeginUser;
  PetscCall(SimSolidEnergy(sim, &ek, &es));
  Analyse(&c->tip, &T, &A, &A_last, &ncross);
  if (f && c->vf == 0) { /* a static load (-gravity) instead of the mode: the end's sag against beam theory */
    PetscReal g = PetscSqrtReal(SimGravity(sim)[0] * SimGravity(sim)[0] + SimGravity(sim)[1] * SimGravity(sim)[1] + SimGravity(sim)[2] * SimGravity(sim)[2]), L = c->L, H = c->H;
    PetscReal eb = 1.5 * m->rho0 * g * PetscPowReal(L, 4) / (Ep * H * H), shear = m->rho0 * g * L * L / (2 * (5.0 / 6.0) * m->G), sag = c->tip.n ? -c->tip.y[c->tip.n - 1] : 0;
    fprintf(f, "\"g\": %.6g, \"sag\": %.6g, \"sag_beam\": %.6g, \"sag_rel_err\": %.6g, \"sag_euler_bernoulli\": %.6g, \"sag_eb_rel_err\": %.6g, \"plate_ny\": %d, \"kinetic_over_strain_energy\": %.6g, ", (double)g, (double)sag, (double)(eb + shear), (double)(sag / (eb + shear) - 1), (double)eb, (double)(sag / eb - 1), (int)c->ny, (double)(es > 0 ? ek / es : 0));
    fprintf(f, "\"reference\": \"sag of the end under the uniform load rho g H: Euler-Bernoulli q L^4 / (8 E' I), E' = E / (1 - nu^2), plus Timoshenko shear q L^2 / (2 (5/6) G H); the end at rest when kinetic_over_strain_energy is small (-solid_damping)\"");
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (f) {
    fprintf(f, "\"period_c0_over_L\": %.6g, \"period_c0_over_L_analytic\": %.6g, \"period_rel_err\": %.6g, ", (double)(T * m->c0 / c->L), (double)(Ta * m->c0 / c->L), (double)(T > 0 ? (T - Ta) / Ta : 1));
    fprintf(f, "\"amplitude_over_L\": %.6g, \"amplitude_over_L_analytic\": %.6g, \"amplitude_rel_err\": %.6g, \"amplitude_last_over_first\": %.6g, ", (double)(A / c->L), (double)(Aa / c->L), (double)(Aa > 0 ? (A - Aa) / Aa : 0), (double)(A > 0 ? A_last / A : 0));
    fprintf(f, "\"zero_crossings\": %d, \"energy_rel_drift_final\": %.6g, \"energy_rel_drift_max\": %.6g, \"period_s\": %.6g, \"period_s_analytic\": %.6g, ", (int)ncross, (double)(c->e0 > 0 ? (ek + es - c->e0) / c->e0 : 0), (double)c->de_max, (double)T, (double)Ta);
    fprintf(f, "\"period_c0_over_L_timoshenko\": %.6g, \"period_rel_err_timoshenko\": %.6g, \"dim\": %d, ", (double)(Tt * m->c0 / c->L), (double)(T > 0 ? (T - Tt) / Tt : 1), (int)SimDim(sim));
    if (SimDim(sim) == 3) fprintf(f, "\"plate_ny\": %d, \"E\": %.6g, \"nu\": %.6g, \"reference\": \"Euler-Bernoulli cantilever of square section (E, free sides), root at the clamp face x = 0; Timoshenko-corrected period beside it\"", (int)c->ny, (double)E, (double)nu);
    else fprintf(f, "\"plate_ny\": %d, \"E\": %.6g, \"nu\": %.6g, \"reference\": \"thin-plate analytic (Gray et al. 2001); published SPH T c0/L 81-82, A/L 0.124-0.125 (paper Table 1)\"", (int)c->ny, (double)E, (double)nu);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Plate *c = (Plate *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->tip));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneOscillatingPlate = {
  .name = "oscillating_plate", .help = "clamped elastic plate in its first bending mode (Gray et al. 2001)",
  .create = Create, .populate = Populate,
  .nprobes = 3, .probe_names = {"tip_y", "e_kin", "e_strain"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
