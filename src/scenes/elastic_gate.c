/* Water column released through an elastic gate (paper section 3.3; Antoci, Gallati & Sibilla
 * 2007).  Water W wide and H deep in a tank; on its right a rubber gate of length L and thickness
 * t, clamped at its top into a rigid wall that holds the water above it, free at the bottom where
 * it rests on the floor and closes the outflow.  The water pushes the gate open and runs out along
 * the floor, which goes on downstream of the gate (the experiment's tank bottom: the opening is then
 * the gap between the gate's end and the floor, not the whole swing of the gate); fluid that leaves
 * the domain box is removed.  x points downstream, y up.
 * -dim 3: the same layout extruded in z (SceneExtrudeBegin) over -gate_width, periodic across it
 * (a slab of the 2D case, which it must reproduce), or with -gate_side_walls between the walls of
 * the tank's real width (0.1 m by default), on a uniform lattice. */
#include <sphfsi.h>

typedef struct {
  PetscReal W, H, L, t, top;   /* water width and depth, gate length and thickness, wall top */
  PetscReal dxc, fine;         /* coarse spacing away from the gate; width of the fine zone before it */
  PetscReal floor;             /* length of the floor downstream of the gate */
  PetscReal width;             /* 3D: the slab's width in z, periodic (m) */
  PetscInt  nz;                /* 3D: particle layers across it */
  PetscBool side_walls;        /* 3D: walls at z = 0 and z = width instead of periodicity */
  PetscInt  rows, nclamp;      /* wall rows (coarse spacing); clamp rows of the gate inside its support */
  Series    dx_tip, dy_tip;
} Gate;

