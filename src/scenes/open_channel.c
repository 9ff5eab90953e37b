/* An open channel: plane Poiseuille flow developing from a uniform inflow, with no periodicity.  A
 * channel of height H between walls at y = 0 and y = H, an inlet at x = 0 (its buffer at x < 0) with
 * a uniform (or parabolic) velocity of mean U, and an outlet at x = L at zero pressure (its buffer at
 * x > L).  Re = U H / nu.  Downstream of the entrance length (Durst et al. 2005: L_e / H = 0.631 /
 * (1 + 0.044 Re) + 0.0442 Re, 0.9 at Re 10) the profile is the parabola u = 6 U s (1 - s), s = y / H.
 * Probes: the mass that entered and left, and the profile's L2 error at x = probe_x (default 3.5 H). */
#include <sphfsi.h>

typedef struct {
  PetscReal H, L, U, Re, ramp, xp, pout;
  PetscInt  nx, ny, rows;
  PetscBool parabolic;
  char      table[PETSC_MAX_PATH_LEN]; /* an inflow profile from a file ("y u" lines) */
  Series    min, mout; /* mass in and out against time, for the rates over the run's second half */
  Series    usum, ysum, ucount; /* from half the run on: sums of u and y and the count of the particles at probe_x in each row (t: the row) */
  PetscReal l2_last;
} Channel;

