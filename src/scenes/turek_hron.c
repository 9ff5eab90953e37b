/* The Turek-Hron benchmark (Turek & Hron 2006): an elastic flag, 0.35 m x 0.02 m, attached to the
 * downstream side of a rigid cylinder (centre (0.2, 0.2), radius 0.05) in a channel; point A =
 * (0.6, 0.2), the middle of the flag's free end.  The benchmark's solid is St Venant-Kirchhoff in
 * plane strain (-solid_law st_venant_kirchhoff, the scene's default).  Cases (-turek_hron_case):
 *   csm1  the solid alone under gravity 2 m/s^2, static: reached by dynamic relaxation
 *         (-solid_damping; cases/turek_hron_csm1.opts), the settled displacement of A;
 *   csm3  the same, dynamic, released from rest: mean, amplitude and frequency of A's motion.
 * The fluid cases (cfd*, fsi*) will join the table below with the channel and the cylinder's wall.
 *
 * Layout.  The flag's rows (-flag_ny across the thickness, spacing dy = 0.02 / ny) each run from
 * the circle, x_arc(y) = 0.2 + sqrt(R^2 - (y - 0.2)^2) at the row's centre line (0.24899 at the
 * flag's faces, 0.25 on its axis), to x = 0.6, with n = round(0.35 / dy) particles evenly spaced:
 * the row's spacing (0.6 - x_arc) / n differs from dy by at most 0.3 %, and the flag fills exactly
 * the region between the arc and its free end at every resolution (a uniform lattice would put the
 * root up to 1 mm off the arc, and the end deflection goes as L^4: up to 1 % at any dx).  The clamp
 * is the rows continued into the disc with the same spacing for -clamp_columns columns (not the
 * whole disc): the total-Lagrangian solid's clamp face (midway between the last clamp particle and
 * the first solid one of a row) then lies on the arc, and only those columns take part in the solid
 * (with -solid_clamp_face 0, as material, the kernel's support).  The rest of the disc is the
 * fluid's wall, which the fluid cases will add.
 *
 * Point A.  The displacement at A is extrapolated to the end face x = 0.6 from the last three
 * columns of the rows nearest to y = 0.2 (the two middle rows for an even ny, averaged, which is
 * exact for the linear variation across the thickness; the middle row for an odd ny), by the
 * quadratic through the columns at 0.5, 1.5 and 2.5 row spacings from the end: u_A = (15 u_1 -
 * 10 u_2 + 3 u_3) / 8.  The particles' own displacement, half a spacing inside the end, is the probe
 * ux_A_nearest, uy_A_nearest (first order in dx: the end slope times dx / 2). */
#include <sphfsi.h>

/* The benchmark's cases: the solid's parameters and gravity (the reference file's header). */
typedef struct {
  const char *name;
  PetscReal   rho_s, mu_s, nu_s, g;
  PetscBool   periodic; /* its reference is mean, amplitude and frequency, not a steady value */
} Case;
static const Case Cases[] = {
  {"csm1", 1000, 0.5e6, 0.4, 2.0, PETSC_FALSE},
  {"csm3", 1000, 0.5e6, 0.4, 2.0, PETSC_TRUE },
};
static const char *const CaseNames[] = {"csm1", "csm3", "TurekHronCase", "TH_", NULL};
#define NCASES 2
#define NSTENCIL 6 /* point A: 3 columns of 1 or 2 rows */

typedef struct {
  const Case *cs;
  PetscReal   xc, yc, R, L, H, xend; /* cylinder; flag length, thickness, free end */
  PetscInt    ny, n, nclamp;          /* particles across, along each row, clamp columns */
  PetscInt    nlast;                  /* csm3: the errors over the last nlast periods */
  PetscReal   X[NSTENCIL][2], w[NSTENCIL], wn[NSTENCIL]; /* A's stencil: reference positions, weights (extrapolated, nearest) */
  PetscInt    nst;
  Series      ux, uy; /* point A's displacement history (m) */
} TurekHron;

/* Row j of the flag: its centre line's height, where it meets the circle, and its spacing. */
static void Row(const TurekHron *c, PetscReal dy, PetscInt j, PetscReal *y, PetscReal *xa, PetscReal *s)
{
  *y  = c->yc - 0.5 * c->H + (j + 0.5) * dy;
  *xa = c->xc + PetscSqrtReal(c->R * c->R - (*y - c->yc) * (*y - c->yc));
  *s  = (c->xend - *xa) / c->n;
}

