/* Open boundaries from the options (<sphfsi/scene.h>: SceneOpenBoundaryOptions): -inlet_K and
 * -outlet_K as buffer boxes, for -case boxes and any scene that wants them as data. */
#include "run/sim.h"

static const char *const Directions[] = {"+x", "-x", "+y", "-y", "+z", "-z", "Direction", "", NULL};

/* One boundary's box, direction and values: -PREFIX_K and its -PREFIX_K_* options */
static PetscErrorCode ReadOne(Sim sim, PetscOptionItems *PetscOptionsObject, OpenBoundaryKind kind, PetscInt k, OpenBoundarySpec *b, PetscBool *set)
{
  const char    *prefix = kind == OPEN_INLET ? "inlet" : "outlet";
  const char    *profiles[] = {"uniform", "parabolic", "table", "OpenProfile", "PROFILE_", NULL};
  const PetscInt D = sim->phys.dim;
  PetscReal      box[6], depth;
  PetscInt       n = 2 * D, dir = 0, prof = 0;
  char           name[48];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d", prefix, (int)k));
  PetscCall(PetscOptionsRealArray(name, kind == OPEN_INLET ? "An inlet: its buffer box x0,y0,x1,y1 (3D x0,y0,z0,x1,y1,z1), filled with water, its face toward the flow the inlet's plane" : "An outlet: its buffer box x0,y0,x1,y1 (3D x0,y0,z0,x1,y1,z1), filled with water, its face toward the flow the outlet's plane", "", box, &n, set));
  if (!*set) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(n == 2 * D, sim->comm, PETSC_ERR_USER_INPUT, "%s takes %d numbers, not %d", name, (int)(2 * D), (int)n);
  for (PetscInt d = 0; d < D; d++) PetscCheck(box[D + d] > box[d], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: its high corner must exceed its low corner in every direction", name);
  PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d_direction", prefix, (int)k));
  PetscCall(OptEList(name, kind == OPEN_INLET ? "The direction the water enters the domain in" : "The direction the water leaves the domain in", "", Directions, 2 * D, Directions[0], &dir, NULL));
  b->kind = kind;
  b->axis = dir / 2;
  /* an inlet feeding +axis has its buffer below its plane, an outlet of +axis flow above it */
  b->side  = (PetscInt)((dir % 2 == 0) == (kind == OPEN_INLET) ? -1 : 1);
  b->plane = b->side < 0 ? box[D + b->axis] : box[b->axis];
  depth    = box[D + b->axis] - box[b->axis];
  b->rows  = RoundToInt(depth / sim->phys.dx);
  PetscCheck(b->rows >= 1 && PetscAbsReal(b->rows * sim->phys.dx - depth) < 1e-6 * depth, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-%s_%d: the box's depth %g along the flow must be a whole number of spacings -dx %g", prefix, (int)k, (double)depth, (double)sim->phys.dx);
  for (PetscInt d = 0; d < D; d++) { b->lo[d] = box[d]; b->hi[d] = box[D + d]; }
  if (kind == OPEN_INLET) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-inlet_%d_velocity", (int)k));
    PetscCall(OptReal(name, "The inlet's mean speed into the domain (m/s)", "", b->velocity, &b->velocity, NULL));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-inlet_%d_profile", (int)k));
    PetscCall(OptEList(name, "The inlet's profile across its section: uniform, parabolic (zero at the section's edges) or table (-inlet_K_table)", "", profiles, 3, profiles[0], &prof, NULL));
    b->profile = (OpenProfile)prof;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-inlet_%d_table", (int)k));
    PetscCall(PetscOptionsString(name, "The inlet's profile: a file of lines \"s u\" (s the cross-section coordinate, m; u m/s)", "", b->table, b->table, sizeof(b->table), NULL));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-inlet_%d_ramp", (int)k));
    PetscCall(OptReal(name, "The inlet's speed grows as (1 - cos(pi t / T)) / 2 over this time T (s; 0: from the start)", "", b->ramp, &b->ramp, NULL));
  } else {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-outlet_%d_pressure", (int)k));
    PetscCall(OptReal(name, "The outlet's pressure (Pa)", "", b->pressure, &b->pressure, NULL));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneOpenBoundaryOptions(Sim sim, PetscOptionItems *PetscOptionsObject, OpenBoundarySpec spec[], PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = 0;
  for (PetscInt kind = OPEN_INLET; kind <= OPEN_OUTLET; kind++)
    for (PetscInt k = 1; k <= SCENE_MAX_OPEN; k++) {
      PetscBool set;
      PetscCall(PetscMemzero(&spec[*n], sizeof(spec[*n])));
      PetscCall(ReadOne(sim, PetscOptionsObject, (OpenBoundaryKind)kind, k, &spec[*n], &set));
      if (!set) continue;
      PetscCheck(*n < SCENE_MAX_OPEN, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "At most %d open boundaries (inlets and outlets together)", SCENE_MAX_OPEN);
      (*n)++;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}
