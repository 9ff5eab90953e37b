/* The Turek-Hron benchmark (Turek & Hron 2006): an elastic flag, 0.35 m x 0.02 m, attached to the
 * downstream side of a rigid cylinder (centre (0.2, 0.2), radius 0.05) in a channel 2.5 m x 0.41 m;
 * point A = (0.6, 0.2), the middle of the flag's free end.  The benchmark's solid is St Venant-
 * Kirchhoff in plane strain (-solid_law st_venant_kirchhoff, the scene's default).  Cases
 * (-turek_hron_case; docs/turek_hron.md):
 *   csm1  the solid alone under gravity 2 m/s^2, static: reached by dynamic relaxation
 *         (-solid_damping; cases/turek_hron_csm1.opts), the settled displacement of A;
 *   csm3  the same, dynamic, released from rest: mean, amplitude and frequency of A's motion;
 *   cfd1, cfd3  the flag rigid (walls) in the channel's flow, mean inflow 0.2 and 2 m/s (Re 20,
 *         steady; Re 200, periodic): drag and lift on the cylinder and the flag;
 *   fsi2, fsi3  the flag elastic in that flow (mean inflow 1 and 2 m/s): A's motion, drag and lift.
 * The fluid (rho 1000 kg/m^3, nu 1e-3 m^2/s) enters at x = 0 through an inlet with the parabolic
 * profile of mean U, ramped as (1 - cos(pi t / 2)) / 2 over the first 2 s, and leaves at x = 2.5
 * through an outlet at zero pressure (open boundaries); walls at y = 0 and 0.41.  Drag and lift are
 * the fluid's force on body 1, the cylinder's wall particles and the flag's (SimBodyForce).
 *
 * Layout.  The flag's rows (-flag_ny across the thickness, spacing dy = 0.02 / ny) each run from
 * the circle, x_arc(y) = 0.2 + sqrt(R^2 - (y - 0.2)^2) at the row's centre line (0.24899 at the
 * flag's faces, 0.25 on its axis), to x = 0.6, with n = round(0.35 / dy) particles evenly spaced:
 * the row's spacing (0.6 - x_arc) / n differs from dy by at most 0.3 %, and the flag fills exactly
 * the region between the arc and its free end at every resolution (a uniform lattice would put the
 * root up to 1 mm off the arc, and the end deflection goes as L^4: up to 1 % at any dx).  The clamp
 * of the elastic flag is the rows continued into the disc with the same spacing for -clamp_columns
 * columns (not the whole disc): the total-Lagrangian solid's clamp face (midway between the last
 * clamp particle and the first solid one of a row) then lies on the arc, and only those columns take
 * part in the solid (with -solid_clamp_face 0, as material, the kernel's support).  With the fluid,
 * the cylinder is rings of wall particles at R - (k + 1/2) dx (the outer one KIND_WALL, the rest
 * dummies), without the clamp's place; the fluid is the lattice of spacing dy (0.41 / dy = 20.5 ny
 * rows: ny even) outside the cylinder and the flag, so that its rows continue the flag's.  A rigid
 * flag is the same rows as walls (its outer rows and its end column KIND_WALL).
 *
 * Point A.  The displacement at A is extrapolated to the end face x = 0.6 from the last three
 * columns of the rows nearest to y = 0.2 (the two middle rows for an even ny, averaged, which is
 * exact for the linear variation across the thickness; the middle row for an odd ny), by the
 * quadratic through the columns at 0.5, 1.5 and 2.5 row spacings from the end: u_A = (15 u_1 -
 * 10 u_2 + 3 u_3) / 8.  The particles' own displacement, half a spacing inside the end, is the probe
 * ux_A_nearest, uy_A_nearest (first order in dx: the end slope times dx / 2). */
#include <sphfsi.h>

/* The benchmark's cases: the solid's parameters, gravity and the mean inflow (the reference file's
 * header). */
