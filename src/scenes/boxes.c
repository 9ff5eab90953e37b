/* A case without C (-case boxes): the geometry is data in the options file.  Primitives, made in
 * this order with the helpers of the built-in scenes (so that a file that describes a built-in scene
 * gives the same particles with the same ids, and the same run):
 *   -fluid_box_K x0,y0,x1,y1[,s]       K = 1..8: water at rest on a lattice of spacing s (default
 *                                      -dx), hydrostatic below the lattice's top
 *   -tank_K x0,x1,y0,y1[,s[,rows]]     K = 1..4: floor at y0 from x0 to x1, side walls up to y1
 *   -tank_K_sides both|left|right|none   -wall_rows N: the rows of a tank that gives none
 *   -solid_box_K, -clamp_box_K         K = 1..8: elastic solid (-solid_rho, -solid_K, -solid_G) and
 *                                      its rigid clamp, at -dx; a solid must touch a clamp
 *   -wall_box_K x0,y0,x1,y1            K = 1..8: an obstacle of wall particles at -dx; its rows
 *   -wall_box_K_faces left,right,...   within dx of the faces given (default all) are walls, the
 *                                      others dummies
 *   -outflow                           water leaving the domain is removed
 *   -domain x0,y0,x1,y1                the computational box (default: the tanks with their walls,
 *                                      open to twice the walls' height)
 *   -gauge_level_K x, -gauge_pressure_K x,y, -gauge_solid_K x0,y0,x1,y1    K = 1..4: probes
 * Probes: front_x, v_max, then level_K, pressure_K, solid_dx_K / solid_dy_K (the mean displacement
 * of the solid particles whose reference position is in the box).  No reference: summary.json's
 * errors are empty.  docs/options.md lists the options with their checks. */
#include <sphfsi/scene.h>
#include <sphfsi/options_used.h>

#define NBOX 8
#define NTANK 4
#define NGAUGE 4

typedef struct {
  PetscReal b[4], s; /* box; lattice spacing (tanks: walls' spacing) */
  PetscInt  rows;    /* tanks: wall rows */
  PetscBool left, right, face[4];
} Box;

typedef struct {
  Box       fluid[NBOX], tank[NTANK], solid[NBOX], clamp[NBOX], wall[NBOX];
  PetscInt  nfluid, ntank, nsolid, nclamp, nwall, nlevel, npress, nsgauge;
  PetscReal level[NGAUGE], press[NGAUGE][2], sgauge[NGAUGE][4];
  char      names[SCENE_MAX_PROBES][32];
} Boxes;

extern SceneOps SceneBoxes; /* not const: Create fills in its probe names */