static PetscErrorCode Create(Sim sim)
{
  Gate *c;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->dx_tip)); /* checkpoints carry the histories */
  PetscCall(SceneKeepSeries(sim, &c->dy_tip));
  c->W = 0.1; c->H = 0.14; c->L = 0.079; c->t = 0.005; c->top = 0.16; c->rows = SimKernelRows(sim); c->nclamp = 4; c->dxc = -1; c->fine = 0.02; c->floor = 0.1;
  SimSolidMaterial(sim)->rho0 = 1100; SimSolidMaterial(sim)->K = 2.0e7; SimSolidMaterial(sim)->G = 4.27e6; /* rubber, paper section 3.3 */
  SimFluidMaterial(sim)->mu   = 1.0e-3;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene elastic_gate: water column released through an elastic gate (Antoci et al. 2007)", "");
  PetscCall(OptReal("-water_width", "Width of the water column behind the gate (m)", "", c->W, &c->W, NULL));
  PetscCall(OptReal("-water_depth", "Initial water depth (m)", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-gate_length", "Gate length below its clamp (m)", "", c->L, &c->L, NULL));
  PetscCall(OptReal("-gate_thickness", "Gate thickness (m)", "", c->t, &c->t, NULL));
  PetscCall(OptReal("-tank_height", "Height of the tank walls (m)", "", c->top, &c->top, NULL));
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles", "", c->rows, &c->rows, NULL));
  PetscCall(OptInt("-clamp_rows", "Rows of clamp particles at the top of the gate", "", c->nclamp, &c->nclamp, NULL));
  PetscCall(OptReal("-dx_coarse", "Spacing of the fluid away from the gate (m); default -dx (uniform)", "", c->dxc, &c->dxc, NULL));
  PetscCall(OptReal("-fine_width", "Width of the fine fluid zone before the gate (m), with -dx_coarse", "", c->fine, &c->fine, NULL));
  PetscCall(OptReal("-floor_downstream", "Length of the floor downstream of the gate (m); 0 = the floor ends under the gate and the water falls freely past it", "", c->floor, &c->floor, NULL));
  {
    PetscInt dim = SimDim(sim);
    PetscCall(OptInt("-dim", "Dimension: 2, or 3 for a slab of the 2D case, periodic across -gate_width", "", dim, &dim, NULL));
    PetscCall(SimSetDim(sim, dim));
  }
  c->width = -1;
  if (SimDim(sim) == 3) PetscCall(OptBool("-gate_side_walls", "3D: the tank's side walls at z = 0 and z = -gate_width (default 0.1 m, the experiment's tank) instead of a periodic slab", "", c->side_walls, &c->side_walls, NULL));
  if (SimDim(sim) == 3) PetscCall(OptReal("-gate_width", "3D: width in z (m): of the periodic slab, default 10 dx (the periodic grid needs 3 cells of 2 h + skin); between side walls, default 0.1 m", "", c->width, &c->width, NULL));
  PetscOptionsEnd();
  PetscCheck(SimDim(sim) == 2 || SimDim(sim) == 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dim %" PetscInt_FMT " must be 2 or 3", SimDim(sim));
  PetscCheck(c->W > 0 && c->H > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-water_width %g and -water_depth %g must be > 0", (double)c->W, (double)c->H);
  PetscCheck(c->t > 0 && c->L > c->t, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_length %g must exceed -gate_thickness %g > 0", (double)c->L, (double)c->t);
  PetscCheck(c->L < c->H, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_length %g must be less than -water_depth %g (the rigid wall above the gate holds the rest)", (double)c->L, (double)c->H);
  PetscCheck(c->top > c->H, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-tank_height %g must exceed -water_depth %g", (double)c->top, (double)c->H);
  PetscCheck(c->floor >= 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-floor_downstream %g must be >= 0", (double)c->floor);
  PetscCheck(c->rows >= 1, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", c->rows);
  PetscCheck(c->nclamp >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-clamp_rows %" PetscInt_FMT " must be >= 3 (the clamp must fill the kernel support)", c->nclamp);
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, 0.001));
  PetscCheck(c->t / SimSpacing(sim) > 2.999, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g leaves fewer than 3 particles across the gate thickness %g", (double)SimSpacing(sim), (double)c->t);
  if (c->dxc < 0) c->dxc = SimSpacing(sim);
  PetscCheck(SimDim(sim) == 2 || c->dxc == SimSpacing(sim), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-dim 3 takes a uniform lattice: drop -dx_coarse %g (or set it to -dx %g)", (double)c->dxc, (double)SimSpacing(sim));
  PetscCall(SceneZonesSetUp(sim, c->dxc, &c->W, &c->fine, &c->H));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 0.4));
  PetscCall(SimSetMedia(sim, SimHasFluid(sim), PETSC_TRUE));
  PetscCall(SimSetOutflow(sim, PETSC_TRUE));
  PetscCall(SimSetReferenceSpeed(sim, PetscSqrtReal(2 * 9.81 * c->H)));
  PetscCall(SimSetDomain(sim, 0, -(c->rows + 0.5) * c->dxc, c->W + c->t + PetscMax(0.1, c->floor + 2 * c->dxc))); /* fluid beyond leaves */
  PetscCall(SimSetDomain(sim, 1, -0.1, c->top + SimSpacing(sim)));
  if (SimDim(sim) == 3) {
    if (c->width < 0) c->width = c->side_walls ? 0.1 : 10 * SimSpacing(sim);
    c->nz = RoundToInt(c->width / SimSpacing(sim));
    PetscCheck(c->nz >= 6, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gate_width %g holds fewer than 6 particles", (double)c->width);
    c->width         = c->nz * SimSpacing(sim);
    PetscCall(SimSetDomain(sim, 2, c->side_walls ? -(c->rows + 0.5) * SimSpacing(sim) : 0, c->side_walls ? c->width + (c->rows + 0.5) * SimSpacing(sim) : c->width));
    PetscCall(SimSetPeriodic(sim, 2, (PetscBool)!c->side_walls));
  }
  PetscCall(SimEnableField(sim, "x0"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Gate     *c  = (Gate *)SimSceneContext(sim);
  PetscReal dx = SimSpacing(sim), xg = c->W; /* gate's upstream face */
  PetscInt  nt = RoundToInt(c->t / dx), nl = RoundToInt(c->L / dx), ntop = RoundToInt(c->top / dx);
  PetscFunctionBeginUser;
  if (SimDim(sim) == 3) PetscCall(SceneExtrudeBegin(sim, c->nz, 0, dx));
  PetscCall(SceneAddZonedWater(sim, c->dxc, c->W, c->fine, c->H, c->top, c->rows, xg + nt * dx + RoundToInt(c->floor / dx) * dx, PETSC_FALSE));
  /* the gate and its clamp */
  PetscCall(SceneAddLattice(sim, KIND_SOLID, xg + 0.5 * dx, 0.5 * dx, nt, nl, dx, SimSolidMaterial(sim)->rho0));
  PetscCall(SceneAddLattice(sim, KIND_CLAMP, xg + 0.5 * dx, (nl + 0.5) * dx, nt, c->nclamp, dx, SimSolidMaterial(sim)->rho0));
  { /* rigid wall above the clamp: the column facing the water is wall, the rest dummy */
    const PetscReal above[4] = {xg, (nl + c->nclamp) * dx, xg + nt * dx, ntop * dx};
    const PetscBool faces[4] = {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
    PetscCall(SceneAddWallBox(sim, above, dx, faces));
  }
  PetscCall(SceneHydrostaticDensity(sim, 0, RoundToInt(c->H / dx) * dx));
  PetscCall(SceneExtrudeEnd(sim));
  if (SimDim(sim) == 3 && c->side_walls) { /* the tank's side walls over its whole section: one wall layer, then dummies */
    PetscInt nx = c->rows + nt + RoundToInt(c->W / dx) + RoundToInt(c->floor / dx), ny = c->rows + ntop;
    for (PetscInt k = 0; k < c->rows; k++)
      for (PetscInt side = 0; side < 2; side++) {
        const PetscReal lo[3] = {-(c->rows - 0.5) * dx, -(c->rows - 0.5) * dx, side ? c->width + (k + 0.5) * dx : -(k + 0.5) * dx};
        PetscCall(SceneAddBlock(sim, k ? KIND_DUMMY : KIND_WALL, lo, (PetscInt[]){nx, ny, 1}, dx, SimFluidMaterial(sim)->rho0));
      }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* tip_dx, tip_dy: mean displacement of the gate's bottom row; water_level: the fluid's volume in a
 * strip 4 dx wide at the back wall over the strip's width, measured as the dam break's column height
 * (SceneFluidVolume, SceneStripShare; a drop stuck to the wall above the surface moves it by dx / 4
 * only); load_x: the water's horizontal force on the gate (N/m; mean over the last step's solid
 * sub-steps).  In 3D, per unit width of the slab. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Gate      *c = (Gate *)SimSceneContext(sim);
  const PetscReal *x, *x0, *m, *rho;
  const PetscInt  *kind;
  PetscReal        s[4] = {0, 0, 0, 0}, strip = 4 * SimSpacing(sim);
  PetscInt         D = SimDim(sim), n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "x0", NULL, &x0));
  PetscCall(SimGetField(sim, "m", NULL, &m));
  PetscCall(SimGetField(sim, "rho", NULL, &rho));
  for (PetscInt a = 0; a < n; a++) {
    if (kind[a] == KIND_SOLID && x0[D * a + 1] < SimSpacing(sim)) {
      s[0] += x[D * a] - x0[D * a];
      s[1] += x[D * a + 1] - x0[D * a + 1];
      s[2] += 1;
    }
    if (KindIsFluid(kind[a])) s[3] += SceneFluidVolume(sim, m[a], rho[a]) * SceneStripShare(x[D * a], strip, SimSpacing(sim));
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCall(SimRestoreField(sim, "m", NULL, &m));
  PetscCall(SimRestoreField(sim, "rho", NULL, &rho));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 4, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = s[2] > 0 ? s[0] / s[2] : 0;
  vals[1] = s[2] > 0 ? s[1] / s[2] : 0;
  vals[2] = s[3] / strip;
  vals[3] = SimSolidLoad(sim)[0];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &vals[3], 1, MPIU_REAL, MPI_SUM, SimComm(sim)));
  if (D == 3) { vals[2] /= c->width; vals[3] /= c->width; }
  PetscCall(SeriesAppend(&c->dx_tip, SimTime(sim), vals[0]));
  PetscCall(SeriesAppend(&c->dy_tip, SimTime(sim), vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* RMS and maximum of |sim - experiment| (m) at the experiment's times in [0, t], for one file. */
static PetscErrorCode Compare(Sim sim, FILE *f, const Series *s, const char *file, const char *col, const char *key)
{
  Series    ref = {0};
  PetscBool found;
  PetscReal rms, max;
  PetscInt  n;
  PetscFunctionBeginUser;
  PetscCall(RefDataLoad(SimRefData(sim), file, "t_s", col, &ref, &found));
  if (found && f) {
    PetscCall(SeriesCompare(s, &ref, 1.0, 1.0, 0, SimTime(sim), PETSC_FALSE, &rms, &max, &n));
    fprintf(f, "\"%s_err_rms\": %.6g, \"%s_err_max\": %.6g, \"%s_points\": %d, ", key, (double)rms, key, (double)max, key, (int)n);
  }
  PetscCall(SeriesDestroy(&ref));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Against both digitisations of the experiment (Antoci et al. 2007, Figs. 11-12 of the paper). */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Gate *c = (Gate *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(Compare(sim, f, &c->dx_tip, "antoci2007_exp_tipdx__chrono.csv", "dx_m", "tip_dx"));
  PetscCall(Compare(sim, f, &c->dy_tip, "antoci2007_exp_tipdy__chrono.csv", "dy_m", "tip_dy"));
  PetscCall(Compare(sim, f, &c->dx_tip, "antoci2007_exp_tipdx__fsi_etvf.csv", "dx_m", "tip_dx_digitisation2"));
  PetscCall(Compare(sim, f, &c->dy_tip, "antoci2007_exp_tipdy__fsi_etvf.csv", "dy_m", "tip_dy_digitisation2"));
  if (f) fprintf(f, "\"tip_dx_final\": %.6g, \"tip_dy_final\": %.6g, \"fluid_mass_out\": %.6g, \"reference\": \"Antoci, Gallati & Sibilla 2007 experiment (errors in m)\"", (double)(c->dx_tip.n ? c->dx_tip.y[c->dx_tip.n - 1] : 0), (double)(c->dy_tip.n ? c->dy_tip.y[c->dy_tip.n - 1] : 0), (double)SimFluidMassOut(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Gate *c = (Gate *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->dx_tip));
  PetscCall(SeriesDestroy(&c->dy_tip));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneElasticGate = {
  .name = "elastic_gate", .help = "water column released through an elastic gate (Antoci et al. 2007)",
  .create = Create, .populate = Populate,
  .nprobes = 4, .probe_names = {"tip_dx", "tip_dy", "water_level", "load_x"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