typedef struct {
  const char *name;
  PetscReal   rho_s, mu_s, nu_s, g, U; /* U: the mean inflow (m/s; 0: no fluid) */
  PetscBool   periodic;                /* its reference is mean, amplitude and frequency, not a steady value */
  PetscBool   rigid;                   /* the flag is a wall: no solid */
} Case;
static const Case Cases[] = {
  {"csm1", 1000,  0.5e6, 0.4, 2.0, 0,   PETSC_FALSE, PETSC_FALSE},
  {"csm3", 1000,  0.5e6, 0.4, 2.0, 0,   PETSC_TRUE,  PETSC_FALSE},
  {"cfd1", 0,     0,     0,   0,   0.2, PETSC_FALSE, PETSC_TRUE },
  {"cfd3", 0,     0,     0,   0,   2.0, PETSC_TRUE,  PETSC_TRUE },
  {"fsi2", 10000, 0.5e6, 0.4, 0,   1.0, PETSC_TRUE,  PETSC_FALSE},
  {"fsi3", 1000,  2.0e6, 0.4, 0,   2.0, PETSC_TRUE,  PETSC_FALSE},
};
static const char *const CaseNames[] = {"csm1", "csm3", "cfd1", "cfd3", "fsi2", "fsi3", "TurekHronCase", "TH_", NULL};
#define NCASES   6
#define NSTENCIL 6 /* point A: 3 columns of 1 or 2 rows */
#define RHO_F    1000.0 /* the fluid's density (kg/m^3) and kinematic viscosity (m^2/s) */
#define NU_F     1e-3
#define CHANNEL_L 2.5 /* the channel's length and height (m) */
#define CHANNEL_H 0.41