/* n numbers read into b: 4 (or up to nmax) and a box with x1 > x0, y1 > y0 (x0,y0,x1,y1 order). */
static PetscErrorCode CheckBox(Sim sim, const char *name, const PetscReal b[4], PetscInt n, PetscInt nmax)
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 4 && n <= nmax, sim->comm, PETSC_ERR_USER_INPUT, "%s takes %s numbers, not %d", name, nmax == 4 ? "4" : nmax == 5 ? "4 or 5" : "4 to 6", (int)n);
  PetscCheck(b[2] > b[0] && b[3] > b[1], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g: x1 must exceed x0 and y1 y0", name, (double)b[0], (double)b[1], (double)b[2], (double)b[3]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool Overlap(const PetscReal a[4], const PetscReal b[4]) { return (PetscBool)(a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]); }
static PetscBool Touch(const PetscReal a[4], const PetscReal b[4], PetscReal eps) { return (PetscBool)(a[0] <= b[2] + eps && b[0] <= a[2] + eps && a[1] <= b[3] + eps && b[1] <= a[3] + eps); }

/* The rectangles a tank's particles fill: floor (with the corners) and side walls. */
static PetscInt TankWalls(const Box *t, PetscReal r[3][4])
{
  const PetscReal d = t->rows * t->s;
  PetscInt        n = 0;
  r[n][0] = t->b[0] - (t->left ? d : 0); r[n][1] = t->b[1] - d; r[n][2] = t->b[2] + (t->right ? d : 0); r[n][3] = t->b[1]; n++;
  if (t->left) { r[n][0] = t->b[0] - d; r[n][1] = t->b[1]; r[n][2] = t->b[0]; r[n][3] = t->b[3]; n++; }
  if (t->right) { r[n][0] = t->b[2]; r[n][1] = t->b[1]; r[n][2] = t->b[2] + d; r[n][3] = t->b[3]; n++; }
  return n;
}

/* Boxes K = 1..NBOX of one kind (-PREFIX_K); with spacing: a 5th number, the lattice's spacing; with
 * faces: -PREFIX_K_faces, the faces that meet water (default all). */
static PetscErrorCode ReadBoxes(Sim sim, PetscOptionItems *PetscOptionsObject, const char *prefix, const char *text, Box *list, PetscInt *count, PetscBool spacing, PetscBool faces)
{
  char name[40];
  PetscFunctionBeginUser;
  for (PetscInt k = 1; k <= NBOX; k++) {
    PetscReal v[5];
    PetscInt  n = spacing ? 5 : 4;
    PetscBool set;
    Box      *B;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d", prefix, (int)k));
    PetscCall(PetscOptionsRealArray(name, text, "", v, &n, &set));
    if (!set) continue;
    PetscCall(CheckBox(sim, name, v, n, spacing ? 5 : 4));
    B = &list[(*count)++];
    for (PetscInt i = 0; i < 4; i++) B->b[i] = v[i];
    B->s = n == 5 ? v[4] : sim->dx;
    PetscCheck(B->s > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the spacing %g must be > 0", name, (double)B->s);
    for (PetscInt i = 0; i < 4; i++) B->face[i] = PETSC_TRUE;
    if (faces) {
      char list[64] = "";
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d_faces", prefix, (int)k));
      PetscCall(PetscOptionsString(name, "Faces of the obstacle that meet water: left,right,bottom,top (their outer row is wall, the rest dummies)", "", list, list, sizeof(list), &set));
      if (set) {
        const char *fn[4] = {"left", "bottom", "right", "top"};
        for (PetscInt i = 0; i < 4; i++) B->face[i] = (PetscBool)(strstr(list, fn[i]) != NULL);
      }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The next probe column's name: "base" or "base_k" (k > 0); at most SCENE_MAX_PROBES are kept. */
static PetscErrorCode ProbeName(Boxes *c, PetscInt *n, const char *base, PetscInt k)
{
  PetscFunctionBeginUser;
  if (*n < SCENE_MAX_PROBES) {
    if (k) PetscCall(PetscSNPrintf(c->names[*n], sizeof(c->names[0]), "%s_%d", base, (int)k));
    else PetscCall(PetscStrncpy(c->names[*n], base, sizeof(c->names[0])));
    SceneBoxes.probe_names[*n] = c->names[*n];
  }
  (*n)++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Create(Sim sim)
{
  Boxes      *c;
  const char *sides[] = {"both", "left", "right", "none", "TankSides", "", NULL};
  PetscReal   dom[4] = {0, 0, 0, 0}, top = -PETSC_MAX_REAL, low = PETSC_MAX_REAL;
  PetscInt    n, rows;
  PetscBool   set, dom_set;
  char        name[40];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  sim->scene_ctx = c;
  PetscCheck(sim->dx > 0, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes needs -dx (the particle spacing, m)");
  PetscOptionsBegin(sim->comm, NULL, "Scene boxes: water, tanks, obstacles and solids as boxes given in the options", "");
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "fluid_box", "Water at rest x0,y0,x1,y1[,spacing] (m)", c->fluid, &c->nfluid, PETSC_TRUE, PETSC_FALSE));
  rows = KernelSupportRows(&sim->kernel);
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles of a tank that does not give its own", "", rows, &rows, NULL));
  PetscCheck(rows >= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", rows);
  for (PetscInt k = 1; k <= NTANK; k++) {
    PetscReal v[6];
    PetscInt  side = 0;
    Box      *T;
    n = 6;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-tank_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Tank x0,x1,y0,y1[,spacing[,rows]]: floor at y0 from x0 to x1, side walls up to y1 (m)", "", v, &n, &set));
    if (!set) continue;
    T = &c->tank[c->ntank++];
    PetscCheck(n >= 4 && n <= 6, sim->comm, PETSC_ERR_USER_INPUT, "%s takes x0,x1,y0,y1[,spacing[,rows]], not %d numbers", name, (int)n);
    T->b[0] = v[0]; T->b[1] = v[2]; T->b[2] = v[1]; T->b[3] = v[3];
    PetscCall(CheckBox(sim, name, T->b, 4, 4));
    T->s    = n >= 5 ? v[4] : sim->dx;
    T->rows = n >= 6 ? (PetscInt)v[5] : rows;
    PetscCheck(T->s > 0 && T->rows >= 1 && (n < 6 || v[5] == (PetscReal)T->rows), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the spacing must be > 0 and the rows a whole number >= 1", name);
    PetscCall(PetscSNPrintf(name, sizeof(name), "-tank_%d_sides", (int)k));
    PetscCall(OptEList(name, "Side walls of the tank", "", sides, 4, sides[0], &side, NULL));
    T->left  = (PetscBool)(side == 0 || side == 1);
    T->right = (PetscBool)(side == 0 || side == 2);
  }
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "solid_box", "Elastic solid x0,y0,x1,y1 (m), at -dx", c->solid, &c->nsolid, PETSC_FALSE, PETSC_FALSE));
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "clamp_box", "Rigid clamp of a solid x0,y0,x1,y1 (m), at -dx", c->clamp, &c->nclamp, PETSC_FALSE, PETSC_FALSE));
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "wall_box", "Obstacle of wall particles x0,y0,x1,y1 (m), at -dx", c->wall, &c->nwall, PETSC_FALSE, PETSC_TRUE));
  PetscCall(OptBool("-outflow", "Water that leaves the domain is removed (an open boundary)", "", sim->outflow, &sim->outflow, NULL));
  n = 4;
  PetscCall(PetscOptionsRealArray("-domain", "Computational box x0,y0,x1,y1 (m); default: the tanks with their walls, open to twice their height", "", dom, &n, &dom_set));
  if (dom_set) PetscCall(CheckBox(sim, "-domain", dom, n, 4));
  for (PetscInt k = 1; k <= NGAUGE; k++) {
    PetscInt two = 2, four = 4;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_level_%d", (int)k));
    PetscCall(OptReal(name, "Water level gauge at this x (m)", "", 0, &c->level[c->nlevel], &set));
    c->nlevel += set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_pressure_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Pressure gauge at x,y (m)", "", c->press[c->npress], &two, &set));
    PetscCheck(!set || two == 2, sim->comm, PETSC_ERR_USER_INPUT, "%s takes 2 numbers x,y", name);
    c->npress += set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_solid_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Mean displacement of the solid particles whose reference position is in x0,y0,x1,y1 (m)", "", c->sgauge[c->nsgauge], &four, &set));
    if (set) PetscCall(CheckBox(sim, name, c->sgauge[c->nsgauge++], four, 4));
  }
  PetscOptionsEnd();
  PetscCheck(c->nfluid > 0 || c->nsolid > 0, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes has no water and no solid: give -fluid_box_1 x0,y0,x1,y1");
  if (sim->t_end < 0) sim->t_end = 1.0;
  sim->has_fluid = (PetscBool)(c->nfluid > 0);
  sim->has_solid = (PetscBool)(c->nsolid > 0);
  for (PetscInt i = 0; i < c->nsolid; i++) {
    PetscBool held = PETSC_FALSE;
    for (PetscInt j = 0; j < c->nclamp; j++) held = (PetscBool)(held || Touch(c->solid[i].b, c->clamp[j].b, 1e-9 * sim->dx));
    PetscCheck(held, sim->comm, PETSC_ERR_ARG_INCOMP, "-solid_box_%d touches no -clamp_box: a free solid is not supported; clamp it (a -clamp_box_K sharing an edge with it)", (int)i + 1);
  }
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const Box *F = &c->fluid[i];
    PetscCheck(F->b[2] - F->b[0] >= F->s && F->b[3] - F->b[1] >= F->s, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_box_%d is thinner than its spacing %g: choose a smaller spacing", (int)i + 1, (double)F->s);
    for (PetscInt j = 0; j < i; j++) PetscCheck(!Overlap(F->b, c->fluid[j].b), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -fluid_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nwall; j++) PetscCheck(!Overlap(F->b, c->wall[j].b), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -wall_box_%d: water and wall cannot share space", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nsolid; j++) PetscCheck(!Overlap(F->b, c->solid[j].b), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -solid_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nclamp; j++) PetscCheck(!Overlap(F->b, c->clamp[j].b), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -clamp_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->ntank; j++) {
      PetscReal r[3][4];
      PetscInt  nr = TankWalls(&c->tank[j], r);
      for (PetscInt q = 0; q < nr; q++) PetscCheck(!Overlap(F->b, r[q]), sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps the walls of -tank_%d: water and wall cannot share space", (int)i + 1, (int)j + 1);
    }
    top = PetscMax(top, F->b[3]);
    low = PetscMin(low, F->b[1]);
  }
  if (dom_set) {
    sim->dom_lo[0] = dom[0]; sim->dom_lo[1] = dom[1];
    sim->dom_hi[0] = dom[2]; sim->dom_hi[1] = dom[3];
  } else {
    PetscCheck(c->ntank > 0, sim->comm, PETSC_ERR_USER_INPUT, "Scene boxes without a -tank_1 needs -domain x0,y0,x1,y1");
    sim->dom_lo[0] = sim->dom_lo[1] = PETSC_MAX_REAL;
    sim->dom_hi[0] = sim->dom_hi[1] = -PETSC_MAX_REAL;
    for (PetscInt j = 0; j < c->ntank; j++) {
      const Box *T = &c->tank[j];
      const PetscReal d = (T->rows + 0.5) * T->s;
      sim->dom_lo[0] = PetscMin(sim->dom_lo[0], T->b[0] - d);
      sim->dom_hi[0] = PetscMax(sim->dom_hi[0], T->b[2] + d);
      sim->dom_lo[1] = PetscMin(sim->dom_lo[1], T->b[1] - d);
      sim->dom_hi[1] = PetscMax(sim->dom_hi[1], T->b[1] + 2 * (T->b[3] - T->b[1]));
    }
  }
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const PetscReal *b = c->fluid[i].b;
    PetscCheck(b[0] >= sim->dom_lo[0] && b[2] <= sim->dom_hi[0] && b[1] >= sim->dom_lo[1] && b[3] <= sim->dom_hi[1], sim->comm, PETSC_ERR_ARG_INCOMP, "-fluid_box_%d reaches outside the domain [%g, %g] x [%g, %g]", (int)i + 1, (double)sim->dom_lo[0], (double)sim->dom_hi[0], (double)sim->dom_lo[1], (double)sim->dom_hi[1]);
  }
  for (PetscInt k = 0; k < c->nlevel; k++) PetscCheck(c->level[k] > sim->dom_lo[0] && c->level[k] < sim->dom_hi[0], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gauge_level_%d %g is outside the domain [%g, %g]", (int)k + 1, (double)c->level[k], (double)sim->dom_lo[0], (double)sim->dom_hi[0]);
  for (PetscInt k = 0; k < c->npress; k++) PetscCheck(c->press[k][0] > sim->dom_lo[0] && c->press[k][0] < sim->dom_hi[0] && c->press[k][1] > sim->dom_lo[1] && c->press[k][1] < sim->dom_hi[1], sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gauge_pressure_%d %g,%g is outside the domain", (int)k + 1, (double)c->press[k][0], (double)c->press[k][1]);
  PetscCheck(!c->nsgauge || c->nsolid, sim->comm, PETSC_ERR_ARG_INCOMP, "-gauge_solid_1 needs a -solid_box_1");
  /* c0 = 10 x the speed of a fall from the highest water surface to the lowest water */
  if (sim->has_fluid) sim->v_ref = PetscSqrtReal(2 * PetscSqrtReal(sim->g[0] * sim->g[0] + sim->g[1] * sim->g[1]) * (top - low));
  /* probes: front_x, v_max, then the gauges */
  n = 0;
  PetscCall(ProbeName(c, &n, "front_x", 0));
  PetscCall(ProbeName(c, &n, "v_max", 0));
  for (PetscInt k = 1; k <= c->nlevel; k++) PetscCall(ProbeName(c, &n, "level", k));
  for (PetscInt k = 1; k <= c->npress; k++) PetscCall(ProbeName(c, &n, "pressure", k));
  for (PetscInt k = 1; k <= c->nsgauge; k++) {
    PetscCall(ProbeName(c, &n, "solid_dx", k));
    PetscCall(ProbeName(c, &n, "solid_dy", k));
  }
  PetscCheck(n <= SCENE_MAX_PROBES, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "Scene boxes has %d probe columns (front_x, v_max and the gauges; a solid gauge counts 2): at most %d", (int)n, SCENE_MAX_PROBES);
  SceneBoxes.nprobes = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Boxes *c = (Boxes *)sim->scene_ctx;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->nfluid; i++) { /* at rest: hydrostatic below the lattice's top */
    const Box *F     = &c->fluid[i];
    PetscInt   first = sim->P->n;
    PetscCall(SceneAddBox(sim, KIND_FLUID, F->b, F->s, sim->fl.rho0));
    PetscCall(SceneHydrostaticDensity(sim, first, F->b[1] + RoundToInt((F->b[3] - F->b[1]) / F->s) * F->s));
  }
  for (PetscInt i = 0; i < c->ntank; i++) {
    const Box *T = &c->tank[i];
    PetscCall(SceneAddTank(sim, T->b[0], T->b[2], T->b[1], T->b[3], T->s, T->rows, T->left, T->right));
  }
  for (PetscInt i = 0; i < c->nsolid; i++) PetscCall(SceneAddBox(sim, KIND_SOLID, c->solid[i].b, sim->dx, sim->sl.rho0));
  for (PetscInt i = 0; i < c->nclamp; i++) PetscCall(SceneAddBox(sim, KIND_CLAMP, c->clamp[i].b, sim->dx, sim->sl.rho0));
  for (PetscInt i = 0; i < c->nwall; i++) PetscCall(SceneAddWallBox(sim, c->wall[i].b, sim->dx, c->wall[i].face));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Boxes     *c = (Boxes *)sim->scene_ctx;
  Particles  P = sim->P;
  PetscReal *x = PField(P, FIELD_X), *x0 = P->f[FIELD_X0].on ? PField(P, FIELD_X0) : NULL, m[1 + NGAUGE], s[3 * NGAUGE];
  PetscInt   n = 2;
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k <= c->nlevel; k++) m[k] = -PETSC_MAX_REAL;
  for (PetscInt k = 0; k < 3 * c->nsgauge; k++) s[k] = 0;
  for (PetscInt a = 0; a < P->n; a++) {
    if (KindIsFluid(P->kind[a])) {
      m[0] = PetscMax(m[0], x[2 * a]);
      for (PetscInt k = 0; k < c->nlevel; k++)
        if (PetscAbsReal(x[2 * a] - c->level[k]) < 1.5 * sim->dx) m[1 + k] = PetscMax(m[1 + k], x[2 * a + 1]);
    } else if (P->kind[a] == KIND_SOLID && x0)
      for (PetscInt k = 0; k < c->nsgauge; k++) {
        const PetscReal *g = c->sgauge[k];
        if (x0[2 * a] < g[0] || x0[2 * a] > g[2] || x0[2 * a + 1] < g[1] || x0[2 * a + 1] > g[3]) continue;
        s[3 * k] += x[2 * a] - x0[2 * a];
        s[3 * k + 1] += x[2 * a + 1] - x0[2 * a + 1];
        s[3 * k + 2] += 1;
      }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 1 + c->nlevel, MPIU_REAL, MPIU_MAX, sim->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 3 * c->nsgauge, MPIU_REAL, MPIU_SUM, sim->comm));
  vals[0] = m[0] > -PETSC_MAX_REAL ? m[0] + 0.5 * sim->dx : 0;
  PetscCall(SceneMaxSpeed(sim, &vals[1]));
  for (PetscInt k = 0; k < c->nlevel; k++) vals[n++] = m[1 + k] > -PETSC_MAX_REAL ? m[1 + k] + 0.5 * sim->dx : 0; /* 0: no water there */
  for (PetscInt k = 0; k < c->npress; k++) PetscCall(SceneProbePressure(sim, c->press[k], &vals[n++]));
  for (PetscInt k = 0; k < c->nsgauge; k++) {
    vals[n++] = s[3 * k + 2] > 0 ? s[3 * k] / s[3 * k + 2] : 0;
    vals[n++] = s[3 * k + 2] > 0 ? s[3 * k + 1] / s[3 * k + 2] : 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(sim->scene_ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

SceneOps SceneBoxes = {
  .name = "boxes", .help = "a case given as data: water, tanks, obstacles and solids as boxes in the options file",
  .create = Create, .populate = Populate,
  .probe = Probe, .destroy = Destroy,
};
