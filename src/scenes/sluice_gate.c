/* Flow under a sluice gate (paper section 3.1): a reservoir of water, W wide and H deep, between a
 * left wall and a rigid vertical gate whose bottom edge leaves an opening a above the floor, drains
 * under the gate into a horizontal channel.
 *
 *   x = 0          x = W   x = W + t_g                          x = W + t_g + L_c
 *   |  reservoir   |gate|  channel (closed far end)             |
 *   |  (fluid)     |   /                                        |
 *   |              |_/     <- sharp edge at y = a, chamfered     |
 *   |___________________________________________________________|  floor y = 0
 *
 * The gate is t_g = gate_rows dx thick, wall particles on every face touching water (KIND_WALL)
 * and dummy particles inside.  With 2h = 2.6 dx no wall particle of a gate of 4 rows or more sees
 * fluid on both sides, so the Adami extrapolation of each face takes only its own side's water.
 * Under its downstream side the gate is chamfered (-gate_bevel, 45 deg), which leaves the sharp
 * upstream edge of a standard underflow gate (ISO 13550).
 *
 * Reference: free flow under a sharp-edged vertical gate (Henderson 1966; ISO 13550):
 *   q = Cd a sqrt(2 g h_up),  Cd = Cc / sqrt(1 + Cc a / h_up),  vena contracta depth Cc a,
 * with Cc read from the reference data's sluice_gate_reference_coefficients.csv.  The reservoir drains,
 * so the relation is applied quasi-steadily to q(t) and h_up(t) in a window after the start-up. */
#include <sphfsi.h>

typedef struct {
  PetscReal W, H, a, Lc, top;  /* water width, depth, gate opening, channel length, wall height */
  PetscReal dxc, fine;         /* coarse spacing away from the gate; width of the fine zone before it */
  PetscInt  rows, gate_rows;   /* wall rows of the tank, thickness of the gate in rows */
  PetscReal bevel;             /* angle of the gate's downstream chamfer from the horizontal (deg); 0 = square edge */
  PetscReal xg0, xg1;          /* upstream and downstream faces of the gate */
  PetscReal x_up, x_down;      /* stations of h_up and h_down */
  PetscReal win[2];            /* quasi-steady window of the errors */
  Series    q, hup, hdown, vup; /* probe histories; vup = fluid volume upstream of the gate centre */
} Sluice;

/* Default t_end: the time the reservoir takes to drain from H to h_end = 2a (or (H + a)/2 if H < 4a)
 * under the quasi-steady law W dh/dt = -Cd a sqrt(2 g h) with Cd ~ 0.6:
 *   sqrt(h) = sqrt(H) - k t / 2,  k = Cd a sqrt(2 g) / W.
 * Below h ~ 2a the surface dips under the gate lip soon and the gate no longer controls the flow. */
static PetscReal DrainTime(PetscReal W, PetscReal H, PetscReal a, PetscReal g)
{
  PetscReal k = 0.6 * a * PetscSqrtReal(2 * g) / W, h_end = H > 4 * a ? 2 * a : 0.5 * (H + a);
  return 2 * (PetscSqrtReal(H) - PetscSqrtReal(h_end)) / k;
}

