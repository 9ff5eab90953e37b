/* Water at rest on a thick elastic plate (fluid on solid, issue 5), periodic in x so that no side
 * wall takes a share of the weight (SPH pair forces between fluid and side-wall particles at
 * different heights carry some): the plate's lowest rows are clamped, and the force the clamp
 * takes must equal the weight of the water plus the plate's own.  Checks that the fluid's
 * pressure reaches the solid whole (Newton's third law of the fluid-solid pair forces) in both
 * fluid schemes. */
#include <sphfsi.h>

typedef struct {
  PetscReal W, H, T;       /* periodic width, water depth, plate thickness */
  PetscInt  nclamp;        /* clamped rows at the plate's bottom */
  PetscReal w_water, w_plate; /* weights (N/m), from the particles' masses */
  Series    ratio;         /* (support - plate weight) / water weight */
} Plate;

static PetscErrorCode Create(Sim sim)
{
  Plate *c;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->ratio));
  c->W = 0.05; c->H = 0.05; c->T = 0.01; c->nclamp = 2;
  SimSolidMaterial(sim)->rho0 = 1100; SimSolidMaterial(sim)->K = 2.0e7; SimSolidMaterial(sim)->G = 4.27e6; /* the elastic gate's rubber */
  PetscOptionsBegin(SimComm(sim), NULL, "Scene water_on_plate: water at rest on a clamped elastic plate", "");
  PetscCall(OptReal("-tank_width", "Periodic width of the water and the plate (m)", "", c->W, &c->W, NULL));
  PetscCall(OptReal("-water_depth", "Water depth (m)", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-plate_thickness", "Plate thickness (m), clamp rows included", "", c->T, &c->T, NULL));
  PetscCall(OptInt("-clamp_rows", "Rows of clamped particles at the plate's bottom", "", c->nclamp, &c->nclamp, NULL));
  PetscOptionsEnd();
  PetscCheck(c->W > 0 && c->H > 0 && c->T > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-tank_width %g, -water_depth %g and -plate_thickness %g must be > 0", (double)c->W, (double)c->H, (double)c->T);
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->H / 20));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 0.3));
  PetscCheck(SimSpacing(sim) <= 0.5 * PetscMin(c->W, c->H), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g is larger than half the water region (%g x %g m): choose a smaller -dx", (double)SimSpacing(sim), (double)c->W, (double)c->H);
  PetscCheck(c->nclamp >= 1 && c->T / SimSpacing(sim) > c->nclamp + 0.999, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-plate_thickness %g must leave at least one free row above -clamp_rows %" PetscInt_FMT " >= 1 at -dx %g", (double)c->T, c->nclamp, (double)SimSpacing(sim));
  c->W = RoundToInt(c->W / SimSpacing(sim)) * SimSpacing(sim); /* whole lattice columns in the period */
  PetscCheck(c->W >= 3 * (2 * SimKernelHFactor(sim) + 0.5) * SimSpacing(sim), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-tank_width %g: the periodic grid needs at least 3 cells of 2 h + skin; choose a smaller -dx", (double)c->W);
  PetscCall(SimSetMedia(sim, SimHasFluid(sim), PETSC_TRUE));
  PetscCall(SimSetReferenceSpeed(sim, PetscSqrtReal(2 * 9.81 * c->H)));
  PetscCall(SimSetPeriodic(sim, 0, PETSC_TRUE));
  PetscCall(SimSetDomain(sim, 0, 0, c->W));
  PetscCall(SimSetDomain(sim, 1, -c->T - SimSpacing(sim), 1.5 * c->H));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Plate    *c  = (Plate *)SimSceneContext(sim);
  PetscReal dx = SimSpacing(sim);
  PetscInt  nx = RoundToInt(c->W / dx), ny = RoundToInt(c->H / dx), nt = RoundToInt(c->T / dx);
  PetscFunctionBeginUser;
  c->W = nx * dx; c->H = ny * dx; c->T = nt * dx;
  PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dx, 0.5 * dx, nx, ny, dx, SimFluidMaterial(sim)->rho0));
  PetscCall(SceneAddLattice(sim, KIND_CLAMP, 0.5 * dx, 0.5 * dx - c->T, nx, c->nclamp, dx, SimSolidMaterial(sim)->rho0));
  PetscCall(SceneAddLattice(sim, KIND_SOLID, 0.5 * dx, (c->nclamp + 0.5) * dx - c->T, nx, nt - c->nclamp, dx, SimSolidMaterial(sim)->rho0));
  PetscCall(SceneHydrostaticDensity(sim, 0, c->H));
  { /* weights from the masses the particles carry */
    const PetscReal *m;
    const PetscInt  *kind;
    PetscReal        w[2] = {0, 0}, g = -SimGravity(sim)[1];
    PetscInt         n;
    PetscCall(SimGetLocalSize(sim, &n));
    PetscCall(SimGetField(sim, "kind", NULL, &kind));
    PetscCall(SimGetField(sim, "m", NULL, &m));
    for (PetscInt a = 0; a < n; a++) {
      if (KindIsFluid(kind[a])) w[0] += m[a] * g;
      if (KindIsSolid(kind[a])) w[1] += m[a] * g;
    }
    PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
    PetscCall(SimRestoreField(sim, "m", NULL, &m));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, w, 2, MPIU_REAL, MPI_SUM, SimComm(sim)));
    c->w_water = w[0]; c->w_plate = w[1];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* support_y: the clamp's upward force on the plate (N/m), the mean over the last step's solid
 * sub-steps (a load cell's low-pass: the plate rings at its acoustic frequency); load_ratio: (support_y - plate weight) /
 * water weight, 1 when the plate carries the water; v_max. */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Plate    *c = (Plate *)SimSceneContext(sim);
  PetscReal f = SimSolidSupport(sim)[1];
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &f, 1, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = f;
  vals[1] = (f - c->w_plate) / c->w_water;
  PetscCall(SceneMaxSpeed(sim, &vals[2]));
  if (SimStep(sim) > 0) PetscCall(SeriesAppend(&c->ratio, SimTime(sim), vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The load ratio's mean over the second half of the run (the acoustic oscillations of the start
 * average out) against 1. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Plate    *c = (Plate *)SimSceneContext(sim);
  PetscReal s = 0;
  PetscInt  n = 0;
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < c->ratio.n; k++)
    if (c->ratio.t[k] >= 0.5 * SimTime(sim)) { s += c->ratio.y[k]; n++; }
  if (f) fprintf(f, "\"load_ratio_mean\": %.6g, \"load_rel_err\": %.6g, \"water_weight\": %.6g, \"plate_weight\": %.6g, \"reference\": \"support = water + plate weight\"", (double)(n ? s / n : -1), (double)(n ? PetscAbsReal(s / n - 1) : -1), (double)c->w_water, (double)c->w_plate);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Plate *c = (Plate *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->ratio));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneWaterOnPlate = {
  .name = "water_on_plate", .help = "water at rest on a clamped elastic plate: the support carries the water's weight",
  .create = Create, .populate = Populate,
  .nprobes = 3, .probe_names = {"support_y", "load_ratio", "v_max"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
