/* A case without C: the geometry is data in the options file (-case boxes).  Water in boxes, a tank
 * (floor and side walls of -wall_rows rows), obstacles as boxes of wall particles, and probes: level
 * gauges, pressure gauges, the front and the largest speed.  Primitives, in the order their particles
 * are made (the same helpers as the built-in scenes, so that a file that describes a built-in scene
 * reproduces it bit for bit):
 *   -fluid_box_K x0,y0,x1,y1   K = 1..8: water at rest (hydrostatic density below the box's top)
 *   -tank x0,x1,y0,y1          floor at y0 from x0 to x1, side walls from y0 up to y1
 *   -tank_sides both|left|right|none
 *   -wall_box_K x0,y0,x1,y1    K = 1..8: a solid obstacle of wall particles (its outer row faces the
 *                              water, the inner rows are dummies)
 *   -domain x0,y0,x1,y1        the computational box (particles leaving it are a fault); default:
 *                              the tank and its walls, open to twice the walls' height
 *   -gauge_level_K x           K = 1..4: water level at x (highest water particle within 1.5 dx, + dx/2)
 *   -gauge_pressure_K x,y      K = 1..4: pressure at a point (Shepard sum, carried hydrostatically)
 * Probes also give front_x (the water's right-most extent) and v_max.  No reference: summary.json's
 * errors are empty. */
#include <sphfsi/scene.h>

#define BOXES_MAX 8
#define GAUGES_MAX 4

typedef struct {
  PetscInt  nfluid, nwall, nlevel, npress, rows;
  PetscReal fluid[BOXES_MAX][4], wall[BOXES_MAX][4], tank[4], level[GAUGES_MAX], press[GAUGES_MAX][2];
  PetscBool has_tank, left, right;
  char      names[2 + 2 * GAUGES_MAX][32];
} Boxes;

extern SceneOps SceneBoxes; /* not const: Create fills in its probe names */