static PetscErrorCode Create(Sim sim)
{
  Sluice   *c;
  PetscReal g = 9.81, vmax; /* standard gravity for the defaults below (-gravity is read after the scene) */
  PetscInt  nwin = 2;
  PetscBool win_set;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->q));
  PetscCall(SceneKeepSeries(sim, &c->hup));
  PetscCall(SceneKeepSeries(sim, &c->hdown));
  PetscCall(SceneKeepSeries(sim, &c->vup));
  c->W = 0.1; c->H = 0.14; c->a = 0.03; c->Lc = -1; c->top = -1; c->rows = SimKernelRows(sim); c->gate_rows = 4; c->bevel = 45;
  c->dxc = -1; c->fine = 0.02;
  c->win[0] = -1; c->win[1] = -1;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene sluice_gate: a reservoir drains under a vertical gate", "");
  PetscCall(OptReal("-water_width", "Reservoir (water) width W between the left wall and the gate (m)", "", c->W, &c->W, NULL));
  PetscCall(OptReal("-water_depth", "Initial water depth H (m)", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-gate_opening", "Opening a between the gate's bottom edge and the floor (m)", "", c->a, &c->a, NULL));
  PetscCall(OptReal("-channel_length", "Channel length downstream of the gate, closed at its far end (m); default 1.3 sqrt(2 g H) t_end + 4a, beyond the jet front at t_end", "", c->Lc, &c->Lc, NULL));
  PetscCall(OptReal("-tank_height", "Height of the walls and the gate top (m); default 1.25 H", "", c->top, &c->top, NULL));
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles of the tank", "", c->rows, &c->rows, NULL));
  PetscCall(OptInt("-gate_rows", "Gate thickness in particle rows (>= 4: no gate particle sees water on both sides)", "", c->gate_rows, &c->gate_rows, NULL));
  PetscCall(OptReal("-gate_bevel", "Angle (deg) from the horizontal of the chamfer under the gate's downstream side, which leaves a sharp upstream edge; 0 = square-cut bottom", "", c->bevel, &c->bevel, NULL));
  PetscCall(OptReal("-dx_coarse", "Spacing of the water away from the gate (m); -dx is the spacing next to it, in the channel and of the gate; default -dx (uniform)", "", c->dxc, &c->dxc, NULL));
  PetscCall(OptReal("-fine_width", "Width of the fine zone of water before the gate (m), with -dx_coarse", "", c->fine, &c->fine, NULL));
  PetscCall(PetscOptionsRealArray("-q_window", "t0,t1: quasi-steady window (s) of the errors against the sluice relation; default 2 W / sqrt(g H) (the drawdown wave's round trip across the reservoir), t_end", "", c->win, &nwin, &win_set));
  PetscOptionsEnd();
  PetscCheck(c->W > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-water_width %g must be > 0", (double)c->W);
  PetscCheck(c->H > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-water_depth %g must be > 0", (double)c->H);
  PetscCheck(c->a > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_opening %g must be > 0", (double)c->a);
  PetscCheck(c->a < c->H, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_opening %g must be smaller than -water_depth %g: otherwise the gate holds no water back", (double)c->a, (double)c->H);
  PetscCheck(c->rows >= 1, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", c->rows);
  PetscCheck(c->gate_rows >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_rows %" PetscInt_FMT " must be >= 3 (water on both sides of the gate needs wall particles under its kernel)", c->gate_rows);
  PetscCheck(c->bevel >= 0 && c->bevel < 90, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_bevel %g must be in [0, 90) degrees", (double)c->bevel);
  PetscCheck(!win_set || (nwin == 2 && c->win[0] >= 0 && c->win[1] > c->win[0]), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-q_window needs two times t0,t1 with 0 <= t0 < t1");
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->H / 56));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, DrainTime(c->W, c->H, c->a, g)));
  if (c->top < 0) c->top = 1.25 * c->H;
  /* jet speed <= sqrt(2 g H) (Bernoulli from the initial surface): the front must not reach the far end */
  vmax = PetscSqrtReal(2 * g * c->H);
  if (c->Lc < 0) c->Lc = 1.3 * vmax * SimEndTime(sim) + 4 * c->a;
  /* start-up: the drawdown wave crosses the reservoir and comes back, 2 W / sqrt(g H) */
  if (!win_set) { c->win[0] = 2 * c->W / PetscSqrtReal(g * c->H); c->win[1] = SimEndTime(sim); }
  PetscCheck(c->a >= 4 * SimSpacing(sim) * (1 - 1e-9), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves %.2g particles across the gate opening %g m; at least 4 are needed: choose -dx <= %g", (double)SimSpacing(sim), (double)(c->a / SimSpacing(sim)), (double)c->a, (double)(c->a / 4));
  PetscCheck(SimSpacing(sim) <= 0.25 * c->W, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves fewer than 4 particles across -water_width %g: choose -dx <= %g", (double)SimSpacing(sim), (double)c->W, (double)(0.25 * c->W));
  PetscCheck(c->Lc >= 2 * c->a, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-channel_length %g must be at least twice the gate opening (%g m) so that the jet's vena contracta lies in the channel", (double)c->Lc, (double)(2 * c->a));
  PetscCheck(c->top >= c->H + 2 * SimSpacing(sim), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-tank_height %g must exceed -water_depth %g by at least 2 dx", (double)c->top, (double)c->H);
  /* the lattice's own extents: the gate edge and the water sit on lattice lines */
  c->W   = RoundToInt(c->W / SimSpacing(sim)) * SimSpacing(sim);
  c->H   = RoundToInt(c->H / SimSpacing(sim)) * SimSpacing(sim);
  c->a   = RoundToInt(c->a / SimSpacing(sim)) * SimSpacing(sim);
  c->Lc  = RoundToInt(c->Lc / SimSpacing(sim)) * SimSpacing(sim);
  c->top = RoundToInt(c->top / SimSpacing(sim)) * SimSpacing(sim);
  if (c->dxc < 0) c->dxc = SimSpacing(sim);
  PetscCall(SceneZonesSetUp(sim, c->dxc, &c->W, &c->fine, &c->H));
  c->xg0 = c->W;
  c->xg1 = c->W + c->gate_rows * SimSpacing(sim);
  /* h_up mid-reservoir; h_down two openings past the gate's sharp upstream edge, beyond the vena
   * contracta (at ~ a / Cc = 1.6 a; the frictionless supercritical jet keeps its depth after it) */
  c->x_up   = 0.5 * c->W;
  c->x_down = c->xg0 + 2 * c->a;
  PetscCheck(c->x_down + 2 * SimSpacing(sim) < c->xg1 + c->Lc, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The h_down station x = %g lies outside the channel: increase -channel_length", (double)c->x_down);
  PetscCall(SimSetReferenceSpeed(sim, vmax));
  /* walls: rows at the coarse spacing, or the fine rows as deep (< rows dc + dx) */
  PetscCall(SimSetDomain(sim, 0, -(c->rows + 0.5) * c->dxc, c->xg1 + c->Lc + c->rows * c->dxc + 1.5 * SimSpacing(sim)));
  PetscCall(SimSetDomain(sim, 1, -(c->rows * c->dxc + 1.5 * SimSpacing(sim)), c->top + c->H)); /* room for splashes above the walls */
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Sluice   *c  = (Sluice *)SimSceneContext(sim);
  PetscReal dx = SimSpacing(sim), rho0 = SimFluidMaterial(sim)->rho0;
  PetscInt  ng = c->gate_rows, nj = RoundToInt((c->top - c->a) / dx);
  PetscReal tb = PetscTanReal(c->bevel * PETSC_PI / 180);
  PetscFunctionBeginUser;
  PetscCheck(RoundToInt((ng - 1) * tb) < nj - ng, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_bevel %g is too steep for a %" PetscInt_FMT "-row gate below -tank_height %g: the chamfer would cut the gate through", (double)c->bevel, ng, (double)c->top);
  /* the water (coarse and fine zones) and the floor from the left wall to the channel's far end,
   * closed at both ends */
  PetscCall(SceneAddZonedWater(sim, c->dxc, c->W, c->fine, c->H, c->top, c->rows, c->xg1 + c->Lc, PETSC_TRUE));
  /* gate: column i starts j0(i) = round(i tan(bevel)) rows above the edge (the chamfer); particles on
   * a face touching water (upstream, downstream, underside) are wall, the inside dummy */
  for (PetscInt i = 0; i < ng; i++) {
    PetscInt j0 = RoundToInt(i * tb), j1 = i < ng - 1 ? RoundToInt((i + 1) * tb) : j0;
    for (PetscInt j = j0; j < nj; j++) {
      ParticleKind kind = (i == 0 || i == ng - 1 || j == j0 || j < j1) ? KIND_WALL : KIND_DUMMY;
      PetscCall(SceneAddLattice(sim, kind, c->xg0 + (i + 0.5) * dx, c->a + (j + 0.5) * dx, 1, 1, dx, rho0));
    }
  }
  PetscCall(SceneHydrostaticDensity(sim, 0, c->H));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Normalised 1D cubic B-spline of knot spacing s (support |r| < 2s, integral 1).  On particles
 * spaced s/n (n integer) it sums to exactly 1/(spacing): a lattice-exact sampling weight. */
static inline PetscReal BSpline1(PetscReal r, PetscReal s)
{
  PetscReal R = PetscAbsReal(r) / s;
  if (R < 1) return (2.0 / 3.0 - R * R + 0.5 * R * R * R) / s;
  if (R < 2) return (2 - R) * (2 - R) * (2 - R) / (6 * s);
  return 0;
}

/* Section integrals over the fluid, V_a = m_a / rho_a, phi = BSpline1:
 *   q      = sum_a V_a u_a phi_dx(x_a - x_c),  x_c the gate's centre: ~ int u dy through the
 *            section under the gate (phi's support 2 dx lies under a gate of >= 4 rows);
 *   h_up   = sum_a V_a phi_2dc(x_a - W/2):       the water column's volume per unit length = depth
 *            (dc the coarse spacing: exact on either zone's lattice);
 *   h_down = sum_a V_a phi_dx(x_a - (x_g0 + 2a)): the jet's depth the same way.
 * Also the fluid volume upstream of x_c, whose rate of decrease is q by mass conservation. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Sluice    *c = (Sluice *)SimSceneContext(sim);
  const PetscReal *x, *v, *m, *rho;
  const PetscInt  *kind;
  PetscReal        s[4] = {0, 0, 0, 0}, dx = SimSpacing(sim), xc = 0.5 * (c->xg0 + c->xg1);
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  PetscCall(SimGetField(sim, "m", NULL, &m));
  PetscCall(SimGetField(sim, "rho", NULL, &rho));
  for (PetscInt a = 0; a < n; a++) {
    PetscReal V, xa = x[2 * a];
    if (!KindIsFluid(kind[a])) continue;
    V = SceneFluidVolume(sim, m[a], rho[a]);
    s[0] += V * v[2 * a] * BSpline1(xa - xc, dx);
    s[1] += V * BSpline1(xa - c->x_up, 2 * c->dxc);
    s[2] += V * BSpline1(xa - c->x_down, dx);
    if (xa < xc) s[3] += V;
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCall(SimRestoreField(sim, "m", NULL, &m));
  PetscCall(SimRestoreField(sim, "rho", NULL, &rho));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 4, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = s[0]; vals[1] = s[1]; vals[2] = s[2];
  PetscCall(SeriesAppend(&c->q, SimTime(sim), s[0]));
  PetscCall(SeriesAppend(&c->hup, SimTime(sim), s[1]));
  PetscCall(SeriesAppend(&c->hdown, SimTime(sim), s[2]));
  PetscCall(SeriesAppend(&c->vup, SimTime(sim), s[3]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cc of a sharp-edged vertical gate from the reference table (row "Cc_sharp_edged_vertical_gate",
 * column "value"); the table is key-value, not the x,y curves RefDataLoad reads.  Rank 0 reads,
 * everyone gets it; *found false leaves *Cc alone. */
static PetscErrorCode LoadCc(Sim sim, PetscReal *Cc, PetscBool *found)
{
  char        line[4096];
  const char *file = "sluice_gate_reference_coefficients.csv", *key = "Cc_sharp_edged_vertical_gate";
  PetscReal   buf[2] = {0, 0};
  FILE       *f;
  PetscFunctionBeginUser;
  PetscCall(RefDataOpen(SimRefData(sim), file, &f)); /* a missing file is reported there */
  if (f) {
    while (fgets(line, sizeof(line), f)) {
      size_t n = strlen(key);
      if (!strncmp(line, key, n) && line[n] == ',') { buf[0] = atof(line + n + 1); buf[1] = 1; break; }
    }
    fclose(f);
    if (!(buf[1] > 0 && buf[0] > 0 && buf[0] < 1)) {
      PetscCall(PetscInfo(NULL, "Reference %s has no valid row %s: the sluice-gate errors are not reported\n", file, key));
      buf[1] = 0;
    }
  }
  PetscCallMPI(MPI_Bcast(buf, 2, MPIU_REAL, 0, SimComm(sim)));
  *found = (PetscBool)(buf[1] > 0);
  if (*found) *Cc = buf[0];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Sluice relation: q = Cd a sqrt(2 g h), Cd = Cc / sqrt(1 + Cc a / h) */
static inline PetscReal SluiceQ(PetscReal Cc, PetscReal a, PetscReal h, PetscReal g) { return Cc / PetscSqrtReal(1 + Cc * a / h) * a * PetscSqrtReal(2 * g * h); }

/* Cc implied by a measured (q, h): Cd^2 (1 + Cc a / h) = Cc^2, the positive root */
static inline PetscReal ImpliedCc(PetscReal q, PetscReal a, PetscReal h, PetscReal g)
{
  PetscReal Cd = q / (a * PetscSqrtReal(2 * g * h)), b = Cd * Cd * a / h;
  return 0.5 * (b + PetscSqrtReal(b * b + 4 * Cd * Cd));
}

/* Time averages (trapezoid) over the window [t0, t1] of the probe histories:
 *   q_rel_err_mean = <|q - q_rel(h_up)| / q_rel(h_up)>, q_rel_bias = <(q - q_rel) / q_rel>;
 *   q_mass = (V_up(t0) - V_up(t1)) / (t1 - t0): the mean discharge from the volume upstream of the
 *            gate, against <q_rel>;
 *   Cc_from_h_down = <h_down> / a;  Cc_from_q = <Cc implied by q and h_up>. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Sluice   *c = (Sluice *)SimSceneContext(sim);
  PetscReal Cc = 0.611, g = -SimGravity(sim)[1], t0 = c->win[0], t1 = PetscMin(c->win[1], SimTime(sim));
  PetscReal T = 0, Eabs = 0, Ebias = 0, Qs = 0, Qr = 0, Hd = 0, Ccq = 0, hmin = PETSC_MAX_REAL, hmax = 0;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(LoadCc(sim, &Cc, &found));
  for (PetscInt k = 1; k < c->q.n; k++) {
    PetscReal ta = c->q.t[k - 1], tb = c->q.t[k], w;
    if (tb <= t0 || ta >= t1) continue;
    w = 0.5 * (PetscMin(tb, t1) - PetscMax(ta, t0)); /* both ends weighted alike: a trapezoid on the clipped interval */
    for (PetscInt j = k - 1; j <= k; j++) {
      PetscReal q = c->q.y[j], h = c->hup.y[j], qr = SluiceQ(Cc, c->a, h, g);
      Eabs += w * PetscAbsReal(q - qr) / qr;
      Ebias += w * (q - qr) / qr;
      Qs += w * q; Qr += w * qr;
      Hd += w * c->hdown.y[j];
      Ccq += w * ImpliedCc(q, c->a, h, g);
      hmin = PetscMin(hmin, h); hmax = PetscMax(hmax, h);
      T += w;
    }
  }
  if (f) {
    fprintf(f, "\"gate_opening\": %.6g, \"q_window\": [%.6g, %.6g], ", (double)c->a, (double)t0, (double)t1);
    if (T > 0 && found) {
      PetscReal qm = (SeriesAt(&c->vup, t0) - SeriesAt(&c->vup, t1)) / (t1 - t0);
      fprintf(f, "\"q_rel_err_mean\": %.6g, \"q_rel_bias\": %.6g, \"q_mean\": %.6g, \"q_ref_mean\": %.6g, ", (double)(Eabs / T), (double)(Ebias / T), (double)(Qs / T), (double)(Qr / T));
      fprintf(f, "\"q_mass\": %.6g, \"q_mass_rel_err\": %.6g, ", (double)qm, (double)((qm - Qr / T) / (Qr / T)));
      fprintf(f, "\"Cc_from_h_down\": %.6g, \"Cc_from_q\": %.6g, \"Cc_ref\": %.6g, \"h_up_range\": [%.6g, %.6g], \"h_down_mean\": %.6g, ", (double)(Hd / T / c->a), (double)(Ccq / T), (double)Cc, (double)hmin, (double)hmax, (double)(Hd / T));
    }
    fprintf(f, "\"reference\": \"free-flow sluice relation q = Cd a sqrt(2 g h_up), Cd = Cc / sqrt(1 + Cc a / h_up)%s\"", found ? "" : " (reference table not found: no errors)");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Sluice *c = (Sluice *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->q));
  PetscCall(SeriesDestroy(&c->hup));
  PetscCall(SeriesDestroy(&c->hdown));
  PetscCall(SeriesDestroy(&c->vup));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneSluiceGate = {
  .name = "sluice_gate", .help = "a reservoir drains under a vertical gate (paper section 3.1)",
  .create = Create, .populate = Populate,
  .nprobes = 3, .probe_names = {"q", "h_up", "h_down"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