/* Point A's stencil (reference positions and weights): geometry alone, so a restart, which does
 * not populate, has it too. */
static void StencilA(TurekHron *c, PetscReal dy)
{
  const PetscInt  r0 = (c->ny - 1) / 2, r1 = c->ny / 2;  /* the rows nearest to y = 0.2 (one when ny is odd) */
  const PetscReal L[3] = {15.0 / 8, -10.0 / 8, 3.0 / 8}; /* the quadratic through 0.5, 1.5, 2.5 spacings from the end, at the end */
  c->nst = 0;
  for (PetscInt j = r0; j <= r1; j++) {
    PetscReal y, xa, s;
    Row(c, dy, j, &y, &xa, &s);
    for (PetscInt k = 0; k < 3; k++) {
      c->X[c->nst][0] = c->xend - (k + 0.5) * s;
      c->X[c->nst][1] = y;
      c->w[c->nst]    = L[k] / (r1 - r0 + 1);
      c->wn[c->nst]   = k == 0 ? 1.0 / (r1 - r0 + 1) : 0;
      c->nst++;
    }
  }
}

static PetscErrorCode Create(Sim sim)
{
  TurekHron *c;
  PetscInt   k = 0;
  PetscBool  ny_set;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->ux)); /* checkpoints carry the histories */
  PetscCall(SceneKeepSeries(sim, &c->uy));
  c->xc = 0.2; c->yc = 0.2; c->R = 0.05; c->L = 0.35; c->H = 0.02; c->xend = 0.6; c->ny = 4; c->nclamp = 4; c->nlast = 1;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene turek_hron: the Turek-Hron FSI benchmark's flag behind a cylinder (Turek & Hron 2006)", "");
  PetscCall(OptEList("-turek_hron_case", "The benchmark's case: csm1 (the flag alone under gravity 2 m/s^2, static: give -solid_damping) or csm3 (the same released from rest, dynamic)", "", CaseNames, NCASES, CaseNames[k], &k, NULL));
  PetscCall(OptInt("-flag_ny", "Particles across the flag's thickness 0.02 m (sets dx = 0.02 / ny unless -dx is given)", "", c->ny, &c->ny, &ny_set));
  if (Cases[k].periodic) PetscCall(OptInt("-turek_hron_periods", "Periodic cases: mean, amplitude and frequency over the last this many whole periods (the reference's are of the last period of a run to 10 s); 0 = every whole period after the release", "", c->nlast, &c->nlast, NULL));
  PetscCall(OptInt("-clamp_columns", "Columns of clamp particles continuing the flag's rows into the cylinder", "", c->nclamp, &c->nclamp, NULL));
  PetscOptionsEnd();
  c->cs = &Cases[k];
  PetscCheck(!(ny_set && SimSpacing(sim) > 0), SimComm(sim), PETSC_ERR_ARG_INCOMP, "Give -flag_ny or -dx, not both");
  if (SimSpacing(sim) > 0) c->ny = RoundToInt(c->H / SimSpacing(sim));
  PetscCheck(c->ny >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The flag needs >= 3 particles across its thickness (-flag_ny %" PetscInt_FMT " or -dx <= %g)", c->ny, (double)(c->H / 3));
  PetscCheck(c->nlast >= 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-turek_hron_periods %" PetscInt_FMT " must be >= 0", c->nlast);
  PetscCheck(c->nclamp >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_columns %" PetscInt_FMT " must be >= 3 (the clamp must fill the kernel support)", c->nclamp);
  PetscCall(SimSetSpacing(sim, c->H / c->ny));
  c->n = RoundToInt(c->L / SimSpacing(sim));
  PetscCheck(c->nclamp * SimSpacing(sim) < c->R, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_columns %" PetscInt_FMT " reach past the cylinder's centre at dx %g", c->nclamp, (double)SimSpacing(sim));
  PetscCheck(SimDim(sim) == 2, SimComm(sim), PETSC_ERR_SUP, "The Turek-Hron benchmark is 2D");
  PetscCall(SimSetMedia(sim, PETSC_FALSE, PETSC_TRUE)); /* the CSM cases: no fluid */
  { /* the benchmark's solid: St Venant-Kirchhoff, lambda = 2 mu nu / (1 - 2 nu), K = lambda + 2 mu / 3 */
    SolidMaterial  *m = SimSolidMaterial(sim);
    const PetscReal lambda = 2 * c->cs->mu_s * c->cs->nu_s / (1 - 2 * c->cs->nu_s);
    m->rho0 = c->cs->rho_s;
    m->G    = c->cs->mu_s;
    m->K    = lambda + 2 * c->cs->mu_s / 3;
    m->law  = SOLID_LAW_ST_VENANT_KIRCHHOFF;
    /* a free swing: no artificial viscosity (the total-Lagrangian solid is stable without it, and
     * keeps its energy to 1e-9 over 10 s; alpha 1 loses 0.5 % and shrinks the swing) */
    if (c->cs->periodic) m->alpha = 0;
  }
  PetscCall(SimSetGravity(sim, 0, -c->cs->g, 0));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, c->cs->periodic ? 10.0 : 2.0)); /* csm3: the benchmark's 10 s; csm1: at rest to 5e-5 with -solid_damping 14 */
  /* the channel's height; in x from the cylinder's left to past the end, which moves up to ~0.03 m
   * left and ~0.13 m down in csm3 */
  PetscCall(SimSetDomain(sim, 0, c->xc - c->R, c->xend + 0.1));
  PetscCall(SimSetDomain(sim, 1, 0, 0.41));
  PetscCall(SimEnableField(sim, "x0"));
  StencilA(c, SimSpacing(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  TurekHron      *c  = (TurekHron *)SimSceneContext(sim);
  const PetscReal dy = SimSpacing(sim), rho = SimSolidMaterial(sim)->rho0;
  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < c->ny; j++) {
    PetscReal y, xa, s;
    Row(c, dy, j, &y, &xa, &s);
    for (PetscInt i = -c->nclamp; i < c->n; i++) {
      const PetscReal p[2] = {xa + (i + 0.5) * s, y}, sp[2] = {s, dy};
      PetscCall(SceneAddPoint(sim, i < 0 ? KIND_CLAMP : KIND_SOLID, p, sp, dy, rho));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ux_A, uy_A (extrapolated to the end face), the same of the particles nearest to A, the solid's
 * kinetic and strain energy, and the total with gravity's potential, sum m |g| (y - y0). */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  TurekHron       *c = (TurekHron *)SimSceneContext(sim);
  const PetscReal *x, *x0, *m, *g = SimGravity(sim), tol = 0.25 * SimSpacing(sim);
  const PetscInt  *kind;
  PetscReal        s[6] = {0, 0, 0, 0, 0, 0}; /* extrapolated, nearest (x, y); potential; stencil weight found */
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "x0", NULL, &x0));
  PetscCall(SimGetField(sim, "m", NULL, &m));
  for (PetscInt a = 0; a < n; a++) {
    if (kind[a] != KIND_SOLID) continue;
    s[4] -= m[a] * (g[0] * (x[2 * a] - x0[2 * a]) + g[1] * (x[2 * a + 1] - x0[2 * a + 1]));
    if (x0[2 * a] < c->xend - 3 * SimSpacing(sim) * 1.01) continue;
    for (PetscInt k = 0; k < c->nst; k++)
      if (PetscAbsReal(x0[2 * a] - c->X[k][0]) < tol && PetscAbsReal(x0[2 * a + 1] - c->X[k][1]) < tol) {
        for (PetscInt d = 0; d < 2; d++) {
          s[d] += c->w[k] * (x[2 * a + d] - x0[2 * a + d]);
          s[2 + d] += c->wn[k] * (x[2 * a + d] - x0[2 * a + d]);
        }
        s[5] += 1;
      }
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCall(SimRestoreField(sim, "m", NULL, &m));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 6, MPIU_REAL, MPI_SUM, SimComm(sim)));
  PetscCheck(RoundToInt(s[5]) == c->nst, SimComm(sim), PETSC_ERR_PLIB, "Point A's stencil: found %d of its %d particles", (int)RoundToInt(s[5]), (int)c->nst);
  for (PetscInt d = 0; d < 4; d++) vals[d] = s[d];
  PetscCall(SimSolidEnergy(sim, &vals[4], &vals[5]));
  vals[6] = vals[4] + vals[5] + s[4];
  PetscCall(SeriesAppend(&c->ux, SimTime(sim), vals[0]));
  PetscCall(SeriesAppend(&c->uy, SimTime(sim), vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The reference's row (case, quantity): mean, amplitude, frequency (columns by the header's names;
 * RefDataLoad reads numeric x,y curves, this table is keyed by text).  Rank 0 reads, every rank gets
 * it; found[0] says whether the row is there. */
static PetscErrorCode LoadReference(Sim sim, const char *cs, const char *quantity, PetscReal ref[3], PetscBool *found)
{
  const char *file = "turek_hron2006_fsi_benchmark.csv", *want[5] = {"case", "quantity", "mean", "amplitude", "frequency_hz"};
  PetscReal   buf[4] = {0, 0, 0, 0};
  char        line[1024];
  FILE       *f;
  PetscFunctionBeginUser;
  PetscCall(RefDataOpen(SimRefData(sim), file, &f)); /* a missing file is reported there */
  if (f) {
    int col[5] = {-1, -1, -1, -1, -1};
    while (fgets(line, sizeof(line), f)) {
      char *tok, *rest = line, *val[16] = {NULL};
      int   nt = 0;
      if (line[0] == '#' || line[0] == '\n') continue;
      line[strcspn(line, "\r\n")] = 0;
      while ((tok = strsep(&rest, ",")) && nt < 16) val[nt++] = tok;
      if (col[0] < 0) { /* the header */
        for (int q = 0; q < 5; q++)
          for (int t = 0; t < nt; t++)
            if (!strcmp(val[t], want[q])) col[q] = t;
        if (col[0] < 0 || col[1] < 0 || col[2] < 0) break;
        continue;
      }
      if (col[0] >= nt || col[1] >= nt || strcasecmp(val[col[0]], cs) || strcmp(val[col[1]], quantity)) continue;
      for (int q = 2; q < 5; q++) buf[q - 2] = col[q] >= 0 && col[q] < nt && val[col[q]][0] ? atof(val[col[q]]) : 0;
      buf[3] = 1;
      break;
    }
    fclose(f);
  }
  PetscCallMPI(MPI_Bcast(buf, 4, MPIU_REAL, 0, SimComm(sim)));
  *found = (PetscBool)(buf[3] > 0);
  for (int q = 0; q < 3; q++) ref[q] = buf[q];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A periodic history as the benchmark defines it: mean = (max + min) / 2, amplitude = (max - min) /
 * 2 and the frequency, over whole periods: those between the upward crossings of the level (max +
 * min) / 2 of the whole history (linear interpolation between samples).  The window is the last
 * `last` periods before the end (last = 0: every whole period, from the first crossing, which
 * leaves out the release: the first 3/4 period for a flag released at its top). */
typedef struct {
  PetscReal mean, amp, freq, t0, t1;
  PetscInt  nper;
} PeriodicStats;

static PeriodicStats Periodic(const Series *s, PetscInt last)
{
  PeriodicStats r = {0, 0, 0, 0, 0, 0};
  PetscReal     lo = PETSC_MAX_REAL, hi = -PETSC_MAX_REAL, level, tc[2] = {0, 0};
  PetscInt      nc = 0, k = 0;
  for (PetscInt i = 0; i < s->n; i++) { lo = PetscMin(lo, s->y[i]); hi = PetscMax(hi, s->y[i]); }
  level = 0.5 * (lo + hi);
  for (PetscInt i = 1; i < s->n; i++) nc += s->y[i - 1] < level && s->y[i] >= level;
  if (nc < 2) return r;
  r.nper = last > 0 ? PetscMin(last, nc - 1) : nc - 1;
  for (PetscInt i = 1; i < s->n; i++) /* the window's first and last crossings */
    if (s->y[i - 1] < level && s->y[i] >= level) {
      PetscReal t = s->t[i - 1] + (s->t[i] - s->t[i - 1]) * (level - s->y[i - 1]) / (s->y[i] - s->y[i - 1]);
      if (k == nc - 1 - r.nper) tc[0] = t;
      if (k == nc - 1) tc[1] = t;
      k++;
    }
  lo = PETSC_MAX_REAL; hi = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < s->n; i++)
    if (s->t[i] >= tc[0] && s->t[i] <= tc[1]) { lo = PetscMin(lo, s->y[i]); hi = PetscMax(hi, s->y[i]); }
  r.mean = 0.5 * (hi + lo);
  r.amp  = 0.5 * (hi - lo);
  r.freq = r.nper / (tc[1] - tc[0]);
  r.t0   = tc[0];
  r.t1   = tc[1];
  return r;
}

/* (sim - ref) / ref: positive when the simulated magnitude is the larger (0 without a reference value) */
static PetscReal Rel(PetscReal sim, PetscReal ref) { return ref != 0 ? (sim - ref) / ref : 0; }

/* One quantity of A (in mm, as the reference) against the reference's row.  csm3: over the last
 * -turek_hron_periods periods, as the reference (its values are of the last period of a run to
 * 10 s), with the same over every whole period after the release beside them (_all): the envelope
 * drifts slowly (energy passes between the first and higher modes), so the two differ. */
static PetscErrorCode CompareA(Sim sim, FILE *f, const char *q, const Series *s)
{
  TurekHron    *c = (TurekHron *)SimSceneContext(sim);
  PeriodicStats w, all;
  PetscReal     ref[3];
  PetscBool     found;
  PetscFunctionBeginUser;
  PetscCall(LoadReference(sim, c->cs->name, q, ref, &found));
  if (!f) PetscFunctionReturn(PETSC_SUCCESS);
  if (!c->cs->periodic) { /* static: the last value */
    PetscReal u = s->n ? 1e3 * s->y[s->n - 1] : 0, u9 = 1e3 * SeriesAt(s, 0.9 * SimTime(sim));
    fprintf(f, "\"%s_mm\": %.6g, \"%s_change_last_tenth_mm\": %.6g, ", q, (double)u, q, (double)(u - u9));
    if (found) fprintf(f, "\"%s_ref_mm\": %.6g, \"%s_rel_err\": %.6g, ", q, (double)ref[0], q, (double)Rel(u, ref[0]));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  w   = Periodic(s, c->nlast);
  all = Periodic(s, 0);
  fprintf(f, "\"%s_mean_mm\": %.6g, \"%s_amplitude_mm\": %.6g, \"%s_frequency_hz\": %.6g, \"%s_periods\": %d, \"%s_window_s\": [%.6g, %.6g], ", q, (double)(1e3 * w.mean), q, (double)(1e3 * w.amp), q, (double)w.freq, q, (int)w.nper, q, (double)w.t0, (double)w.t1);
  fprintf(f, "\"%s_mean_all_mm\": %.6g, \"%s_amplitude_all_mm\": %.6g, \"%s_frequency_all_hz\": %.6g, \"%s_periods_all\": %d, ", q, (double)(1e3 * all.mean), q, (double)(1e3 * all.amp), q, (double)all.freq, q, (int)all.nper);
  if (found && w.nper > 0) {
    fprintf(f, "\"%s_mean_ref_mm\": %.6g, \"%s_amplitude_ref_mm\": %.6g, \"%s_frequency_ref_hz\": %.6g, ", q, (double)ref[0], q, (double)ref[1], q, (double)ref[2]);
    fprintf(f, "\"%s_mean_rel_err\": %.6g, \"%s_amplitude_rel_err\": %.6g, \"%s_frequency_rel_err\": %.6g, ", q, (double)Rel(1e3 * w.mean, ref[0]), q, (double)Rel(1e3 * w.amp, ref[1]), q, (double)Rel(w.freq, ref[2]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Errors(Sim sim, FILE *f)
{
  TurekHron *c = (TurekHron *)SimSceneContext(sim);
  PetscReal  ek, es;
  PetscFunctionBeginUser;
  PetscCall(CompareA(sim, f, "ux_A", &c->ux));
  PetscCall(CompareA(sim, f, "uy_A", &c->uy));
  PetscCall(SimSolidEnergy(sim, &ek, &es));
  if (f) {
    fprintf(f, "\"flag_ny\": %d, \"flag_nx\": %d, \"kinetic_over_strain_energy\": %.6g, ", (int)c->ny, (int)c->n, (double)(es > 0 ? ek / es : 0));
    fprintf(f, "\"reference\": \"Turek & Hron 2006, %s, point A extrapolated to the free end (turek_hron2006_fsi_benchmark.csv)%s\"", c->cs->name, c->cs->periodic ? "; mean, amplitude = (max +- min) / 2 and frequency over the last whole periods (between upward crossings of the mean), _all over every whole period after the release" : "; static: the value at the end of the run, at rest when kinetic_over_strain_energy is small (-solid_damping)");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  TurekHron *c = (TurekHron *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->ux));
  PetscCall(SeriesDestroy(&c->uy));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneTurekHron = {
  .name = "turek_hron", .help = "the Turek-Hron benchmark's flag behind a cylinder: the solid cases csm1 (static) and csm3 (dynamic) (Turek & Hron 2006)",
  .create = Create, .populate = Populate,
  .nprobes = 7, .probe_names = {"ux_A", "uy_A", "ux_A_nearest", "uy_A_nearest", "e_kin", "e_strain", "e_total"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
