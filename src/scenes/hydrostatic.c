/* Water at rest in a tank: the floor pressure must be rho g H, the side wall's rho g (H - y), and
 * nothing must move.  In 2D or 3D (-dim 3: a square tank W x W, the water H deep, gravity along -z).
 * The side wall's pressure is read as a wall sensor reads it (SceneProbePressure on the wall's
 * face) at NWALL heights; its spread about rho g (H - y) after the first second is what the impact
 * cases' sensors carry as noise (issue 56). */
#include <sphfsi.h>

#define NWALL 8 /* heights on the side wall */

typedef struct {
  PetscReal W, H;
  PetscInt  rows;
  Series    pb;   /* p_bottom history */
  Series    dev;  /* rms over the wall's heights of (p - rho g (H - y)) / (rho g H) */
  Series    dmax; /* the largest |p - rho g (H - y)| / (rho g H) over the wall's heights */
} Hydro;

static PetscErrorCode Create(Sim sim)
{
  Hydro *c;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepSeries(sim, &c->pb));
  PetscCall(SceneKeepSeries(sim, &c->dev));
  PetscCall(SceneKeepSeries(sim, &c->dmax));
  c->W = 0.1; c->H = 0.1; c->rows = SimKernelRows(sim);
  PetscOptionsBegin(SimComm(sim), NULL, "Scene hydrostatic: water at rest in a tank", "");
  PetscCall(OptReal("-tank_width", "Tank (and water) width (m)", "", c->W, &c->W, NULL));
  PetscCall(OptReal("-water_depth", "Water depth H (m)", "", c->H, &c->H, NULL));
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles", "", c->rows, &c->rows, NULL));
  {
    PetscInt dim = SimDim(sim);
    PetscCall(OptInt("-dim", "Dimension: 2, or 3 for a square tank W x W with gravity along -z", "", dim, &dim, NULL));
    PetscCall(SimSetDim(sim, dim));
  }
  PetscOptionsEnd();
  PetscCheck(SimDim(sim) == 2 || SimDim(sim) == 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dim %" PetscInt_FMT " must be 2 or 3", SimDim(sim));
  if (SimDim(sim) == 3) PetscCall(SimSetGravity(sim, SimGravity(sim)[0], 0, -9.81));
  PetscCheck(c->W > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-tank_width %g must be > 0", (double)c->W);
  PetscCheck(c->H > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-water_depth %g must be > 0", (double)c->H);
  PetscCheck(c->rows >= 1, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", c->rows);
  if (SimSpacing(sim) < 0) PetscCall(SimSetSpacing(sim, c->H / 40));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 1.0));
  PetscCheck(SimSpacing(sim) <= 0.5 * PetscMin(c->W, c->H), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dx %g is larger than half the water region (%g x %g m): choose a smaller -dx", (double)SimSpacing(sim), (double)c->W, (double)c->H);
  PetscCall(SimSetReferenceSpeed(sim, PetscSqrtReal(2 * 9.81 * c->H)));
  SceneTankDomain(sim, c->W, 1.5 * c->H, c->rows);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Hydro   *c = (Hydro *)SimSceneContext(sim);
  PetscReal dx = SimSpacing(sim);
  PetscInt nx = RoundToInt(c->W / dx), ny = RoundToInt(c->H / dx);
  PetscFunctionBeginUser;
  c->W = nx * dx; c->H = ny * dx; /* the lattice's own extent */
  if (SimDim(sim) == 3) {
    const PetscReal lo[3] = {0, 0, 0}, hi[3] = {c->W, c->W, c->H}, first[3] = {0.5 * dx, 0.5 * dx, 0.5 * dx};
    PetscCall(SceneAddBlock(sim, KIND_FLUID, first, (PetscInt[]){nx, nx, ny}, dx, SimFluidMaterial(sim)->rho0));
    PetscCall(SceneAddTankBox(sim, lo, hi, 1.2 * c->H, dx, c->rows));
  } else {
    PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dx, 0.5 * dx, nx, ny, dx, SimFluidMaterial(sim)->rho0));
    PetscCall(SceneAddTank(sim, 0, c->W, 0, 1.2 * c->H, dx, c->rows, PETSC_TRUE, PETSC_TRUE));
  }
  PetscCall(SceneHydrostaticDensity(sim, 0, c->H));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* p_bottom, v_max, and the side wall's deviation from rho g (H - y) (rms over NWALL heights,
 * over rho g H) */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Hydro         *c  = (Hydro *)SimSceneContext(sim);
  const PetscInt up = SimDim(sim) - 1;
  const PetscReal rg = SimFluidMaterial(sim)->rho0 * (-SimGravity(sim)[up]) * c->H;
  PetscReal      x0[3] = {0.5 * c->W, SimDim(sim) == 3 ? 0.5 * c->W : 0, 0}; /* the middle of the floor */
  PetscReal      s2 = 0, dm = 0;
  PetscFunctionBeginUser;
  PetscCall(SceneProbePressure(sim, x0, &vals[0]));
  PetscCall(SceneMaxSpeed(sim, &vals[1]));
  PetscCall(SeriesAppend(&c->pb, SimTime(sim), vals[0]));
  for (PetscInt k = 0; k < NWALL; k++) { /* the wall x = 0, in 3D the middle of its face */
    PetscReal xw[3] = {0, 0.5 * c->W, 0}, p, d;
    xw[up] = (k + 0.5) * c->H / NWALL;
    PetscCall(SceneProbePressure(sim, xw, &p));
    d = (p - rg * (1 - xw[up] / c->H)) / rg;
    s2 += d * d;
    dm = PetscMax(dm, PetscAbsReal(d));
  }
  vals[2] = PetscSqrtReal(s2 / NWALL);
  PetscCall(SeriesAppend(&c->dev, SimTime(sim), vals[2]));
  PetscCall(SeriesAppend(&c->dmax, SimTime(sim), dm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mean floor pressure over the last quarter of the run against rho g H; the side wall's spread
 * about rho g (H - y) after the first second (rms over the heights and the samples), and its largest
 * deviation. */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Hydro    *c = (Hydro *)SimSceneContext(sim);
  PetscReal ref = SimFluidMaterial(sim)->rho0 * (-SimGravity(sim)[SimDim(sim) - 1]) * c->H, s = 0, vmax;
  PetscInt  n = 0;
  PetscFunctionBeginUser;
  PetscCall(SceneMaxSpeed(sim, &vmax));
  for (PetscInt k = 0; k < c->pb.n; k++)
    if (c->pb.t[k] >= 0.75 * SimTime(sim)) { s += c->pb.y[k]; n++; }
  if (f) fprintf(f, "\"p_bottom_rel_err\": %.6g, \"p_bottom_ref\": %.6g, \"v_max_final\": %.6g", (double)(n ? PetscAbsReal(s / n - ref) / ref : -1), (double)ref, (double)vmax);
  {
    PetscReal s2 = 0, dm = 0;
    n = 0;
    for (PetscInt k = 0; k < c->dev.n; k++)
      if (c->dev.t[k] >= 1.0) { s2 += c->dev.y[k] * c->dev.y[k]; dm = PetscMax(dm, c->dmax.y[k]); n++; }
    if (f && n) fprintf(f, ", \"p_wall_spread\": %.6g, \"p_wall_dev_max\": %.6g", (double)PetscSqrtReal(s2 / n), (double)dm);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Hydro *c = (Hydro *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->pb));
  PetscCall(SeriesDestroy(&c->dev));
  PetscCall(SeriesDestroy(&c->dmax));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneHydrostatic = {
  .name = "hydrostatic", .help = "water at rest in a tank",
  .create = Create, .populate = Populate,
  .nprobes = 3, .probe_names = {"p_bottom", "v_max", "p_wall_dev"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
