/* A scene of one's own, outside sphfsi's source tree: an elastic plate whose base (its columns at
 * x < 0) is shaken up and down, y_base(t) = A (1 - cos w t) (a prescribed motion: the base's
 * velocity is set in every solid step), and a probe of one's own: the tip's deflection relative to
 * the base.
 * Below the plate's first bending frequency the plate follows its base nearly rigidly; the tip lags
 * by about A r^2 / (1 - r^2) times the cantilever's participation factor (1.57), r = w / w_1.
 *
 *   PKG_CONFIG_PATH=PREFIX/lib/pkgconfig make
 *   mpiexec -n 2 ./shaken_plate -options_file shaken_plate.opts */
#include <sphfsi.h>

typedef struct {
  PetscReal L, H, A, f; /* plate length and thickness, base amplitude and frequency (Hz) */
  PetscInt  ny, nx, nbase; /* particles across, along the free plate, columns of the base */
  PetscReal rel_min, rel_max; /* extremes of the tip's deflection relative to the base */
} ShakenPlate;

static PetscErrorCode Create(Sim sim)
{
  ShakenPlate *c;
  PetscReal    reach;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepReal(sim, &c->rel_min)); /* restarts continue the extremes */
  PetscCall(SceneKeepReal(sim, &c->rel_max));
  c->L = 0.1; c->H = 0.02; c->A = 0.002; c->f = 3; c->ny = 6; c->nbase = 4;
  SimSolidMaterial(sim)->rho0 = 1000; SimSolidMaterial(sim)->K = 3.25e6; SimSolidMaterial(sim)->G = 7.15e5;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene shaken_plate: a cantilever whose clamp is shaken", "");
  PetscCall(OptReal("-plate_length", "Plate length outside the clamp (m)", "", c->L, &c->L, NULL));
  PetscCall(OptReal("-plate_thickness", "Plate thickness (m)", "", c->H, &c->H, NULL));
  PetscCall(OptInt("-plate_ny", "Particles across the thickness", "", c->ny, &c->ny, NULL));
  PetscCall(OptReal("-shake_amplitude", "A of the base's motion A (1 - cos 2 pi f t) (m)", "", c->A, &c->A, NULL));
  PetscCall(OptReal("-shake_frequency", "f of the base's motion (Hz)", "", c->f, &c->f, NULL));
  PetscOptionsEnd();
  PetscCheck(c->L > 0 && c->H > 0 && c->ny >= 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "Give a plate length and thickness > 0 and -plate_ny >= 3");
  PetscCheck(c->A >= 0 && c->f > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-shake_amplitude must be >= 0 and -shake_frequency > 0");
  PetscCall(SimSetSpacing(sim, c->H / c->ny));
  c->nx = RoundToInt(c->L / SimSpacing(sim));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 0.5 / c->f)); /* the base's rise to 2 A */
  PetscCall(SimSetMedia(sim, PETSC_FALSE, PETSC_TRUE)); /* a solid only: no fluid fields */
  PetscCall(SimSetGravity(sim, 0, 0, 0));
  reach = 0.5 * c->H + 2 * c->A + 0.2 * c->L; /* the plate's sweep, with room */
  PetscCall(SimSetDomain(sim, 0, -(c->nbase + 2) * SimSpacing(sim), 1.1 * c->L));
  PetscCall(SimSetDomain(sim, 1, -reach, reach));
  PetscCall(SimEnableField(sim, "x0")); /* the reference positions, for the displacements */
  c->rel_min = PETSC_MAX_REAL;
  c->rel_max = -PETSC_MAX_REAL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  ShakenPlate    *c  = (ShakenPlate *)SimSceneContext(sim);
  const PetscReal dx = SimSpacing(sim), y0 = -0.5 * c->H + 0.5 * dx, rho0 = SimSolidMaterial(sim)->rho0;
  PetscFunctionBeginUser;
  /* one block of solid: the base's columns at x < 0, then the free plate */
  PetscCall(SceneAddBlock(sim, KIND_SOLID, (PetscReal[]){-(c->nbase - 0.5) * dx, y0}, (PetscInt[]){c->nbase + c->nx, c->ny}, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The prescribed motion: the base's particles (x0 < 0) move with v = (0, A w sin w t). */
static PetscErrorCode Prescribe(Sim sim)
{
  ShakenPlate    *c = (ShakenPlate *)SimSceneContext(sim);
  const PetscReal w = 2 * PETSC_PI * c->f, vy = c->A * w * PetscSinReal(w * SimTime(sim));
  const PetscReal *x0;
  PetscReal       *v;
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "x0", NULL, &x0));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  for (PetscInt a = 0; a < n; a++)
    if (x0[2 * a] < 0) { v[2 * a] = 0; v[2 * a + 1] = vy; }
  PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* base_y: the base's mean displacement; base_exact: A (1 - cos w t); tip_rel: the last column's
 * mean displacement minus the base's (collective). */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  ShakenPlate     *c = (ShakenPlate *)SimSceneContext(sim);
  const PetscReal *x, *x0, w = 2 * PETSC_PI * c->f;
  PetscReal        s[4] = {0, 0, 0, 0}; /* base sum and count, tip sum and count */
  PetscInt         n;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "x0", NULL, &x0));
  for (PetscInt a = 0; a < n; a++) {
    if (x0[2 * a] < 0) { s[0] += x[2 * a + 1] - x0[2 * a + 1]; s[1] += 1; }
    if (x0[2 * a] > (c->nx - 1) * SimSpacing(sim)) { s[2] += x[2 * a + 1] - x0[2 * a + 1]; s[3] += 1; }
  }
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 4, MPIU_REAL, MPI_SUM, SimComm(sim)));
  vals[0] = s[0] / s[1];
  vals[1] = c->A * (1 - PetscCosReal(w * SimTime(sim)));
  vals[2] = s[2] / s[3] - vals[0];
  c->rel_min = PetscMin(c->rel_min, vals[2]);
  c->rel_max = PetscMax(c->rel_max, vals[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* summary.json: the tip's extremes relative to the base, over A */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  ShakenPlate *c = (ShakenPlate *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  if (f) fprintf(f, "\"tip_rel_min_over_A\": %.6g, \"tip_rel_max_over_A\": %.6g", (double)(c->rel_min / c->A), (double)(c->rel_max / c->A));
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

static const SceneOps ShakenPlateScene = {
  .name = "shaken_plate", .help = "a cantilever whose clamp is shaken (a scene of one's own)",
  .create = Create, .populate = Populate, .prescribe = Prescribe,
  .nprobes = 3, .probe_names = {"base_y", "base_exact", "tip_rel"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};

int main(int argc, char **argv)
{
  int status;
  if (SPHFSIInitialize(&argc, &argv, "shaken_plate: a scene of one's own on sphfsi\n", &status)) return status;
  PetscCall(SPHFSIRegisterScene(&ShakenPlateScene));
  PetscCall(SPHFSIRegisterBuiltinScenes()); /* optional: -case dam_break etc. work too */
  PetscCall(SPHFSIRun(&status));
  PetscCall(SPHFSIFinalize());
  return status;
}