/* A box x0,y0,x1,y1 read by PetscOptionsRealArray (n numbers): 4 of them, and x1 > x0, y1 > y0. */
static PetscErrorCode CheckBox(Sim sim, const char *name, const PetscReal b[4], PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCheck(n == 4, sim->comm, PETSC_ERR_USER_INPUT, "%s takes 4 numbers x0,y0,x1,y1, not %d", name, (int)n);
  PetscCheck(b[2] > b[0] && b[3] > b[1], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g: x1 must exceed x0 and y1 y0", name, (double)b[0], (double)b[1], (double)b[2], (double)b[3]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool Overlap(const PetscReal a[4], const PetscReal b[4]) { return (PetscBool)(a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]); }

static PetscErrorCode Create(Sim sim)
{
  Boxes      *c;
  const char *sides[] = {"both", "left", "right", "none", "BoxesSides", "", NULL};
  PetscInt    side = 0, n;
  PetscReal   dom[4] = {0, 0, 0, 0}, top = -PETSC_MAX_REAL, floor = PETSC_MAX_REAL;
  PetscBool   set, dom_set;
  char        name[32];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  sim->scene_ctx = c;
  c->rows        = KernelSupportRows(&sim->kernel);
  PetscOptionsBegin(sim->comm, NULL, "Scene boxes: water, tank and obstacles as boxes given in the options", "");
  for (PetscInt k = 1; k <= BOXES_MAX; k++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-fluid_box_%d", (int)k));
    n = 4;
    PetscCall(PetscOptionsRealArray(name, "Water at rest in the box x0,y0,x1,y1 (m)", "", c->fluid[c->nfluid], &n, &set));
    if (set) PetscCall(CheckBox(sim, name, c->fluid[c->nfluid++], n));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-wall_box_%d", (int)k));
    n = 4;
    PetscCall(PetscOptionsRealArray(name, "An obstacle of wall particles filling the box x0,y0,x1,y1 (m)", "", c->wall[c->nwall], &n, &set));
    if (set) PetscCall(CheckBox(sim, name, c->wall[c->nwall++], n));
  }
  n = 4;
  PetscCall(PetscOptionsRealArray("-tank", "Tank x0,x1,y0,y1: floor at y0 from x0 to x1, side walls up to y1 (m)", "", c->tank, &n, &c->has_tank));
  PetscCheck(!c->has_tank || (n == 4 && c->tank[1] > c->tank[0] && c->tank[3] > c->tank[2]), sim->comm, PETSC_ERR_USER_INPUT, "-tank takes x0,x1,y0,y1 with x1 > x0 and y1 > y0");
  PetscCall(PetscOptionsEList("-tank_sides", "Side walls of the tank", "", sides, 4, sides[0], &side, NULL));
  PetscCall(PetscOptionsInt("-wall_rows", "Rows of wall + dummy particles of the tank", "", c->rows, &c->rows, NULL));
  n = 4;
  PetscCall(PetscOptionsRealArray("-domain", "Computational box x0,y0,x1,y1 (m); default: the tank with its walls, open to twice its height", "", dom, &n, &dom_set));
  PetscCheck(!dom_set || (n == 4 && dom[2] > dom[0] && dom[3] > dom[1]), sim->comm, PETSC_ERR_USER_INPUT, "-domain takes x0,y0,x1,y1 with x1 > x0 and y1 > y0");
  for (PetscInt k = 1; k <= GAUGES_MAX; k++) {
    PetscInt two = 2;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_level_%d", (int)k));
    PetscCall(PetscOptionsReal(name, "Water level gauge at this x (m)", "", 0, &c->level[c->nlevel], &set));
    c->nlevel += set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_pressure_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Pressure gauge at x,y (m)", "", c->press[c->npress], &two, &set));
    PetscCheck(!set || two == 2, sim->comm, PETSC_ERR_USER_INPUT, "%s takes 2 numbers x,y", name);
    c->npress += set;
  }
  PetscOptionsEnd();
  c->left  = (PetscBool)(side == 0 || side == 1);
  c->right = (PetscBool)(side == 0 || side == 2);
  PetscCheck(c->nfluid > 0, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes has no water: give -fluid_box_1 x0,y0,x1,y1");
  PetscCheck(c->rows >= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", c->rows);
  PetscCheck(sim->dx > 0, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes needs -dx (the particle spacing, m)");
  if (sim->t_end < 0) sim->t_end = 1.0;
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const PetscReal *b = c->fluid[i];
    PetscCheck(b[2] - b[0] >= sim->dx && b[3] - b[1] >= sim->dx, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_box_%d is thinner than -dx %g: choose a smaller -dx", (int)i + 1, (double)sim->dx);
    for (PetscInt j = 0; j < c->nwall; j++) PetscCheck(!Overlap(b, c->wall[j]), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -wall_box_%d: water and wall cannot share space", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < i; j++) PetscCheck(!Overlap(b, c->fluid[j]), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -fluid_box_%d", (int)i + 1, (int)j + 1);
    if (c->has_tank) PetscCheck(b[0] >= c->tank[0] - 1e-12 && b[2] <= c->tank[1] + 1e-12 && b[1] >= c->tank[2] - 1e-12, sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d %g,%g,%g,%g is not inside the -tank %g,%g,%g,%g (water would sit in its walls)", (int)i + 1, (double)b[0], (double)b[1], (double)b[2], (double)b[3], (double)c->tank[0], (double)c->tank[1], (double)c->tank[2], (double)c->tank[3]);
    top   = PetscMax(top, b[3]);
    floor = PetscMin(floor, b[1]);
  }
  if (dom_set) {
    sim->dom_lo[0] = dom[0]; sim->dom_lo[1] = dom[1];
    sim->dom_hi[0] = dom[2]; sim->dom_hi[1] = dom[3];
  } else {
    PetscCheck(c->has_tank, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes without -tank needs -domain x0,y0,x1,y1");
    sim->dom_lo[0] = c->tank[0] - (c->rows + 0.5) * sim->dx;
    sim->dom_hi[0] = c->tank[1] + (c->rows + 0.5) * sim->dx;
    sim->dom_lo[1] = c->tank[2] - (c->rows + 0.5) * sim->dx;
    sim->dom_hi[1] = c->tank[2] + 2 * (c->tank[3] - c->tank[2]);
  }
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const PetscReal *b = c->fluid[i];
    PetscCheck(b[0] >= sim->dom_lo[0] && b[2] <= sim->dom_hi[0] && b[1] >= sim->dom_lo[1] && b[3] <= sim->dom_hi[1], sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d reaches outside the -domain", (int)i + 1);
  }
  for (PetscInt k = 0; k < c->nlevel; k++) PetscCheck(c->level[k] > sim->dom_lo[0] && c->level[k] < sim->dom_hi[0], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gauge_level_%d %g is outside the domain [%g, %g]", (int)k + 1, (double)c->level[k], (double)sim->dom_lo[0], (double)sim->dom_hi[0]);
  for (PetscInt k = 0; k < c->npress; k++) PetscCheck(c->press[k][0] > sim->dom_lo[0] && c->press[k][0] < sim->dom_hi[0] && c->press[k][1] > sim->dom_lo[1] && c->press[k][1] < sim->dom_hi[1], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gauge_pressure_%d %g,%g is outside the domain", (int)k + 1, (double)c->press[k][0], (double)c->press[k][1]);
  /* c0 = 10 x the speed of a fall from the highest water surface to the lowest water */
  sim->v_ref = PetscSqrtReal(2 * PetscSqrtReal(sim->g[0] * sim->g[0] + sim->g[1] * sim->g[1]) * (top - floor));
  /* probes: front_x, v_max, then the gauges */
  SceneBoxes.nprobes        = 2 + c->nlevel + c->npress;
  SceneBoxes.probe_names[0] = "front_x";
  SceneBoxes.probe_names[1] = "v_max";
  for (PetscInt k = 0; k < c->nlevel; k++) {
    PetscCall(PetscSNPrintf(c->names[k], sizeof(c->names[k]), "level_%d", (int)k + 1));
    SceneBoxes.probe_names[2 + k] = c->names[k];
  }
  for (PetscInt k = 0; k < c->npress; k++) {
    PetscCall(PetscSNPrintf(c->names[c->nlevel + k], sizeof(c->names[0]), "pressure_%d", (int)k + 1));
    SceneBoxes.probe_names[2 + c->nlevel + k] = c->names[c->nlevel + k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A box of wall particles: the particles within dx of its edges are walls (they face the water), the
 * inner ones dummies. */
static PetscErrorCode AddWallBox(Sim sim, const PetscReal b[4])
{
  const PetscReal dx = sim->dx;
  const PetscInt  nx = RoundToInt((b[2] - b[0]) / dx), ny = RoundToInt((b[3] - b[1]) / dx);
  PetscInt        first = sim->P->n;
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_WALL, b[0] + 0.5 * dx, b[1] + 0.5 * dx, nx, ny, dx, sim->fl.rho0));
  for (PetscInt a = first; a < sim->P->n; a++) { /* this rank's share of the lattice */
    const PetscReal *x = PField(sim->P, FIELD_X) + 2 * a;
    if (x[0] > b[0] + dx && x[0] < b[2] - dx && x[1] > b[1] + dx && x[1] < b[3] - dx) sim->P->kind[a] = KIND_DUMMY;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Boxes          *c  = (Boxes *)sim->scene_ctx;
  const PetscReal dx = sim->dx;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const PetscReal *b     = c->fluid[i];
    PetscInt         first = sim->P->n, nx = RoundToInt((b[2] - b[0]) / dx), ny = RoundToInt((b[3] - b[1]) / dx);
    PetscReal       *x, *rho, *p;
    PetscCall(SceneAddLattice(sim, KIND_FLUID, b[0] + 0.5 * dx, b[1] + 0.5 * dx, nx, ny, dx, sim->fl.rho0));
    x = PField(sim->P, FIELD_X); rho = PField(sim->P, FIELD_RHO); p = PField(sim->P, FIELD_P);
    for (PetscInt a = first; a < sim->P->n; a++) { /* at rest: hydrostatic below the lattice's top (Eq. 20) */
      p[a]   = sim->fl.rho0 * (-sim->g[1]) * (b[1] + ny * dx - x[2 * a + 1]);
      rho[a] = EOSDensity(&sim->fl, p[a]);
    }
  }
  if (c->has_tank) PetscCall(SceneAddTank(sim, c->tank[0], c->tank[1], c->tank[2], c->tank[3], dx, c->rows, c->left, c->right));
  for (PetscInt i = 0; i < c->nwall; i++) PetscCall(AddWallBox(sim, c->wall[i]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Boxes     *c = (Boxes *)sim->scene_ctx;
  Particles  P = sim->P;
  PetscReal *x = PField(P, FIELD_X), m[1 + GAUGES_MAX];
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k <= c->nlevel; k++) m[k] = -PETSC_MAX_REAL;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    m[0] = PetscMax(m[0], x[2 * a]);
    for (PetscInt k = 0; k < c->nlevel; k++)
      if (PetscAbsReal(x[2 * a] - c->level[k]) < 1.5 * sim->dx) m[1 + k] = PetscMax(m[1 + k], x[2 * a + 1]);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 1 + c->nlevel, MPIU_REAL, MPIU_MAX, sim->comm));
  vals[0] = m[0] + 0.5 * sim->dx;
  PetscCall(SceneMaxSpeed(sim, &vals[1]));
  for (PetscInt k = 0; k < c->nlevel; k++) vals[2 + k] = m[1 + k] > -PETSC_MAX_REAL ? m[1 + k] + 0.5 * sim->dx : 0; /* 0: no water there */
  for (PetscInt k = 0; k < c->npress; k++) PetscCall(SceneProbePressure(sim, c->press[k], &vals[2 + c->nlevel + k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(sim->scene_ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

SceneOps SceneBoxes = {
  .name = "boxes", .help = "a case given as data: water, tank and obstacles as boxes in the options file",
  .create = Create, .populate = Populate,
  .probe = Probe, .destroy = Destroy,
};