typedef struct {
  const Case *cs;
  PetscBool   fluid, solid;            /* the media of the case */
  PetscReal   xc, yc, R, L, H, xend;   /* cylinder; flag length, thickness, free end */
  PetscInt    ny, n, nclamp;           /* particles across, along each row, clamp columns */
  PetscInt    rows, nch, nx;           /* wall rows (and each buffer's); fluid rows across the channel, columns along it */
  PetscInt    nlast;                   /* periodic cases: the statistics over the last nlast periods */
  PetscReal   t_from, smooth, ramp;    /* the statistics' window from t_from; the forces' moving average (s); the inflow's ramp (s) */
  PetscReal   pout;                    /* the outlet's pressure (Pa) */
  PetscReal   X[NSTENCIL][2], w[NSTENCIL], wn[NSTENCIL]; /* A's stencil: reference positions, weights (extrapolated, nearest) */
  PetscInt    nst;
  Series      ux, uy;      /* point A's displacement history (m) */
  Series      drag, lift;  /* the fluid's force on the cylinder and the flag (N/m) */
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

/* The channel's open boundaries: the inlet's parabola of mean U at x = 0, ramped; the outlet at zero
 * pressure at x = 2.5. */
static PetscErrorCode AddOpenBoundaries(Sim sim, TurekHron *c)
{
  OpenBoundarySpec in = {0}, out = {0};
  PetscFunctionBeginUser;
  in.kind = OPEN_INLET; in.axis = 0; in.side = -1; in.plane = 0; in.rows = c->rows;
  in.lo[1] = 0; in.hi[1] = CHANNEL_H;
  in.profile  = PROFILE_PARABOLIC; /* 1.5 U y (H - y) / (H / 2)^2 */
  in.velocity = c->cs->U;
  in.ramp     = c->ramp;
  PetscCall(SimAddOpenBoundary(sim, &in));
  out.kind = OPEN_OUTLET; out.axis = 0; out.side = 1; out.plane = CHANNEL_L; out.rows = c->rows;
  out.lo[1] = 0; out.hi[1] = CHANNEL_H; out.pressure = c->pout;
  PetscCall(SimAddOpenBoundary(sim, &out));
  PetscFunctionReturn(PETSC_SUCCESS);
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
  PetscCall(SceneKeepSeries(sim, &c->drag));
  PetscCall(SceneKeepSeries(sim, &c->lift));
  c->xc = 0.2; c->yc = 0.2; c->R = 0.05; c->L = 0.35; c->H = 0.02; c->xend = 0.6; c->ny = 4; c->nclamp = 4; c->nlast = 1;
  c->rows = SimKernelRows(sim); c->ramp = 2; c->t_from = -1;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene turek_hron: the Turek-Hron FSI benchmark's flag behind a cylinder (Turek & Hron 2006)", "");
  PetscCall(OptEList("-turek_hron_case", "The benchmark's case: csm1 (the flag alone under gravity 2 m/s^2, static: give -solid_damping), csm3 (the same released from rest), cfd1, cfd3 (the flag rigid in the channel's flow, Re 20 and 200), fsi2, fsi3 (the flag elastic in it)", "", CaseNames, NCASES, CaseNames[k], &k, NULL));
  c->cs    = &Cases[k];
  c->fluid = (PetscBool)(c->cs->U > 0);
  c->solid = (PetscBool)!c->cs->rigid;
  if (c->fluid) c->nlast = 3;
  PetscCall(OptInt("-flag_ny", "Particles across the flag's thickness 0.02 m (sets dx = 0.02 / ny unless -dx is given; even with the fluid)", "", c->ny, &c->ny, &ny_set));
  if (c->cs->periodic) PetscCall(OptInt("-turek_hron_periods", "Periodic cases: mean, amplitude and frequency over the last this many whole periods (the reference's are of the last periods of a long run); 0 = every whole period in the window", "", c->nlast, &c->nlast, NULL));
  if (c->solid) PetscCall(OptInt("-clamp_columns", "Columns of clamp particles continuing the flag's rows into the cylinder", "", c->nclamp, &c->nclamp, NULL));
  if (c->fluid) {
    PetscCall(OptReal("-turek_hron_ramp", "The inflow grows as (1 - cos(pi t / T)) / 2 over this time T (s; the benchmark's 2)", "", c->ramp, &c->ramp, NULL));
    PetscCall(OptReal("-turek_hron_from", "The statistics (a steady mean, or the periods' mean, amplitude and frequency) from this time on (s; default: the run's last quarter if steady, its second half if periodic)", "", c->t_from, &c->t_from, NULL));
    PetscCall(OptReal("-turek_hron_smooth", "Drag and lift: a centred moving average over this width (s) before their statistics (0: none; the weakly compressible fluid's acoustic noise)", "", c->smooth, &c->smooth, NULL));
    /* WCSPH: the pressure's level is free (a uniform offset exerts no force on a closed body), and a
     * positive one keeps the wake's low pressure from the tensile instability; ISPH's outlet is at 0 */
    if (!SimFluidIncompressible(sim)) c->pout = RHO_F * PetscSqr(1.5 * c->cs->U);
    PetscCall(OptReal("-outlet_pressure", "The outlet's pressure (Pa; WCSPH default rho (1.5 U)^2, the inflow's centre's dynamic pressure twice; ISPH 0)", "", c->pout, &c->pout, NULL));
    PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles on the channel's walls (and of each buffer)", "", c->rows, &c->rows, NULL));
  }
  PetscOptionsEnd();
  PetscCheck(!(ny_set && SimSpacing(sim) > 0), SimComm(sim), PETSC_ERR_ARG_INCOMP, "Give -flag_ny or -dx, not both");
  if (SimSpacing(sim) > 0) c->ny = RoundToInt(c->H / SimSpacing(sim));
  PetscCheck(c->ny >= (c->solid ? 3 : 2), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The flag needs >= %d particles across its thickness (-flag_ny %" PetscInt_FMT " or -dx <= %g)", c->solid ? 3 : 2, c->ny, (double)(c->H / (c->solid ? 3 : 2)));
  PetscCheck(!c->fluid || c->ny % 2 == 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "With the fluid the flag needs an even number of particles across (-flag_ny %" PetscInt_FMT "): the channel's 0.41 m is 20.5 flag thicknesses", c->ny);
  PetscCheck(c->nlast >= 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-turek_hron_periods %" PetscInt_FMT " must be >= 0", c->nlast);
  PetscCheck(c->smooth >= 0 && c->ramp >= 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-turek_hron_smooth and -turek_hron_ramp must be >= 0");
  PetscCheck(!c->solid || c->nclamp >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_columns %" PetscInt_FMT " must be >= 3 (the clamp must fill the kernel support)", c->nclamp);
  PetscCall(SimSetSpacing(sim, c->H / c->ny));
  c->n = RoundToInt(c->L / SimSpacing(sim));
  PetscCheck(!c->solid || c->nclamp * SimSpacing(sim) < c->R, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_columns %" PetscInt_FMT " reach past the cylinder's centre at dx %g", c->nclamp, (double)SimSpacing(sim));
  PetscCheck(SimDim(sim) == 2, SimComm(sim), PETSC_ERR_SUP, "The Turek-Hron benchmark is 2D");
  PetscCall(SimSetMedia(sim, c->fluid, c->solid));
  if (c->solid) { /* the benchmark's solid: St Venant-Kirchhoff, lambda = 2 mu nu / (1 - 2 nu), K = lambda + 2 mu / 3 */
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
  if (!c->fluid) {
    if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, c->cs->periodic ? 10.0 : 2.0)); /* csm3: the benchmark's 10 s; csm1: at rest to 5e-5 with -solid_damping 14 */
    /* the channel's height; in x from the cylinder's left to past the end, which moves up to ~0.03 m
     * left and ~0.13 m down in csm3 */
    PetscCall(SimSetDomain(sim, 0, c->xc - c->R, c->xend + 0.1));
    PetscCall(SimSetDomain(sim, 1, 0, CHANNEL_H));
  } else {
    const PetscReal dx = SimSpacing(sim), depth = c->rows * dx;
    FluidMaterial  *f  = SimFluidMaterial(sim);
    c->nch = RoundToInt(CHANNEL_H / dx);
    c->nx  = RoundToInt(CHANNEL_L / dx);
    if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, c->cs->periodic ? 10.0 : 8.0));
    if (c->t_from < 0) c->t_from = (c->cs->periodic ? 0.5 : 0.75) * SimEndTime(sim);
    PetscCall(SimSetDomain(sim, 0, -depth, CHANNEL_L + depth));
    PetscCall(SimSetDomain(sim, 1, -(c->rows + 0.5) * dx, CHANNEL_H + (c->rows + 0.5) * dx));
    f->rho0 = RHO_F;
    f->mu   = RHO_F * NU_F;
    f->wall_clip = PETSC_FALSE; /* no free surface: the wake's pressure lies below the outlet's */
    PetscCall(SimSetConfined(sim, PETSC_TRUE));
    { /* WCSPH's c0 is 10 times the reference speed: the inflow's centre 1.5 U, or the speed of the
       * pressure that accelerates the channel's water during the ramp, rho L dU/dt <= rho L U pi / (2 T),
       * if larger (cfd1: 0.63 m/s against 0.3; measured: the water compressed by 6 % at c0 3 m/s) */
      const PetscReal U = c->cs->U, accel = c->ramp > 0 ? CHANNEL_L * U * PETSC_PI / (2 * c->ramp) : 0;
      PetscCall(SimSetReferenceSpeed(sim, PetscMax(1.5 * U, PetscSqrtReal(accel))));
    }
    PetscCall(SimEnableField(sim, "body"));
    PetscCall(AddOpenBoundaries(sim, c));
  }
  if (c->solid) {
    PetscCall(SimEnableField(sim, "x0"));
    StencilA(c, SimSpacing(sim));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Inside the cylinder or the flag (at rest) */
static PetscBool InBody(const TurekHron *c, const PetscReal p[])
{
  const PetscReal dx = p[0] - c->xc, dy = p[1] - c->yc;
  return (PetscBool)(dx * dx + dy * dy < c->R * c->R || (dx >= 0 && p[0] < c->xend && PetscAbsReal(dy) < 0.5 * c->H));
}

/* The channel: its walls along the whole length and the buffers, the fluid outside the body, the
 * cylinder's rings of wall particles (without the clamp's place). */
static PetscErrorCode PopulateChannel(Sim sim, TurekHron *c)
{
  const PetscReal dx = SimSpacing(sim), x0 = -(c->rows - 0.5) * dx;
  const PetscInt  n  = c->nx + 2 * c->rows; /* the buffers' columns too */
  const PetscReal xclamp = c->xc + PetscSqrtReal(c->R * c->R - 0.25 * c->H * c->H) - (c->nclamp + 0.5) * dx * 1.01;
  /* WCSPH: the water starts at the outlet's pressure, not at 0 (from 0 a pressure wave would run in
   * from the outlet and ring between it and the inlet at the start) */
  const PetscReal rho = SimFluidIncompressible(sim) ? RHO_F : EOSDensity(SimFluidMaterial(sim), c->pout);
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < c->rows; k++) {
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, x0, -(k + 0.5) * dx, n, 1, dx, RHO_F));
    PetscCall(SceneAddLattice(sim, k ? KIND_DUMMY : KIND_WALL, x0, CHANNEL_H + (k + 0.5) * dx, n, 1, dx, RHO_F));
  }
  for (PetscInt j = 0; j < c->nch; j++)
    for (PetscInt i = 0; i < n; i++) {
      const PetscReal p[2] = {x0 + i * dx, (j + 0.5) * dx}, sp[2] = {dx, dx};
      if (!InBody(c, p)) PetscCall(SceneAddPoint(sim, KIND_FLUID, p, sp, dx, rho));
    }
  for (PetscInt k = 0;; k++) { /* rings at R - (k + 1/2) dx, each of whole spacings ~dx */
    const PetscReal r  = c->R - (k + 0.5) * dx;
    PetscInt        nk;
    if (r <= 0) break;
    nk = PetscMax(1, RoundToInt(2 * PETSC_PI * r / dx));
    for (PetscInt i = 0; i < nk; i++) {
      const PetscReal th = (i + 0.5) * 2 * PETSC_PI / nk, p[2] = {c->xc + r * PetscCosReal(th), c->yc + r * PetscSinReal(th)}, sp[2] = {2 * PETSC_PI * r / nk, dx};
      if (c->solid && PetscAbsReal(p[1] - c->yc) < 0.5 * c->H && p[0] > xclamp) continue; /* the clamp's place */
      PetscCall(SceneAddPoint(sim, k ? KIND_DUMMY : KIND_WALL, p, sp, dx, RHO_F));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Body 1: the cylinder's wall particles and the flag's (walls, or the solid and its clamp). */
static PetscErrorCode TagBody(Sim sim, TurekHron *c)
{
  const PetscReal *x, dx = SimSpacing(sim);
  const PetscInt  *kind;
  PetscReal       *body;
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "body", NULL, &body));
  for (PetscInt a = 0; a < n; a++) {
    const PetscReal dxc = x[2 * a] - c->xc, dyc = x[2 * a + 1] - c->yc;
    const PetscBool near = (PetscBool)(dxc * dxc + dyc * dyc < PetscSqr(c->R + dx) || (dxc >= 0 && x[2 * a] < c->xend + dx && PetscAbsReal(dyc) < 0.5 * c->H + dx));
    body[a] = (KindIsSolid(kind[a]) || (KindIsWall(kind[a]) && near)) ? 1 : 0;
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "body", NULL, &body));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  TurekHron      *c  = (TurekHron *)SimSceneContext(sim);
  const PetscReal dy = SimSpacing(sim), rho = c->solid ? SimSolidMaterial(sim)->rho0 : RHO_F;
  PetscFunctionBeginUser;
  if (c->fluid) PetscCall(PopulateChannel(sim, c));
  for (PetscInt j = 0; j < c->ny; j++) {
    PetscReal y, xa, s;
    Row(c, dy, j, &y, &xa, &s);
    for (PetscInt i = c->solid ? -c->nclamp : 0; i < c->n; i++) {
      const PetscReal p[2] = {xa + (i + 0.5) * s, y}, sp[2] = {s, dy};
      ParticleKind    kind = i < 0 ? KIND_CLAMP : KIND_SOLID;
      if (!c->solid) kind = j == 0 || j == c->ny - 1 || i == c->n - 1 ? KIND_WALL : KIND_DUMMY; /* a rigid flag */
      PetscCall(SceneAddPoint(sim, kind, p, sp, dy, rho));
    }
  }
  if (c->fluid) PetscCall(TagBody(sim, c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ux_A, uy_A (extrapolated to the end face), the same of the particles nearest to A, the solid's
 * kinetic and strain energy, and the total with gravity's potential, sum m |g| (y - y0). */
static PetscErrorCode ProbeA(Sim sim, PetscReal *vals)
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

/* Point A's and the solid's probes (0 with a rigid flag), then drag and lift (0 without the fluid). */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  TurekHron *c = (TurekHron *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 9; k++) vals[k] = 0;
  if (c->solid) PetscCall(ProbeA(sim, vals));
  if (c->fluid) {
    PetscReal f[3];
    PetscCall(SimBodyForce(sim, 1, f));
    vals[7] = f[0];
    vals[8] = f[1];
    PetscCall(SeriesAppend(&c->drag, SimTime(sim), vals[7]));
    PetscCall(SeriesAppend(&c->lift, SimTime(sim), vals[8]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (sim - ref) / ref: positive when the simulated magnitude is the larger (0 without a reference value) */
static PetscReal Rel(PetscReal sim, PetscReal ref) { return ref != 0 ? (sim - ref) / ref : 0; }

/* One quantity against the reference's row: values times `scale` (1e3: A in mm), keys q + unit.
 * Static (csm1, at rest after the dynamic relaxation): the last value.  Steady with the fluid (cfd1):
 * the mean (and the spread) over [t_from, end].  Periodic: over the last -turek_hron_periods periods
 * in [t_from, end] (csm3: the whole run, as its reference's last period of a run to 10 s), after the
 * moving average `smooth`, with the same over every whole period beside them (_all): the envelope
 * of csm3 drifts slowly (energy passes between the first and higher modes), so the two differ. */
static PetscErrorCode Compare(Sim sim, FILE *f, const char *q, const Series *s, PetscReal scale, const char *unit, PetscReal smooth)
{
  TurekHron          *c = (TurekHron *)SimSceneContext(sim);
  const char *const   key[2] = {"case", "quantity"}, *const val[2] = {c->cs->name, q}, *const col[3] = {"mean", "amplitude", "frequency_hz"};
  const PetscReal     t_from = c->fluid ? c->t_from : 0;
  SeriesPeriodicStats w, all;
  PetscReal           ref[3];
  PetscBool           found;
  PetscFunctionBeginUser;
  PetscCall(RefDataRow(SimRefData(sim), SimComm(sim), "turek_hron2006_fsi_benchmark.csv", key, val, 3, col, ref, &found)); /* collective */
  if (!f) PetscFunctionReturn(PETSC_SUCCESS); /* rank 0 writes */
  if (!c->cs->periodic) {
    PetscReal u, sd = 0, u9 = scale * SeriesAt(s, 0.9 * SimTime(sim));
    if (c->fluid) SeriesMean(s, t_from, SimTime(sim), &u, &sd);
    else u = s->n ? s->y[s->n - 1] : 0; /* at rest */
    u *= scale; sd *= scale;
    fprintf(f, "\"%s%s\": %.6g, \"%s_std%s\": %.6g, \"%s_change_last_tenth%s\": %.6g, ", q, unit, (double)u, q, unit, (double)sd, q, unit, (double)(scale * (s->n ? s->y[s->n - 1] : 0) - u9));
    if (found) fprintf(f, "\"%s_ref%s\": %.6g, \"%s_rel_err\": %.6g, ", q, unit, (double)ref[0], q, (double)Rel(u, ref[0]));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(SeriesPeriodic(s, t_from, c->nlast, smooth, &w));
  PetscCall(SeriesPeriodic(s, t_from, 0, smooth, &all));
  fprintf(f, "\"%s_mean%s\": %.6g, \"%s_amplitude%s\": %.6g, \"%s_frequency_hz\": %.6g, \"%s_periods\": %d, \"%s_window_s\": [%.6g, %.6g], ", q, unit, (double)(scale * w.mean), q, unit, (double)(scale * w.amplitude), q, (double)w.frequency, q, (int)w.periods, q, (double)w.t0, (double)w.t1);
  fprintf(f, "\"%s_mean_all%s\": %.6g, \"%s_amplitude_all%s\": %.6g, \"%s_frequency_all_hz\": %.6g, \"%s_periods_all\": %d, ", q, unit, (double)(scale * all.mean), q, unit, (double)(scale * all.amplitude), q, (double)all.frequency, q, (int)all.periods);
  if (found && w.periods > 0) {
    fprintf(f, "\"%s_mean_ref%s\": %.6g, \"%s_amplitude_ref%s\": %.6g, \"%s_frequency_ref_hz\": %.6g, ", q, unit, (double)ref[0], q, unit, (double)ref[1], q, (double)ref[2]);
    fprintf(f, "\"%s_mean_rel_err\": %.6g, \"%s_amplitude_rel_err\": %.6g, \"%s_frequency_rel_err\": %.6g, ", q, (double)Rel(scale * w.mean, ref[0]), q, (double)Rel(scale * w.amplitude, ref[1]), q, (double)Rel(w.frequency, ref[2]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Errors(Sim sim, FILE *f)
{
  TurekHron *c = (TurekHron *)SimSceneContext(sim);
  PetscReal  ek = 0, es = 0;
  PetscFunctionBeginUser;
  if (c->solid) {
    PetscCall(Compare(sim, f, "ux_A", &c->ux, 1e3, "_mm", 0));
    PetscCall(Compare(sim, f, "uy_A", &c->uy, 1e3, "_mm", 0));
    PetscCall(SimSolidEnergy(sim, &ek, &es));
  }
  if (c->fluid) {
    PetscCall(Compare(sim, f, "drag", &c->drag, 1, "", c->smooth));
    PetscCall(Compare(sim, f, "lift", &c->lift, 1, "", c->smooth));
  }
  if (!f) PetscFunctionReturn(PETSC_SUCCESS);
  if (c->fluid) fprintf(f, "\"forces_unit\": \"N/m\", \"forces_smoothing_s\": %.6g, \"statistics_from_s\": %.6g, \"channel_rows\": %d, ", (double)c->smooth, (double)c->t_from, (int)c->nch);
  fprintf(f, "\"flag_ny\": %d, \"flag_nx\": %d, \"kinetic_over_strain_energy\": %.6g, ", (int)c->ny, (int)c->n, (double)(es > 0 ? ek / es : 0));
  fprintf(f, "\"reference\": \"Turek & Hron 2006, %s (turek_hron2006_fsi_benchmark.csv): %s%s\"", c->cs->name, c->solid ? "point A extrapolated to the free end; " : "", c->cs->periodic ? "mean, amplitude = (max +- min) / 2 and frequency over the last whole periods (between upward crossings of the mean), _all over every whole period in the window" : c->fluid ? "steady: the mean over the window" : "static: the value at the end of the run, at rest when kinetic_over_strain_energy is small (-solid_damping)");
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  TurekHron *c = (TurekHron *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->ux));
  PetscCall(SeriesDestroy(&c->uy));
  PetscCall(SeriesDestroy(&c->drag));
  PetscCall(SeriesDestroy(&c->lift));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneTurekHron = {
  .name = "turek_hron", .help = "the Turek-Hron benchmark's flag behind a cylinder: the solid alone (csm1, csm3), rigid in the channel's flow (cfd1, cfd3), elastic in it (fsi2, fsi3) (Turek & Hron 2006)",
  .create = Create, .populate = Populate,
  .nprobes = 9, .probe_names = {"ux_A", "uy_A", "ux_A_nearest", "uy_A_nearest", "e_kin", "e_strain", "e_total", "drag", "lift"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