static PetscErrorCode Create(Sim sim)
{
  Channel         *c;
  OpenBoundarySpec in = {0}, out = {0};
  PetscReal        dx, depth;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->min));
  PetscCall(SceneKeepSeries(sim, &c->mout));
  PetscCall(SceneKeepSeries(sim, &c->usum));
  PetscCall(SceneKeepSeries(sim, &c->ysum));
  PetscCall(SceneKeepSeries(sim, &c->ucount));
  PetscCall(SceneKeepReal(sim, &c->l2_last));
  c->H = 0.1; c->L = 0.5; c->U = 0.1; c->Re = 10; c->ramp = 0; c->xp = -1;
  c->rows = SimKernelRows(sim);
  PetscOptionsBegin(SimComm(sim), NULL, "Scene open_channel: Poiseuille flow developing from an inlet to an outlet", "");
  PetscCall(OptReal("-channel_height", "Channel height H between the walls (m)", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-channel_length", "Channel length L from the inlet's plane to the outlet's (m)", "", c->L, &c->L, NULL));
  PetscCall(OptReal("-inlet_velocity", "Mean inflow speed U (m/s)", "", c->U, &c->U, NULL));
  PetscCall(OptReal("-inlet_ramp", "The inflow grows as (1 - cos(pi t / T)) / 2 over this time T (s; 0: from the start)", "", c->ramp, &c->ramp, NULL));
  PetscCall(OptBool("-inlet_parabolic", "A parabolic inflow (the developed profile) rather than a uniform one", "", c->parabolic, &c->parabolic, NULL));
  PetscCall(PetscOptionsString("-inlet_table", "An inflow profile from a file: lines \"y u\" (m, m/s), y across the channel from its floor; -inlet_velocity is then its mean, for the probes", "", c->table, c->table, sizeof(c->table), NULL));
  PetscCall(OptReal("-re", "Reynolds number U H / nu (sets the viscosity)", "", c->Re, &c->Re, NULL));
  PetscCall(OptReal("-outlet_pressure", "The outlet's pressure (Pa)", "", c->pout, &c->pout, NULL));
  PetscCall(OptReal("-probe_x", "Where the profile is measured (m; default 3.5 H, or 0.7 L if shorter)", "", c->xp, &c->xp, NULL));
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles (and of each buffer)", "", c->rows, &c->rows, NULL));
  PetscOptionsEnd();
  PetscCheck(c->H > 0 && c->L > 0 && c->Re > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-channel_height, -channel_length and -re must be > 0");
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->H / 20));
  c->ny = RoundToInt(c->H / SimSpacing(sim));
  PetscCheck(c->ny >= 4, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves fewer than 4 rows across the channel (%g m)", (double)SimSpacing(sim), (double)c->H);
  PetscCall(SimSetSpacing(sim, c->H / c->ny)); /* whole rows across */
  dx    = SimSpacing(sim);
  c->nx = RoundToInt(c->L / dx);
  c->L  = c->nx * dx;
  if (c->xp < 0) c->xp = PetscMin(3.5 * c->H, 0.7 * c->L);
  PetscCheck(c->xp > 0 && c->xp < c->L, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-probe_x %g must lie in the channel (0, %g)", (double)c->xp, (double)c->L);
  depth = c->rows * dx;
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 2 * c->L / PetscAbsReal(c->U) + c->ramp)); /* two flow-throughs */
  PetscCall(SimSetMedia(sim, PETSC_TRUE, PETSC_FALSE));
  PetscCall(SimSetGravity(sim, 0, 0, 0));
  PetscCall(SimSetDomain(sim, 0, -depth, c->L + depth));
  PetscCall(SimSetDomain(sim, 1, -(c->rows + 0.5) * dx, c->H + (c->rows + 0.5) * dx));
  SimFluidMaterial(sim)->mu = SimFluidMaterial(sim)->rho0 * PetscAbsReal(c->U) * c->H / c->Re; /* (an inflow pointing out is refused below) */
  { /* the developed profile's centre, or the speed of the channel's pressure drop 12 mu U L / H^2 if
     * larger: WCSPH's c0 = 10 v_ref keeps the density within 1 % of rho0 either way */
    const PetscReal U = PetscAbsReal(c->U), dp = 12 * U * c->H / c->Re * U * c->L / (c->H * c->H);
    PetscCall(SimSetReferenceSpeed(sim, PetscMax(1.5 * U, PetscSqrtReal(dp))));
  }
  in.kind = OPEN_INLET; in.axis = 0; in.side = -1; in.plane = 0; in.rows = c->rows;
  in.lo[1] = 0; in.hi[1] = c->H;
  in.profile  = c->table[0] ? PROFILE_TABLE : c->parabolic ? PROFILE_PARABOLIC : PROFILE_UNIFORM;
  PetscCall(PetscStrncpy(in.table, c->table, sizeof(in.table)));
  in.velocity = c->U;
  in.ramp     = c->ramp;
  PetscCall(SimAddOpenBoundary(sim, &in));
  out.kind = OPEN_OUTLET; out.axis = 0; out.side = 1; out.plane = c->L; out.rows = c->rows;
  out.lo[1] = 0; out.hi[1] = c->H; out.pressure = c->pout;
  PetscCall(SimAddOpenBoundary(sim, &out));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Channel        *c  = (Channel *)SimSceneContext(sim);
  const PetscReal dx = SimSpacing(sim), rho0 = SimFluidMaterial(sim)->rho0;
  const PetscInt  n  = c->nx + 2 * c->rows; /* the buffers' columns too */
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_FLUID, -(c->rows - 0.5) * dx, 0.5 * dx, n, c->ny, dx, rho0));
  for (PetscInt k = 0; k < c->rows; k++) { /* the walls along the whole length, the buffers' included */
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, -(c->rows - 0.5) * dx, -(k + 0.5) * dx, n, 1, dx, rho0));
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, -(c->rows - 0.5) * dx, c->H + (k + 0.5) * dx, n, 1, dx, rho0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* mass_in, mass_out: the fluid mass that entered and left (kg/m); u_center and l2_profile at probe_x:
 * the mean u of the particles within 3 dx / 4 of the centre line (the two middle rows), and sqrt(sum (u - u_p)^2 / sum u_p^2)
 * over the particles within dx of x = probe_x (two columns), u_p = 6 U s (1 - s); from half the run on,
 * the particles' u and y summed row by row, for the mean profile (each row's mean u against u_p at
 * its particles' mean height). */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Channel         *c = (Channel *)SimSceneContext(sim);
  const PetscReal *x, *v, dx = SimSpacing(sim);
  const PetscInt  *kind;
  PetscReal        s[4] = {0, 0, 0, 0}, *rows;
  PetscInt         n;
  const PetscBool  mean = (PetscBool)(SimTime(sim) >= 0.5 * SimEndTime(sim)); /* the profile's mean over the run's second half */
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(3 * c->ny, &rows));
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal sy, up;
    if (!KindIsFluid(kind[a]) || PetscAbsReal(x[2 * a] - c->xp) >= dx) continue;
    sy = x[2 * a + 1] / c->H;
    up = 6 * c->U * sy * (1 - sy);
    s[0] += (v[2 * a] - up) * (v[2 * a] - up) + v[2 * a + 1] * v[2 * a + 1];
    s[1] += up * up;
    if (PetscAbsReal(x[2 * a + 1] - 0.5 * c->H) < 0.75 * dx) { s[2] += v[2 * a]; s[3] += 1; }
    if (mean) {
      const PetscInt j = PetscMin(PetscMax((PetscInt)(sy * c->ny), 0), c->ny - 1);
      rows[j] += v[2 * a];
      rows[c->ny + j] += x[2 * a + 1];
      rows[2 * c->ny + j] += 1;
    }
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 4, MPIU_REAL, MPI_SUM, SimComm(sim)));
  if (mean) {
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, rows, 3 * c->ny, MPIU_REAL, MPI_SUM, SimComm(sim)));
    if (!c->usum.n)
      for (PetscInt j = 0; j < c->ny; j++) {
        PetscCall(SeriesAppend(&c->usum, j, 0));
        PetscCall(SeriesAppend(&c->ysum, j, 0));
        PetscCall(SeriesAppend(&c->ucount, j, 0));
      }
    for (PetscInt j = 0; j < c->ny; j++) { c->usum.y[j] += rows[j]; c->ysum.y[j] += rows[c->ny + j]; c->ucount.y[j] += rows[2 * c->ny + j]; }
  }
  PetscCall(PetscFree(rows));
  vals[0] = SimFluidMassIn(sim);
  vals[1] = SimFluidMassOut(sim);
  vals[2] = s[3] > 0 ? s[2] / s[3] : 0;
  vals[3] = s[1] > 0 ? PetscSqrtReal(s[0] / s[1]) : 0;
  c->l2_last = vals[3];
  PetscCall(SeriesAppend(&c->min, SimTime(sim), vals[0]));
  PetscCall(SeriesAppend(&c->mout, SimTime(sim), vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The least-squares slope of a series over [t0, t1]: a rate of whole particles (an inlet's rows
 * arrive one at a time) without the steps' error at the window's ends */
static PetscReal Slope(const Series *s, PetscReal t0, PetscReal t1)
{
  PetscReal n = 0, st = 0, sy = 0, stt = 0, sty = 0;
  for (PetscInt i = 0; i < s->n; i++) {
    if (s->t[i] < t0 || s->t[i] > t1) continue;
    n += 1; st += s->t[i]; sy += s->y[i]; stt += s->t[i] * s->t[i]; sty += s->t[i] * s->y[i];
  }
  return n > 1 && n * stt - st * st > 0 ? (n * sty - st * sy) / (n * stt - st * st) : 0;
}

/* Rates over the run's second half: mass_in and mass_out's slopes, their balance, the inflow against
 * rho0 U H; the profile's last L2 error, and that of its mean over the second half. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Channel        *c  = (Channel *)SimSceneContext(sim);
  const PetscReal t1 = SimTime(sim), t0 = PetscMax(0.5 * t1, c->ramp);
  PetscReal       in, out, q = SimFluidMaterial(sim)->rho0 * c->U * c->H;
  PetscFunctionBeginUser;
  if (!f || c->min.n < 2 || t1 <= t0) PetscFunctionReturn(PETSC_SUCCESS);
  in  = Slope(&c->min, t0, t1);
  out = Slope(&c->mout, t0, t1);
  {
    PetscReal e2 = 0, u2 = 0;
    for (PetscInt j = 0; j < c->usum.n; j++) {
      PetscReal sy, up;
      if (c->ucount.y[j] <= 0) continue;
      sy = c->ysum.y[j] / c->ucount.y[j] / c->H; /* the row's particles' mean height */
      up = 6 * c->U * sy * (1 - sy);
      e2 += PetscSqr(c->usum.y[j] / c->ucount.y[j] - up);
      u2 += up * up;
    }
    if (u2 > 0) fprintf(f, "\"l2_profile_mean\": %.6g, ", (double)PetscSqrtReal(e2 / u2));
  }
  fprintf(f, "\"rate_in\": %.6g, \"rate_out\": %.6g, \"mass_balance_rel\": %.6g, \"rate_in_vs_rho_U_H\": %.6g, \"l2_profile\": %.6g, \"probe_x\": %.6g, \"rate_window\": [%.6g, %.6g], \"reference\": \"the developed plane Poiseuille profile 6 U s (1 - s)\"", (double)in, (double)out, (double)(in > 0 ? (out - in) / in : 0), (double)((in - q) / q), (double)c->l2_last, (double)c->xp, (double)t0, (double)t1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Channel *c = (Channel *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->min));
  PetscCall(SeriesDestroy(&c->mout));
  PetscCall(SeriesDestroy(&c->usum));
  PetscCall(SeriesDestroy(&c->ysum));
  PetscCall(SeriesDestroy(&c->ucount));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneOpenChannel = {
  .name = "open_channel", .help = "Poiseuille flow developing from an inlet to an outlet (open boundaries)",
  .create = Create, .populate = Populate,
  .nprobes = 4, .probe_names = {"mass_in", "mass_out", "u_center", "l2_profile"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
