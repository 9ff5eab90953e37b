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
 *   -wall_box_K_body N                 the body (1..4) whose force -body_force gives; 0: none (a
 *                                      channel's walls; also -wall_box_K_measured 0); likewise
 *                                      -solid_box_K_body, -clamp_box_K_body and a shape's _body
 *   -outflow                           water leaving the domain is removed
 *   -domain x0,y0,x1,y1                the computational box (default: the tanks with their walls,
 *                                      open to twice the walls' height)
 *   -gauge_level_K x, -gauge_pressure_K x,y, -gauge_solid_K x0,y0,x1,y1    K = 1..4: probes
 * Probes: front_x, v_max, then level_K, pressure_K, solid_dx_K / solid_dy_K (the mean displacement
 * of the solid particles whose reference position is in the box); with -body_force, force_x, force_y
 * of body 1 and force_x_N, force_y_N of each further body N.  No reference: summary.json's
 * errors are empty.  docs/options.md lists the options with their checks.
 * -dim 3: the same primitives in 3D (z up): a box is x0,y0,z0,x1,y1,z1[,s]; a tank
 * x0,x1,y0,y1,z0,z1[,s[,rows]] has its floor at z0 and walls on all four sides up to z1; obstacle
 * faces left,right,front,back,bottom,top (x-, x+, y-, y+, z-, z+); -domain six numbers; a level
 * gauge x,y; a pressure gauge x,y,z; a solid gauge x0,y0,z0,x1,y1,z1 (probes solid_dx, _dy, _dz).
 * Inlets and outlets (docs/open_boundaries.md): -inlet_K, -outlet_K buffer boxes (SceneOpenBoundaryOptions).
 * Shapes (<sphfsi/shapes.h>, docs/geometry.md): -cylinder_K x,y,r (3D -sphere_K x,y,z,r), -polygon_K
 * x0,y0,x1,y1,... (2D), each -..._kind wall|fluid|solid|clamp, made after the wall boxes; water of
 * the boxes is cut where an obstacle, solid or clamp shape is.  -periodic x[,y[,z]] with -domain;
 * -confined (no free surface; default when every direction is periodic); -flow_probe. */
#include <sphfsi.h>

#define NBOX 8
#define NTANK 4
#define NGAUGE 4

typedef struct {
  PetscReal b[6], s; /* box: its low corner, then its high corner (2D x0,y0,x1,y1); lattice spacing (tanks: walls' spacing) */
  PetscInt  rows;    /* tanks: wall rows */
  PetscBool left, right, face[6];
  PetscInt  body;   /* walls, solids, clamps: the body whose force -body_force gives (0: none) */
} Box;

typedef struct {
  Box       fluid[NBOX], tank[NTANK], solid[NBOX], clamp[NBOX], wall[NBOX];
  PetscInt  nfluid, ntank, nsolid, nclamp, nwall, nlevel, npress, nsgauge;
  PetscReal level[NGAUGE][2], press[NGAUGE][3], sgauge[NGAUGE][6];
  char      names[SCENE_MAX_PROBES][32];
  Shapes    shapes;
  OpenBoundarySpec open[SCENE_MAX_OPEN]; /* -inlet_K, -outlet_K */
  PetscInt         nopen;
  PetscBool        body_force; /* probes of the fluid's force on the obstacles (SimBodyForce) */
  PetscInt         nbody;      /* with it: bodies 1..nbody, each a probe of its force */
} Boxes;

extern SceneOps SceneBoxes; /* not const: Create fills in its probe names */

/* n numbers read into b: 2 D (or up to nmax) and a box whose high corner exceeds its low one. */
static PetscErrorCode CheckBox(Sim sim, const char *name, const PetscReal b[], PetscInt n, PetscInt nmax)
{
  const PetscInt D = SimDim(sim);
  PetscBool      empty = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCheck(n >= 2 * D && n <= nmax, SimComm(sim), PETSC_ERR_USER_INPUT, "%s takes %d%s numbers, not %d", name, (int)(2 * D), nmax == 2 * D ? "" : nmax == 2 * D + 1 ? (D == 3 ? " or 7" : " or 5") : (D == 3 ? " to 8" : " to 6"), (int)n);
  for (PetscInt d = 0; d < D; d++) empty = (PetscBool)(empty || !(b[D + d] > b[d]));
  if (D == 3) PetscCheck(!empty, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g: x1, y1, z1 must exceed x0, y0, z0", name, (double)b[0], (double)b[1], (double)b[2], (double)b[3], (double)b[4], (double)b[5]);
  else PetscCheck(!empty, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g: x1 must exceed x0 and y1 y0", name, (double)b[0], (double)b[1], (double)b[2], (double)b[3]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool Overlap(const PetscReal a[], const PetscReal b[], PetscInt D)
{
  PetscBool o = PETSC_TRUE;
  for (PetscInt d = 0; d < D; d++) o = (PetscBool)(o && a[d] < b[D + d] && b[d] < a[D + d]);
  return o;
}

static PetscBool Touch(const PetscReal a[], const PetscReal b[], PetscReal eps, PetscInt D)
{
  PetscBool t = PETSC_TRUE;
  for (PetscInt d = 0; d < D; d++) t = (PetscBool)(t && a[d] <= b[D + d] + eps && b[d] <= a[D + d] + eps);
  return t;
}

/* The boxes a tank's particles fill: the floor (with the corners) and the side walls. */
static PetscInt TankWalls(const Box *t, PetscInt D, PetscReal r[5][6])
{
  const PetscReal d = t->rows * t->s, *b = t->b;
  PetscInt        n = 0;
  if (D == 2) {
    r[n][0] = b[0] - (t->left ? d : 0); r[n][1] = b[1] - d; r[n][2] = b[2] + (t->right ? d : 0); r[n][3] = b[1]; n++;
    if (t->left) { r[n][0] = b[0] - d; r[n][1] = b[1]; r[n][2] = b[0]; r[n][3] = b[3]; n++; }
    if (t->right) { r[n][0] = b[2]; r[n][1] = b[1]; r[n][2] = b[2] + d; r[n][3] = b[3]; n++; }
    return n;
  }
  { /* 3D: floor; walls at x0 and x1 (full width), at y0 and y1 (between them) */
    const PetscReal w[5][6] = {{b[0] - d, b[1] - d, b[2] - d, b[3] + d, b[4] + d, b[2]},
                               {b[0] - d, b[1] - d, b[2], b[0], b[4] + d, b[5]},
                               {b[3], b[1] - d, b[2], b[3] + d, b[4] + d, b[5]},
                               {b[0], b[1] - d, b[2], b[3], b[1], b[5]},
                               {b[0], b[4], b[2], b[3], b[4] + d, b[5]}};
    for (; n < 5; n++)
      for (PetscInt k = 0; k < 6; k++) r[n][k] = w[n][k];
  }
  return n;
}

/* The boxes of walls, solids and clamps, which no shape may share space with. */
static PetscErrorCode BodyBoxes(const Boxes *c, PetscInt D, ShapesBoxes *B)
{
  const struct { const Box *box; PetscInt n; const char *prefix; } kinds[] = {{c->wall, c->nwall, "wall_box"}, {c->solid, c->nsolid, "solid_box"}, {c->clamp, c->nclamp, "clamp_box"}};
  PetscFunctionBeginUser;
  B->n = 0;
  PetscCheck(5 * c->ntank + c->nwall + c->nsolid + c->nclamp <= SHAPES_MAX_BOXES, PETSC_COMM_SELF, PETSC_ERR_PLIB, "More boxes than SHAPES_MAX_BOXES");
  for (PetscInt j = 0; j < c->ntank; j++) {
    PetscReal r[5][6];
    PetscInt  nr = TankWalls(&c->tank[j], D, r);
    for (PetscInt q = 0; q < nr; q++, B->n++) {
      PetscCall(PetscArraycpy(B->b[B->n], r[q], 6));
      PetscCall(PetscSNPrintf(B->name[B->n], sizeof(B->name[0]), "the walls of -tank_%d", (int)j + 1));
    }
  }
  for (PetscInt k = 0; k < 3; k++)
    for (PetscInt j = 0; j < kinds[k].n; j++, B->n++) {
      PetscCall(PetscArraycpy(B->b[B->n], kinds[k].box[j].b, 6));
      PetscCall(PetscSNPrintf(B->name[B->n], sizeof(B->name[0]), "-%s_%d", kinds[k].prefix, (int)j + 1));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Boxes K = 1..NBOX of one kind (-PREFIX_K); with spacing: a 5th number, the lattice's spacing; with
 * faces: -PREFIX_K_faces, the faces that meet water (default all), and -PREFIX_K_measured; an
 * obstacle: -PREFIX_K_body, the body whose force -body_force gives (default 1). */
static PetscErrorCode ReadBoxes(Sim sim, PetscOptionItems *PetscOptionsObject, const char *prefix, const char *text, Box *list, PetscInt *count, PetscBool spacing, PetscBool faces, PetscBool obstacle)
{
  const PetscInt D = SimDim(sim), nb = 2 * D;
  char           name[40];
  PetscFunctionBeginUser;
  for (PetscInt k = 1; k <= NBOX; k++) {
    PetscReal v[7];
    PetscInt  n = spacing ? nb + 1 : nb;
    PetscBool set, measured = PETSC_TRUE;
    Box      *B;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d", prefix, (int)k));
    PetscCall(PetscOptionsRealArray(name, text, "", v, &n, &set));
    if (!set) continue;
    PetscCall(CheckBox(sim, name, v, n, spacing ? nb + 1 : nb));
    B = &list[(*count)++];
    for (PetscInt i = 0; i < nb; i++) B->b[i] = v[i];
    B->s = n == nb + 1 ? v[nb] : SimSpacing(sim);
    PetscCheck(B->s > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "%s: the spacing %g must be > 0", name, (double)B->s);
    for (PetscInt i = 0; i < nb; i++) B->face[i] = PETSC_TRUE;
    B->body = obstacle ? 1 : 0;
    if (faces) {
      char list[64] = "";
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d_faces", prefix, (int)k));
      PetscCall(PetscOptionsString(name, "Faces of the obstacle that meet water: left,right,bottom,top (3D also front,back) (their outer row is wall, the rest dummies)", "", list, list, sizeof(list), &set));
      if (set) { /* the faces in the box's order: low faces, then high faces */
        const char *fn2[4] = {"left", "bottom", "right", "top"}, *fn3[6] = {"left", "front", "bottom", "right", "back", "top"};
        for (PetscInt i = 0; i < nb; i++) B->face[i] = (PetscBool)(strstr(list, D == 3 ? fn3[i] : fn2[i]) != NULL);
      }
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d_measured", prefix, (int)k));
      PetscCall(PetscOptionsBool(name, "Whether -body_force counts the fluid's force on this obstacle (0 for a channel's walls, whose friction is not the body's drag; as _body 0)", "", measured, &measured, NULL));
    }
    if (obstacle) {
      PetscBool given;
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d_body", prefix, (int)k));
      PetscCall(OptInt(name, "The body (1-4) whose force -body_force gives this obstacle's share of (probes force_x, force_y for body 1, force_x_N, force_y_N for body N); 0: none", "", B->body, &B->body, &given));
      PetscCheck(B->body >= 0 && B->body <= SHAPES_MAX_BODIES, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT ": a body is numbered 1 to %d (0: none)", name, B->body, SHAPES_MAX_BODIES);
      PetscCheck(measured || !given || B->body == 0, SimComm(sim), PETSC_ERR_ARG_INCOMP, "%s %" PetscInt_FMT " and -%s_%d_measured 0 contradict each other: give one of them", name, B->body, prefix, (int)k);
      if (!measured) B->body = 0;
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
  PetscReal   dom[6] = {0, 0, 0, 0, 0, 0}, top = -PETSC_MAX_REAL, low = PETSC_MAX_REAL;
  PetscInt    n, rows, D, up;
  PetscBool   set, dom_set, outflow;
  char        name[40];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCheck(SimSpacing(sim) > 0, SimComm(sim), PETSC_ERR_USER_INPUT, "Scene boxes needs -dx (the particle spacing, m)");
  PetscOptionsBegin(SimComm(sim), NULL, "Scene boxes: water, tanks, obstacles and solids as boxes given in the options", "");
  {
    PetscInt dim = SimDim(sim);
    PetscCall(OptInt("-dim", "Dimension: 2, or 3 (z up; every box then has six numbers)", "", dim, &dim, NULL));
    PetscCall(SimSetDim(sim, dim));
  }
  PetscCheck(SimDim(sim) == 2 || SimDim(sim) == 3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-dim %" PetscInt_FMT " must be 2 or 3", SimDim(sim));
  D = SimDim(sim); up = D - 1;
  if (D == 3) PetscCall(SimSetGravity(sim, SimGravity(sim)[0], 0, -9.81));
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "fluid_box", "Water at rest x0,y0,x1,y1[,spacing] (3D: x0,y0,z0,x1,y1,z1[,spacing]) (m)", c->fluid, &c->nfluid, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE));
  rows = SimKernelRows(sim);
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles of a tank that does not give its own", "", rows, &rows, NULL));
  PetscCheck(rows >= 1, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", rows);
  for (PetscInt k = 1; k <= NTANK; k++) {
    const PetscInt nb = 2 * D; /* x0,x1,y0,y1 (3D: ,z0,z1): each direction's range */
    PetscReal      v[8];
    PetscInt       side = 0;
    Box           *T;
    n = nb + 2;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-tank_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Tank x0,x1,y0,y1[,spacing[,rows]]: floor at y0 from x0 to x1, side walls up to y1 (m); 3D x0,x1,y0,y1,z0,z1[,spacing[,rows]]: floor at z0, walls on four sides up to z1", "", v, &n, &set));
    if (!set) continue;
    T = &c->tank[c->ntank++];
    PetscCheck(n >= nb && n <= nb + 2, SimComm(sim), PETSC_ERR_USER_INPUT, "%s takes %s[,spacing[,rows]], not %d numbers", name, D == 3 ? "x0,x1,y0,y1,z0,z1" : "x0,x1,y0,y1", (int)n);
    for (PetscInt d = 0; d < D; d++) { T->b[d] = v[2 * d]; T->b[D + d] = v[2 * d + 1]; }
    PetscCall(CheckBox(sim, name, T->b, nb, nb));
    T->s    = n >= nb + 1 ? v[nb] : SimSpacing(sim);
    T->rows = n >= nb + 2 ? (PetscInt)v[nb + 1] : rows;
    PetscCheck(T->s > 0 && T->rows >= 1 && (n < nb + 2 || v[nb + 1] == (PetscReal)T->rows), SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "%s: the spacing must be > 0 and the rows a whole number >= 1", name);
    PetscCall(PetscSNPrintf(name, sizeof(name), "-tank_%d_sides", (int)k));
    PetscCall(OptEList(name, "Side walls of the tank (2D)", "", sides, 4, sides[0], &side, NULL));
    PetscCheck(D == 2 || side == 0, SimComm(sim), PETSC_ERR_ARG_INCOMP, "%s: a 3D tank has walls on all four sides (both)", name);
    T->left  = (PetscBool)(side == 0 || side == 1);
    T->right = (PetscBool)(side == 0 || side == 2);
  }
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "solid_box", "Elastic solid x0,y0,x1,y1 (m), at -dx", c->solid, &c->nsolid, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE));
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "clamp_box", "Rigid clamp of a solid x0,y0,x1,y1 (m), at -dx", c->clamp, &c->nclamp, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE));
  PetscCall(ReadBoxes(sim, PetscOptionsObject, "wall_box", "Obstacle of wall particles x0,y0,x1,y1 (m), at -dx", c->wall, &c->nwall, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE));
  PetscCall(ShapesCreate(&c->shapes));
  PetscCall(ShapesRead(sim, PetscOptionsObject, c->shapes, rows));
  PetscCall(SceneOpenBoundaryOptions(sim, PetscOptionsObject, c->open, &c->nopen));
  PetscCall(OptBool("-body_force", "Probes force_x, force_y (3D also force_z): the fluid's force on the obstacles of body 1 (wall boxes, shapes and solids, all unless their _body says otherwise; N/m in 2D, N in 3D), as the momentum equation exchanges it; force_x_N, ... for each further body N", "", c->body_force, &c->body_force, NULL));
  outflow = SimOutflow(sim);
  PetscCall(OptBool("-outflow", "Water that leaves the domain is removed (an open boundary)", "", outflow, &outflow, NULL));
  PetscCall(SimSetOutflow(sim, outflow));
  n = 2 * D;
  PetscCall(PetscOptionsRealArray("-domain", "Computational box x0,y0,x1,y1 (3D: x0,y0,z0,x1,y1,z1) (m); default: the tanks with their walls, open to twice their height", "", dom, &n, &dom_set));
  if (dom_set) PetscCall(CheckBox(sim, "-domain", dom, n, 2 * D));
  {
    char per[16] = "";
    PetscBool all = PETSC_TRUE;
    PetscCall(PetscOptionsString("-periodic", "Directions in which the domain is periodic: x, x,y, ... (needs -domain; the water should fill those directions exactly, in whole spacings)", "", per, per, sizeof(per), &set));
    if (set) {
      PetscCheck(dom_set, SimComm(sim), PETSC_ERR_ARG_INCOMP, "-periodic %s needs -domain: the periodic box", per);
      for (char *q = per; *q; q++) {
        PetscInt d = *q == 'x' ? 0 : *q == 'y' ? 1 : *q == 'z' ? 2 : -1;
        if (*q == ',' || *q == ' ') continue;
        PetscCheck(d >= 0 && d < D, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-periodic %s: the directions are %s, separated by commas", per, D == 3 ? "x, y, z" : "x, y");
        PetscCall(SimSetPeriodic(sim, d, PETSC_TRUE));
      }
    }
    for (PetscInt d = 0; d < D; d++) all = (PetscBool)(all && SimPeriodic(sim, d));
    PetscCall(OptBool("-confined", "The water fills the domain: no free surface (ISPH pins the pressure's constant); default when every direction is periodic", "", all, &all, NULL));
    PetscCall(SimSetConfined(sim, all));
  }
  for (PetscInt k = 1; k <= NGAUGE; k++) {
    PetscInt nl = D - 1, np = D, nbox = 2 * D;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_level_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Water level gauge at this x (m) (3D: x,y)", "", c->level[c->nlevel], &nl, &set));
    PetscCheck(!set || nl == D - 1, SimComm(sim), PETSC_ERR_USER_INPUT, "%s takes %s", name, D == 3 ? "2 numbers x,y" : "1 number x");
    c->nlevel += set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_pressure_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Pressure gauge at x,y (3D: x,y,z) (m)", "", c->press[c->npress], &np, &set));
    PetscCheck(!set || np == D, SimComm(sim), PETSC_ERR_USER_INPUT, "%s takes %s", name, D == 3 ? "3 numbers x,y,z" : "2 numbers x,y");
    c->npress += set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-gauge_solid_%d", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Mean displacement of the solid particles whose reference position is in x0,y0,x1,y1 (3D: x0,y0,z0,x1,y1,z1) (m)", "", c->sgauge[c->nsgauge], &nbox, &set));
    if (set) PetscCall(CheckBox(sim, name, c->sgauge[c->nsgauge++], nbox, 2 * D));
  }
  PetscOptionsEnd();
  {
    PetscInt nfs = 0, nss = 0, ncs = 0;
    for (PetscInt i = 0; i < ShapesCount(c->shapes); i++) {
      ShapeKind kind;
      PetscReal lo[3], hi[3];
      PetscCall(ShapesGetShape(c->shapes, i, &kind, lo, hi));
      nfs += kind == SHAPE_FLUID;
      nss += kind == SHAPE_SOLID;
      ncs += kind == SHAPE_CLAMP;
      if (kind == SHAPE_FLUID) {
        top = PetscMax(top, hi[up]);
        low = PetscMin(low, lo[up]);
      }
    }
    PetscCheck(c->nfluid + nfs > 0 || c->nsolid + nss > 0, SimComm(sim), PETSC_ERR_USER_INPUT, "Scene boxes has no water and no solid: give -fluid_box_1 x0,y0,x1,y1");
    PetscCheck(!nss || c->nclamp + ncs > 0, SimComm(sim), PETSC_ERR_ARG_INCOMP, "A solid shape needs a clamp (-clamp_box_K, or a shape of kind clamp next to it): a free solid is not supported");
    PetscCall(SimSetMedia(sim, (PetscBool)(c->nfluid + nfs > 0), (PetscBool)(c->nsolid + nss > 0)));
  }
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 1.0));
  for (PetscInt i = 0; i < c->nsolid; i++) {
    PetscBool held = PETSC_FALSE;
    for (PetscInt j = 0; j < c->nclamp; j++) held = (PetscBool)(held || Touch(c->solid[i].b, c->clamp[j].b, 1e-9 * SimSpacing(sim), D));
    PetscCheck(held, SimComm(sim), PETSC_ERR_ARG_INCOMP, "-solid_box_%d touches no -clamp_box: a free solid is not supported; clamp it (a -clamp_box_K sharing an edge with it)", (int)i + 1);
  }
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const Box *F    = &c->fluid[i];
    PetscBool  thin = PETSC_FALSE;
    for (PetscInt d = 0; d < D; d++) thin = (PetscBool)(thin || F->b[D + d] - F->b[d] < F->s);
    PetscCheck(!thin, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-fluid_box_%d is thinner than its spacing %g: choose a smaller spacing", (int)i + 1, (double)F->s);
    for (PetscInt j = 0; j < i; j++) PetscCheck(!Overlap(F->b, c->fluid[j].b, D), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -fluid_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nwall; j++) PetscCheck(!Overlap(F->b, c->wall[j].b, D), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -wall_box_%d: water and wall cannot share space", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nsolid; j++) PetscCheck(!Overlap(F->b, c->solid[j].b, D), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -solid_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->nclamp; j++) PetscCheck(!Overlap(F->b, c->clamp[j].b, D), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps -clamp_box_%d", (int)i + 1, (int)j + 1);
    for (PetscInt j = 0; j < c->ntank; j++) {
      PetscReal r[5][6];
      PetscInt  nr = TankWalls(&c->tank[j], D, r);
      for (PetscInt q = 0; q < nr; q++) PetscCheck(!Overlap(F->b, r[q], D), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d overlaps the walls of -tank_%d: water and wall cannot share space", (int)i + 1, (int)j + 1);
    }
    top = PetscMax(top, F->b[D + up]);
    low = PetscMin(low, F->b[up]);
  }
  if (dom_set) {
    for (PetscInt d = 0; d < D; d++) PetscCall(SimSetDomain(sim, d, dom[d], dom[D + d]));
  } else {
    PetscCheck(c->ntank > 0, SimComm(sim), PETSC_ERR_USER_INPUT, "Scene boxes without a -tank_1 needs -domain %s", D == 3 ? "x0,y0,z0,x1,y1,z1" : "x0,y0,x1,y1");
    for (PetscInt d = 0; d < D; d++) PetscCall(SimSetDomain(sim, d, PETSC_MAX_REAL, -PETSC_MAX_REAL));
    for (PetscInt j = 0; j < c->ntank; j++) { /* the tank with its walls, open to twice its height */
      const Box      *T = &c->tank[j];
      const PetscReal d = (T->rows + 0.5) * T->s;
      for (PetscInt q = 0; q < D; q++) {
        PetscCall(SimSetDomain(sim, q, PetscMin(SimDomainLo(sim)[q], T->b[q] - d), PetscMax(SimDomainHi(sim)[q], q == up ? T->b[up] + 2 * (T->b[D + up] - T->b[up]) : T->b[D + q] + d)));
      }
    }
  }
  for (PetscInt k = 0; k < c->nopen; k++) PetscCall(SimAddOpenBoundary(sim, &c->open[k])); /* once the domain is known */
  for (PetscInt i = 0; i < c->nfluid; i++) {
    const PetscReal *b = c->fluid[i].b;
    PetscBool        in = PETSC_TRUE;
    for (PetscInt d = 0; d < D; d++) in = (PetscBool)(in && b[d] >= SimDomainLo(sim)[d] && b[D + d] <= SimDomainHi(sim)[d]);
    if (D == 3) PetscCheck(in, SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d reaches outside the domain [%g, %g] x [%g, %g] x [%g, %g]", (int)i + 1, (double)SimDomainLo(sim)[0], (double)SimDomainHi(sim)[0], (double)SimDomainLo(sim)[1], (double)SimDomainHi(sim)[1], (double)SimDomainLo(sim)[2], (double)SimDomainHi(sim)[2]);
    else PetscCheck(in, SimComm(sim), PETSC_ERR_ARG_INCOMP, "-fluid_box_%d reaches outside the domain [%g, %g] x [%g, %g]", (int)i + 1, (double)SimDomainLo(sim)[0], (double)SimDomainHi(sim)[0], (double)SimDomainLo(sim)[1], (double)SimDomainHi(sim)[1]);
  }
  for (PetscInt k = 0; k < c->nlevel; k++) {
    PetscBool in = PETSC_TRUE;
    for (PetscInt d = 0; d < D - 1; d++) in = (PetscBool)(in && c->level[k][d] > SimDomainLo(sim)[d] && c->level[k][d] < SimDomainHi(sim)[d]);
    PetscCheck(in, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gauge_level_%d %g is outside the domain [%g, %g]", (int)k + 1, (double)c->level[k][0], (double)SimDomainLo(sim)[0], (double)SimDomainHi(sim)[0]);
  }
  for (PetscInt k = 0; k < c->npress; k++) {
    PetscBool in = PETSC_TRUE;
    for (PetscInt d = 0; d < D; d++) in = (PetscBool)(in && c->press[k][d] > SimDomainLo(sim)[d] && c->press[k][d] < SimDomainHi(sim)[d]);
    PetscCheck(in, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-gauge_pressure_%d %g,%g%s is outside the domain", (int)k + 1, (double)c->press[k][0], (double)c->press[k][1], D == 3 ? ",..." : "");
  }
  {
    PetscReal   box[NBOX][6], sp[NBOX];
    ShapesBoxes bodies; /* the walls', solids' and clamps' boxes, for the shapes' overlap check */
    for (PetscInt i = 0; i < c->nfluid; i++) {
      for (PetscInt k = 0; k < 6; k++) box[i][k] = c->fluid[i].b[k];
      sp[i] = c->fluid[i].s;
    }
    PetscCall(BodyBoxes(c, D, &bodies));
    PetscCall(ShapesSetUp(sim, c->shapes, c->nfluid, (const PetscReal(*)[6])box, sp, &bodies));
  }
  PetscCheck(!c->nsgauge || c->nsolid, SimComm(sim), PETSC_ERR_ARG_INCOMP, "-gauge_solid_1 needs a -solid_box_1");
  /* c0 = 10 x the speed of a fall from the highest water surface to the lowest water */
  if (SimHasFluid(sim)) PetscCall(SimSetReferenceSpeed(sim, PetscSqrtReal(2 * SimGravityNorm(sim) * (top - low))));
  /* probes: front_x, v_max, then the gauges */
  n = 0;
  PetscCall(ProbeName(c, &n, "front_x", 0));
  PetscCall(ProbeName(c, &n, "v_max", 0));
  for (PetscInt k = 1; k <= c->nlevel; k++) PetscCall(ProbeName(c, &n, "level", k));
  for (PetscInt k = 1; k <= c->npress; k++) PetscCall(ProbeName(c, &n, "pressure", k));
  for (PetscInt k = 1; k <= c->nsgauge; k++) {
    PetscCall(ProbeName(c, &n, "solid_dx", k));
    PetscCall(ProbeName(c, &n, "solid_dy", k));
    if (D == 3) PetscCall(ProbeName(c, &n, "solid_dz", k));
  }
  if (c->nopen) {
    PetscCall(ProbeName(c, &n, "mass_in", 0));
    PetscCall(ProbeName(c, &n, "mass_out", 0));
  }
  if (ShapesFlowColumns(c->shapes)) {
    PetscCall(ProbeName(c, &n, "u_mean", 0));
    PetscCall(ProbeName(c, &n, "drag", 0));
  }
  if (c->body_force) {
    PetscCheck(SimHasFluid(sim), SimComm(sim), PETSC_ERR_ARG_INCOMP, "-body_force measures the fluid's force: give a -fluid_box");
    PetscCall(SimEnableField(sim, "body"));
    c->nbody = 1;
    for (PetscInt i = 0; i < c->nsolid; i++) c->nbody = PetscMax(c->nbody, c->solid[i].body);
    for (PetscInt i = 0; i < c->nclamp; i++) c->nbody = PetscMax(c->nbody, c->clamp[i].body);
    for (PetscInt i = 0; i < c->nwall; i++) c->nbody = PetscMax(c->nbody, c->wall[i].body);
    for (PetscInt i = 0; i < ShapesCount(c->shapes); i++) c->nbody = PetscMax(c->nbody, ShapesGetBody(c->shapes, i, NULL));
    for (PetscInt k = 1; k <= c->nbody; k++) { /* body 1: force_x, ...; body k: force_x_k, ... */
      PetscCall(ProbeName(c, &n, "force_x", k > 1 ? k : 0));
      PetscCall(ProbeName(c, &n, "force_y", k > 1 ? k : 0));
      if (D == 3) PetscCall(ProbeName(c, &n, "force_z", k > 1 ? k : 0));
    }
  }
  PetscCheck(n <= SCENE_MAX_PROBES, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "Scene boxes has %d probe columns (front_x, v_max and the gauges; a solid gauge counts one per dimension): at most %d", (int)n, SCENE_MAX_PROBES);
  SceneBoxes.nprobes = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  Boxes *c = (Boxes *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  const PetscInt D = SimDim(sim), up = D - 1;
  PetscInt       first_body, ids[3][NBOX][2]; /* each solid, clamp and wall box's ids [first, end) */
  for (PetscInt i = 0; i < c->nfluid; i++) { /* at rest: hydrostatic below the lattice's top */
    const Box *F     = &c->fluid[i];
    PetscInt   first, n;
    PetscReal  s     = SceneFitSpacing(F->b[D + up] - F->b[up], F->s, &n);
    PetscCall(SimGetLocalSize(sim, &first));
    PetscCall(SceneAddBox(sim, KIND_FLUID, F->b, F->s, SimFluidMaterial(sim)->rho0));
    if (ShapesCount(c->shapes)) PetscCall(ShapesCutWater(sim, c->shapes, first, F->b, F->b + D, F->s));
    PetscCall(SceneHydrostaticDensity(sim, first, F->b[up] + n * s));
  }
  for (PetscInt i = 0; i < c->ntank; i++) {
    const Box *T = &c->tank[i];
    if (D == 3) PetscCall(SceneAddTankBox(sim, T->b, T->b + 3, T->b[5], T->s, T->rows));
    else PetscCall(SceneAddTank(sim, T->b[0], T->b[2], T->b[1], T->b[3], T->s, T->rows, T->left, T->right));
  }
  first_body = SimNextId(sim); /* the obstacles: what follows the tanks */
  for (PetscInt i = 0; i < c->nsolid; i++) {
    ids[0][i][0] = SimNextId(sim);
    PetscCall(SceneAddBox(sim, KIND_SOLID, c->solid[i].b, SimSpacing(sim), SimSolidMaterial(sim)->rho0));
    ids[0][i][1] = SimNextId(sim);
  }
  for (PetscInt i = 0; i < c->nclamp; i++) {
    ids[1][i][0] = SimNextId(sim);
    PetscCall(SceneAddBox(sim, KIND_CLAMP, c->clamp[i].b, SimSpacing(sim), SimSolidMaterial(sim)->rho0));
    ids[1][i][1] = SimNextId(sim);
  }
  for (PetscInt i = 0; i < c->nwall; i++) {
    ids[2][i][0] = SimNextId(sim);
    PetscCall(SceneAddWallBox(sim, c->wall[i].b, SimSpacing(sim), c->wall[i].face));
    ids[2][i][1] = SimNextId(sim);
  }
  if (D == 3 && ShapesCount(c->shapes)) { /* an STL obstacle's faces resting on these walls are dry */
    PetscReal dry[6 * SHAPES_MAX][6];
    PetscInt  n = 0;
    for (PetscInt i = 0; i < c->ntank && n + 5 <= 6 * SHAPES_MAX; i++) n += TankWalls(&c->tank[i], D, dry + n);
    for (PetscInt i = 0; i < c->nwall && n < 6 * SHAPES_MAX; i++, n++)
      for (PetscInt k = 0; k < 6; k++) dry[n][k] = c->wall[i].b[k];
    PetscCall(ShapesSetDry(sim, c->shapes, n, (const PetscReal(*)[6])dry));
  }
  PetscCall(ShapesPopulate(sim, c->shapes));
  if (c->body_force) { /* every wall or solid particle made after the tanks: its box's or shape's body (default 1) */
    const PetscInt *id, *kind;
    PetscReal      *body;
    PetscInt        np;
    PetscCall(SimGetLocalSize(sim, &np));
    PetscCall(SimGetField(sim, "id", NULL, &id));
    PetscCall(SimGetField(sim, "kind", NULL, &kind));
    PetscCall(SimGetField(sim, "body", NULL, &body));
    const Box *list[3] = {c->solid, c->clamp, c->wall};
    PetscInt   nlist[3] = {c->nsolid, c->nclamp, c->nwall}, range[3 * NBOX + 2 * SHAPES_MAX][3], nr = 0; /* ids [first, end), body */
    for (PetscInt j = 0; j < 3; j++)
      for (PetscInt i = 0; i < nlist[j]; i++, nr++) {
        range[nr][0] = ids[j][i][0]; range[nr][1] = ids[j][i][1]; range[nr][2] = list[j][i].body;
      }
    for (PetscInt i = 0; i < ShapesCount(c->shapes); i++, nr++) range[nr][2] = ShapesGetBody(c->shapes, i, range[nr]);
    for (PetscInt a = 0; a < np; a++) {
      PetscInt k = id[a] >= first_body && !KindIsFluid(kind[a]) ? 1 : 0;
      for (PetscInt r = 0; r < nr && k; r++)
        if (id[a] >= range[r][0] && id[a] < range[r][1]) k = range[r][2];
      body[a] = (PetscReal)k;
    }
    PetscCall(SimRestoreField(sim, "id", NULL, &id));
    PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
    PetscCall(SimRestoreField(sim, "body", NULL, &body));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Boxes     *c = (Boxes *)SimSceneContext(sim);
  const PetscReal *x, *x0 = NULL;
  const PetscInt  *kind;
  PetscReal        m[1 + NGAUGE], s[4 * NGAUGE];
  PetscInt         n = 2, D = SimDim(sim), np;
  PetscBool        has_x0;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &np));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimHasField(sim, "x0", &has_x0));
  if (has_x0) PetscCall(SimGetField(sim, "x0", NULL, &x0));
  for (PetscInt k = 0; k <= c->nlevel; k++) m[k] = -PETSC_MAX_REAL;
  for (PetscInt k = 0; k < (D + 1) * c->nsgauge; k++) s[k] = 0;
  for (PetscInt a = 0; a < np; a++) {
    if (KindIsFluid(kind[a])) {
      m[0] = PetscMax(m[0], x[D * a]);
      for (PetscInt k = 0; k < c->nlevel; k++) { /* the highest water within 1.5 dx of the gauge's vertical */
        PetscBool near = PETSC_TRUE;
        for (PetscInt d = 0; d < D - 1; d++) near = (PetscBool)(near && PetscAbsReal(x[D * a + d] - c->level[k][d]) < 1.5 * SimSpacing(sim));
        if (near) m[1 + k] = PetscMax(m[1 + k], x[D * a + D - 1]);
      }
    } else if (kind[a] == KIND_SOLID && x0)
      for (PetscInt k = 0; k < c->nsgauge; k++) {
        const PetscReal *g = c->sgauge[k];
        PetscBool        in = PETSC_TRUE;
        for (PetscInt d = 0; d < D; d++) in = (PetscBool)(in && x0[D * a + d] >= g[d] && x0[D * a + d] <= g[D + d]);
        if (!in) continue;
        for (PetscInt d = 0; d < D; d++) s[(D + 1) * k + d] += x[D * a + d] - x0[D * a + d];
        s[(D + 1) * k + D] += 1;
      }
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  if (has_x0) PetscCall(SimRestoreField(sim, "x0", NULL, &x0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 1 + c->nlevel, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, (D + 1) * c->nsgauge, MPIU_REAL, MPIU_SUM, SimComm(sim)));
  vals[0] = m[0] > -PETSC_MAX_REAL ? m[0] + 0.5 * SimSpacing(sim) : 0;
  PetscCall(SceneMaxSpeed(sim, &vals[1]));
  for (PetscInt k = 0; k < c->nlevel; k++) vals[n++] = m[1 + k] > -PETSC_MAX_REAL ? m[1 + k] + 0.5 * SimSpacing(sim) : 0; /* 0: no water there */
  for (PetscInt k = 0; k < c->npress; k++) PetscCall(SceneProbePressure(sim, c->press[k], &vals[n++]));
  for (PetscInt k = 0; k < c->nsgauge; k++)
    for (PetscInt d = 0; d < D; d++) vals[n++] = s[(D + 1) * k + D] > 0 ? s[(D + 1) * k + d] / s[(D + 1) * k + D] : 0;
  if (c->nopen) {
    vals[n++] = SimFluidMassIn(sim);
    vals[n++] = SimFluidMassOut(sim);
  }
  PetscCall(ShapesFlowProbe(sim, c->shapes, vals + n));
  n += ShapesFlowColumns(c->shapes);
  if (c->body_force) {
    PetscReal f[SHAPES_MAX_BODIES][3];
    PetscCall(SimBodyForces(sim, 1, c->nbody, f));
    for (PetscInt k = 0; k < c->nbody; k++)
      for (PetscInt d = 0; d < D; d++) vals[n++] = f[k][d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Boxes *c = (Boxes *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(ShapesFlowErrors(sim, c->shapes, f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  Boxes *c = (Boxes *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  if (c) PetscCall(ShapesDestroy(&c->shapes));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

SceneOps SceneBoxes = {
  .name = "boxes", .help = "a case given as data: water, tanks, obstacles and solids as boxes in the options file",
  .create = Create, .populate = Populate,
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
