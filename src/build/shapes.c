/* Circles, spheres, polygons and STL surfaces of -case boxes (shapes.h; docs/geometry.md). */
#include "build/shapes.h"
#include "base/options_used.h"
#include "base/refdata.h"
#include <stdint.h>

const char *const ShapeKinds[] = {"wall", "fluid", "solid", "clamp", "ShapeKind", "SHAPE_", NULL};

/* Vertices x y (or x,y) one a line from a text file, '#' starts a comment. */
static PetscErrorCode ReadVertexFile(Sim sim, const char *opt, const char *file, PetscReal *xy, PetscInt *n)
{
  FILE *f;
  char  line[256];
  PetscInt lineno = 0;
  PetscFunctionBeginUser;
  *n = 0;
  f  = fopen(file, "r");
  PetscCheck(f, sim->comm, PETSC_ERR_FILE_OPEN, "%s: the vertex file %s cannot be opened", opt, file);
  while (fgets(line, sizeof(line), f)) {
    char  *c = strchr(line, '#'), *end;
    double x, y;
    lineno++;
    if (c) *c = 0;
    for (c = line; *c; c++)
      if (*c == ',') *c = ' ';
    x = strtod(line, &end);
    if (end == line) { /* a blank line */
      PetscBool blank = PETSC_TRUE;
      for (c = line; *c; c++) blank = (PetscBool)(blank && (*c == ' ' || *c == '\t' || *c == '\n' || *c == '\r'));
      if (!blank) fclose(f);
      PetscCheck(blank, sim->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: line %d of %s is not two numbers x y", opt, (int)lineno, file);
      continue;
    }
    c = end;
    y = strtod(c, &end);
    if (end == c || *n >= SHAPES_MAX_VERTICES) fclose(f);
    PetscCheck(end != c, sim->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: line %d of %s is not two numbers x y", opt, (int)lineno, file);
    PetscCheck(*n < SHAPES_MAX_VERTICES, sim->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has more than %d vertices", opt, file, SHAPES_MAX_VERTICES);
    xy[2 * *n]     = x;
    xy[2 * *n + 1] = y;
    (*n)++;
  }
  fclose(f);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -NAME_kind, -NAME_body, and for a polygon (or a circle) -NAME_scale, -NAME_rotate (degrees), -NAME_translate. */
static PetscErrorCode ReadShapeOptions(Sim sim, PetscOptionItems *PetscOptionsObject, Shape *s)
{
  char      opt[64];
  PetscInt  kind = SHAPE_WALL, nt = 3;
  PetscReal scale = 1, deg = 0, t[3] = {0, 0, 0}, ang[3] = {0, 0, 0};
  PetscBool set_s, set_r, set_t;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_kind", s->name));
  PetscCall(OptEList(opt, "What the shape is: wall (an obstacle: wall and dummy rows inside its surface), fluid (water at rest), solid (elastic) or clamp", "", ShapeKinds, 4, ShapeKinds[0], &kind, NULL));
  s->kind = (ShapeKind)kind;
  s->body = s->kind == SHAPE_FLUID ? 0 : 1;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_body", s->name));
  PetscCall(OptInt(opt, "The body (1-4) whose force -body_force gives this obstacle's share of; 0: none", "", s->body, &s->body, NULL));
  PetscCheck(s->body >= 0 && s->body <= SHAPES_MAX_BODIES && (s->kind != SHAPE_FLUID || s->body == 0), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT ": a body is numbered 1 to %d (0: none), and water is none", opt, s->body, SHAPES_MAX_BODIES);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_scale", s->name));
  PetscCall(PetscOptionsReal(opt, "Scale of the shape about the origin (applied first)", "", scale, &scale, &set_s));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_rotate", s->name));
  if (s->g.type == GEOM_MESH) {
    PetscInt nr = 3;
    PetscCall(PetscOptionsRealArray(opt, "Rotation of the surface about the origin, degrees: about z (one number), or about x, then y, then z (three; after the scale)", "", ang, &nr, &set_r));
    PetscCheck(!set_r || nr == 1 || nr == 3, sim->comm, PETSC_ERR_USER_INPUT, "%s takes 1 number (about z) or 3 (about x, y, z), not %d", opt, (int)nr);
    if (set_r && nr == 1) { ang[2] = ang[0]; ang[0] = 0; }
  } else PetscCall(PetscOptionsReal(opt, "Rotation of the shape about the origin, degrees anticlockwise (2D; after the scale)", "", deg, &deg, &set_r));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_translate", s->name));
  PetscCall(PetscOptionsRealArray(opt, "Translation of the shape x,y (3D x,y,z) (m; last)", "", t, &nt, &set_t));
  if (set_t) PetscCheck(nt == sim->phys.dim, sim->comm, PETSC_ERR_USER_INPUT, "%s takes %d numbers, not %d", opt, (int)sim->phys.dim, (int)nt);
  if (set_s) PetscCheck(scale > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s_scale %g must be > 0", s->name, (double)scale);
  PetscCheck(!set_r || sim->phys.dim == 2 || s->g.type == GEOM_MESH, sim->comm, PETSC_ERR_ARG_INCOMP, "%s_rotate: a sphere does not turn (rotation is for 2D shapes and STL surfaces)", s->name);
  if (s->g.type == GEOM_MESH && (set_s || set_r || set_t)) {
    for (PetscInt d = 0; d < 3; d++) ang[d] *= PETSC_PI / 180;
    PetscCall(GeomTransform3(&s->g, scale, ang, t));
  } else if (set_s || set_r || set_t) PetscCall(GeomTransform(&s->g, scale, deg * PETSC_PI / 180, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShapesRead(Sim sim, PetscOptionItems *PetscOptionsObject, Shapes S, PetscInt rows)
{
  const PetscInt D = sim->phys.dim;
  PetscReal     *xy;
  char           name[40];
  PetscBool      set;
  PetscFunctionBeginUser;
  S->rows = rows;
  PetscCall(PetscMalloc1(2 * SHAPES_MAX_VERTICES, &xy));
  for (PetscInt k = 1; k <= SHAPES_MAX; k++) { /* circles (2D) and spheres (3D) */
    PetscReal v[4];
    PetscInt  n = 4;
    for (PetscInt t = 0; t < 2; t++) { /* the other dimension's name: refused */
      const char *nm = t ? "sphere" : "cylinder";
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s_%d", nm, (int)k));
      n = 4;
      PetscCall(PetscOptionsRealArray(name, t ? "Sphere x,y,z,r (3D) (m)" : "Cylinder x,y,r (2D: a circle) (m)", "", v, &n, &set));
      if (!set) continue;
      PetscCheck(t == (D == 3), sim->comm, PETSC_ERR_ARG_INCOMP, "%s: a %s is for %dD cases; in %dD give -%s_%d", name, nm, t ? 3 : 2, (int)D, t ? "cylinder" : "sphere", (int)k);
      PetscCheck(n == D + 1, sim->comm, PETSC_ERR_USER_INPUT, "%s takes %d numbers %s, not %d", name, (int)D + 1, D == 3 ? "x,y,z,r" : "x,y,r", (int)n);
      PetscCheck(v[D] > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the radius %g must be > 0", name, (double)v[D]);
      PetscCall(GeomSphere(D, v, v[D], &S->s[S->n].g));
      PetscCall(PetscStrncpy(S->s[S->n].name, name, sizeof(S->s[0].name)));
      PetscCall(ReadShapeOptions(sim, PetscOptionsObject, &S->s[S->n++]));
    }
  }
  for (PetscInt k = 1; k <= SHAPES_MAX; k++) { /* polygons: vertices in the option, or in a file */
    PetscInt  n = 2 * SHAPES_MAX_VERTICES, e[2];
    PetscBool fset;
    char      file[PETSC_MAX_PATH_LEN] = "", fopt[PETSC_MAX_PATH_LEN + 48];
    GeomFault fault;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-polygon_%d", (int)k));
    PetscCall(PetscSNPrintf(fopt, sizeof(fopt), "-polygon_%d_file", (int)k));
    PetscCall(PetscOptionsRealArray(name, "Closed polygon x0,y0,x1,y1,... (2D; the last vertex joins the first; either orientation) (m)", "", xy, &n, &set));
    PetscCall(PetscOptionsString(fopt, "File of the polygon's vertices, x y (or x,y) one a line, # comments", "", file, file, sizeof(file), &fset));
    if (!set && !fset) continue;
    PetscCheck(D == 2, sim->comm, PETSC_ERR_ARG_INCOMP, "%s: polygons are 2D; a 3D case takes boxes and -sphere_K", set ? name : fopt);
    PetscCheck(!(set && fset), sim->comm, PETSC_ERR_ARG_INCOMP, "%s and %s: give the vertices one way", name, fopt);
    if (fset) PetscCall(ReadVertexFile(sim, fopt, file, xy, &n));
    else {
      PetscCheck(n % 2 == 0, sim->comm, PETSC_ERR_USER_INPUT, "%s has %d numbers: give x,y pairs", name, (int)n);
      PetscCheck(n < 2 * SHAPES_MAX_VERTICES, sim->comm, PETSC_ERR_USER_INPUT, "%s: at most %d vertices (more: -polygon_%d_file)", name, SHAPES_MAX_VERTICES - 1, (int)k);
      n /= 2;
    }
    fault = GeomPolygonCheck(n, xy, e);
    if (fset) PetscCall(PetscSNPrintf(fopt, sizeof(fopt), "%s (%s)", name, file)); /* the messages name the file */
    if (fault == GEOM_FEW_VERTICES) SETERRQ(sim->comm, PETSC_ERR_USER_INPUT, "%s: a polygon needs at least 3 vertices, not %d", fset ? fopt : name, (int)n);
    if (fault == GEOM_REPEATED_VERTEX) SETERRQ(sim->comm, PETSC_ERR_ARG_WRONG, "%s: vertices %d and %d are the same point (%g, %g): remove one", fset ? fopt : name, (int)e[0] + 1, (int)e[1] + 1, (double)xy[2 * e[0]], (double)xy[2 * e[0] + 1]);
    if (fault == GEOM_SELF_INTERSECTING) SETERRQ(sim->comm, PETSC_ERR_ARG_WRONG, "%s: edges %d and %d cross or touch (edge i joins vertex i to i + 1): the polygon must be simple", fset ? fopt : name, (int)e[0] + 1, (int)e[1] + 1);
    if (fault == GEOM_ZERO_AREA) SETERRQ(sim->comm, PETSC_ERR_ARG_WRONG, "%s encloses no area", fset ? fopt : name);
    PetscCall(GeomPolygon(n, xy, &S->s[S->n].g));
    PetscCall(PetscStrncpy(S->s[S->n].name, name, sizeof(S->s[0].name)));
    PetscCall(ReadShapeOptions(sim, PetscOptionsObject, &S->s[S->n++]));
  }
  PetscCall(PetscFree(xy));
  for (PetscInt k = 1; k <= SHAPES_MAX; k++) { /* closed triangulated surfaces from STL files (3D) */
    const char *const lattices[] = {"shared", "own", "Lattice", "", NULL};
    char              file[PETSC_MAX_PATH_LEN] = "", fopt[64];
    PetscInt          own = 0;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-stl_%d", (int)k));
    PetscCall(PetscOptionsString(name, "STL file (binary or ASCII) of a closed surface (3D; m, before _scale, _rotate, _translate)", "", file, file, sizeof(file), &set));
    if (!set) continue;
    PetscCheck(D == 3, sim->comm, PETSC_ERR_ARG_INCOMP, "%s: STL surfaces are 3D; a 2D case takes -polygon_K", name);
    PetscCheck(file[0], sim->comm, PETSC_ERR_USER_INPUT, "%s needs a file name", name);
    PetscCall(GeomMeshShape(sim->comm, name, file, &S->s[S->n].g));
    PetscCall(PetscStrncpy(S->s[S->n].name, name, sizeof(S->s[0].name)));
    PetscCall(PetscSNPrintf(fopt, sizeof(fopt), "%s_lattice", name));
    PetscCall(OptEList(fopt, "Lattice of the surface's particles: shared (the water's, interlocking with it) or own (its bounding box filled at -dx as a wall box is: an STL box then gives a wall box's particles)", "", lattices, 2, lattices[0], &own, NULL));
    S->s[S->n].own = (PetscBool)(own == 1);
    PetscCall(ReadShapeOptions(sim, PetscOptionsObject, &S->s[S->n++]));
  }
  PetscCall(OptBool("-flow_probe", "Probe columns u_mean (the superficial velocity along x: the fluid's volume-weighted x-velocity summed over the domain's area, i.e. the flow rate over the width) and drag (the body force on the water per obstacle shape over mu u_mean); summary.json: the drag at the end against the reference for a periodic array", "", S->flow, &S->flow, NULL));
  if (S->flow) PetscCall(SceneKeepSeries(sim, &S->drag));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The lattice points that may lie in shape s: index ranges lo..hi (inclusive) per direction. */
static void LatticeRange(const struct _n_Shapes *S, const GeomShape *g, PetscInt D, PetscInt lo[], PetscInt hi[])
{
  for (PetscInt d = 0; d < 3; d++) { lo[d] = 0; hi[d] = 0; }
  for (PetscInt d = 0; d < D; d++) {
    lo[d] = (PetscInt)PetscFloorReal((g->lo[d] - S->origin[d]) / S->h[d] - 0.5);
    hi[d] = (PetscInt)PetscCeilReal((g->hi[d] - S->origin[d]) / S->h[d] - 0.5);
  }
}

static void LatticePoint(const struct _n_Shapes *S, const PetscInt i[], PetscInt D, PetscReal p[])
{
  for (PetscInt d = 0; d < D; d++) p[d] = S->origin[d] + (i[d] + 0.5) * S->h[d];
}

/* Whether p is strictly inside the box b (its low corner, then its high one): touching is not. */
static PetscBool InsideBox(const PetscReal p[], const PetscReal b[], PetscInt D)
{
  PetscBool in = PETSC_TRUE;
  for (PetscInt d = 0; d < D; d++) in = (PetscBool)(in && p[d] > b[d] && p[d] < b[D + d]);
  return in;
}

/* The signed distance of p to shape s or, for a shape across a periodic boundary, to the nearest of
 * its periodic images (exact within dmax, else the sign: GeomSignedDistanceNear). */
static PetscReal ShapeDistance(const Shape *s, const PetscReal p[], PetscReal dmax, PetscInt D)
{
  PetscReal best = GeomSignedDistanceNear(&s->g, p, dmax);
  if (!s->wraps) return best;
  for (PetscInt k = 1; k < (D == 3 ? 27 : 9); k++) { /* the images k = (k0, k1[, k2]) in {-1, 0, 1}^D but 0 */
    PetscReal q[3] = {p[0], p[1], D == 3 ? p[2] : 0};
    PetscInt  kk = k, skip = 0;
    for (PetscInt d = 0; d < D; d++, kk /= 3) {
      const PetscInt e = kk % 3 == 2 ? -1 : kk % 3;
      if (e && s->period[d] == 0) skip = 1;
      q[d] += e * s->period[d];
    }
    if (!skip) best = PetscMin(best, GeomSignedDistanceNear(&s->g, q, dmax));
  }
  return best;
}

/* A point of a shape across a periodic boundary, brought into the domain. */
static void Wrap(const struct _n_Shapes *S, const Shape *s, PetscReal p[], PetscInt D)
{
  for (PetscInt d = 0; d < D && s->wraps; d++) {
    if (s->period[d] == 0) continue;
    if (p[d] >= S->hi[d]) p[d] -= s->period[d];
    else if (p[d] < S->lo[d]) p[d] += s->period[d];
  }
}

/* A shape's own lattice (-stl_K_lattice own): its bounding box filled at -dx as SceneAddBox fills a
 * box (the same spacing, points and order), indices 0 .. n - 1. */
static void OwnLattice(Sim sim, const GeomShape *g, PetscInt D, PetscReal first[], PetscReal s[], PetscInt lo[], PetscInt hi[])
{
  for (PetscInt d = 0; d < 3; d++) { lo[d] = hi[d] = 0; s[d] = sim->phys.dx; first[d] = 0; }
  for (PetscInt d = 0; d < D; d++) {
    PetscInt n;
    s[d]     = SceneFitSpacing(g->hi[d] - g->lo[d], sim->phys.dx, &n);
    first[d] = g->lo[d] + 0.5 * s[d];
    hi[d]    = n - 1;
  }
}

static PetscBool InDryBox(const PetscReal p[], void *ctx)
{
  const struct _n_Shapes *S = (const struct _n_Shapes *)ctx;
  for (PetscInt b = 0; b < S->ndry; b++)
    if (InsideBox(p, S->dry[b], 3)) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode ShapesSetDry(Sim sim, Shapes S, PetscInt n, const PetscReal (*box)[6])
{
  PetscFunctionBeginUser;
  PetscCheck(n <= 6 * SHAPES_MAX, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "At most %d wall boxes", 6 * SHAPES_MAX);
  S->ndry = n;
  for (PetscInt b = 0; b < n; b++)
    for (PetscInt k = 0; k < 6; k++) S->dry[b][k] = box[b][k];
  for (PetscInt i = 0; i < S->n; i++) {
    PetscInt ndry;
    if (S->s[i].g.type != GEOM_MESH || S->s[i].kind != SHAPE_WALL || !n) continue;
    PetscCall(GeomMeshSetDry(S->s[i].g.mesh, 0.25 * sim->phys.dx, InDryBox, S, &ndry));
    PetscCall(PetscInfo(NULL, "%s: %d of its %d triangles rest on other walls (dry)\n", S->s[i].name, (int)ndry, (int)S->s[i].g.mesh->nt));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool IsBody(ShapeKind k) { return (PetscBool)(k != SHAPE_FLUID); }

/* Whether the lattice point p is in or on another shape of the solid kinds that takes it from s: a
 * clamp takes the points it shares with a solid. */
static PetscBool TakenByClamp(const struct _n_Shapes *S, PetscInt si, const PetscReal p[], PetscInt D)
{
  if (S->s[si].kind != SHAPE_SOLID) return PETSC_FALSE;
  for (PetscInt j = 0; j < S->n; j++)
    if (S->s[j].kind == SHAPE_CLAMP && ShapeDistance(&S->s[j], p, 0, D) <= 0) return PETSC_TRUE; /* the sign only */
  return PETSC_FALSE;
}

/* How shape s walks its lattice (ShapesPopulate): the index ranges, an own lattice's first point and
 * spacings, a wall row's depth, how far the distance matters, dry faces. */
typedef struct {
  PetscInt   lo[3], hi[3];
  PetscReal  f0[3], sp[3];
  PetscReal  hw, dmax;
  PetscBool  dry;
  PetscBool  own; /* on the shape's own lattice (f0, sp), else on the shared one */
  PetscInt64 n;   /* points in the ranges */
} ShapeWalk;

/* The number of points in the walk's ranges */
static void WalkCount(ShapeWalk *w)
{
  w->n = 1;
  for (PetscInt d = 0; d < 3; d++) w->n *= PetscMax(0, w->hi[d] - w->lo[d] + 1);
}

static void WalkSetUp(Sim sim, const struct _n_Shapes *S, const Shape *s, ShapeWalk *w)
{
  const PetscInt D = sim->phys.dim;
  w->hw   = s->own ? sim->phys.dx : (D == 3 ? PetscMin(S->h[0], PetscMin(S->h[1], S->h[2])) : PetscMin(S->h[0], S->h[1])); /* a wall box's rows are -dx deep */
  w->dmax = s->kind != SHAPE_WALL ? 0 : (s->own ? 2 : S->rows + 1) * w->hw;
  w->dry  = (PetscBool)(s->g.type == GEOM_MESH && s->g.mesh->dry);
  w->own  = s->own;
  if (s->own) OwnLattice(sim, &s->g, D, w->f0, w->sp, w->lo, w->hi);
  else LatticeRange(S, &s->g, D, w->lo, w->hi);
  WalkCount(w);
}

/* The l-th point of the walk (x fastest, then y, then z) */
static void WalkPoint(const struct _n_Shapes *S, const ShapeWalk *w, PetscInt64 l, PetscInt D, PetscReal p[])
{
  const PetscInt64 n0 = w->hi[0] - w->lo[0] + 1, n1 = w->hi[1] - w->lo[1] + 1;
  const PetscInt   idx[3] = {w->lo[0] + (PetscInt)(l % n0), w->lo[1] + (PetscInt)(l / n0 % n1), w->lo[2] + (PetscInt)(l / n0 / n1)};
  p[0] = p[1] = p[2] = 0;
  if (w->own)
    for (PetscInt d = 0; d < D; d++) p[d] = w->f0[d] + idx[d] * w->sp[d];
  else LatticePoint(S, idx, D, p);
}

/* What shape si puts at the l-th point of its walk: nothing (0) or a particle of kind code - 1. */
static unsigned char PointCode(const struct _n_Shapes *S, PetscInt si, const ShapeWalk *w, PetscInt64 l, PetscInt D)
{
  const Shape *s = &S->s[si];
  PetscReal    p[3], pu[3], sd;
  ParticleKind kind;
  WalkPoint(S, w, l, D, p);
  sd = GeomSignedDistanceNear(&s->g, p, w->dmax); /* exact within the wall rows; else the sign */
  if (sd > 0) return 0;
  for (PetscInt d = 0; d < 3; d++) pu[d] = p[d]; /* in the shape's frame */
  Wrap(S, s, p, D);
  if (TakenByClamp(S, si, p, D)) return 0;
  switch (s->kind) {
  case SHAPE_WALL: /* the row next to the surface is wall, the deeper rows dummies, down to rows deep */
    if (sd <= -S->rows * w->hw && !s->own) return 0; /* an own lattice fills the inside, as a wall box */
    kind = sd > -w->hw ? KIND_WALL : KIND_DUMMY;
    if (w->dry && kind == KIND_WALL && GeomMeshDistanceWet(s->g.mesh, pu, w->hw) >= w->hw) kind = KIND_DUMMY; /* near dry faces only */
    break;
  case SHAPE_FLUID: kind = KIND_FLUID; break;
  case SHAPE_SOLID: kind = KIND_SOLID; break;
  default: kind = KIND_CLAMP; break;
  }
  return (unsigned char)(kind + 1);
}

/* The points of a walk in blocks of WALK_BLOCK, dealt to the ranks in turn: rank r tests blocks r,
 * r + size, ... (the signed distances are the cost, spread over the ranks). */
#define WALK_BLOCK 256
static PetscBool WalkMine(Sim sim, PetscInt64 l) { return (PetscBool)((l / WALK_BLOCK) % sim->size == sim->rank); }

/* Whether the l-th point of shape i's walk (the shared lattice) lies in shape i and in space that
 * another shape or box of the scene holds: then msg says which (ShapesSetUp). */
static PetscBool Overlap(const struct _n_Shapes *S, PetscInt i, const ShapeWalk *w, PetscInt64 l, PetscInt nbox, const PetscReal (*box)[6], const ShapesBoxes *bodies, PetscInt D, char *msg, size_t len)
{
  const ShapeKind ki = S->s[i].kind;
  PetscReal       p[3];
  WalkPoint(S, w, l, D, p);
  if (GeomSignedDistanceNear(&S->s[i].g, p, 0) > 0) return PETSC_FALSE;
  Wrap(S, &S->s[i], p, D);
  for (PetscInt j = i + 1; j < S->n; j++) {
    const ShapeKind kj = S->s[j].kind;
    if (IsBody(ki) != IsBody(kj) || (ki == SHAPE_SOLID && kj == SHAPE_CLAMP) || (kj == SHAPE_SOLID && ki == SHAPE_CLAMP)) continue; /* water is cut by bodies; a clamp takes from a solid */
    if (ShapeDistance(&S->s[j], p, 0, D) <= 0) {
      (void)PetscSNPrintf(msg, len, "%s (%s) overlaps %s (%s) at (%g, %g): shapes of these kinds cannot share space", S->s[i].name, ShapeKinds[ki], S->s[j].name, ShapeKinds[kj], (double)p[0], (double)p[1]);
      return PETSC_TRUE;
    }
  }
  for (PetscInt b = 0; b < bodies->n; b++) /* strictly inside: touching is fine */
    if (InsideBox(p, bodies->b[b], D)) {
      (void)PetscSNPrintf(msg, len, "%s (%s) overlaps %s at (%g, %g%s): a shape cannot share space with walls, solids or clamps (they may touch)", S->s[i].name, ShapeKinds[ki], bodies->name[b], (double)p[0], (double)p[1], D == 3 ? ", ..." : "");
      return PETSC_TRUE;
    }
  if (ki != SHAPE_FLUID) return PETSC_FALSE;
  for (PetscInt b = 0; b < nbox; b++)
    if (InsideBox(p, box[b], D)) {
      (void)PetscSNPrintf(msg, len, "%s (fluid) overlaps -fluid_box_%d at (%g, %g)", S->s[i].name, (int)b + 1, (double)p[0], (double)p[1]);
      return PETSC_TRUE;
    }
  return PETSC_FALSE;
}

PetscErrorCode ShapesSetUp(Sim sim, Shapes S, PetscInt nbox, const PetscReal (*box)[6], const PetscReal *spacing, const ShapesBoxes *bodies)
{
  const PetscInt D = sim->phys.dim;
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < D; d++) { S->origin[d] = sim->dom_lo[d]; S->h[d] = sim->phys.dx; }
  if (nbox > 0 && spacing[0] == sim->phys.dx) /* the first water box's lattice */
    for (PetscInt d = 0; d < D; d++) {
      PetscInt n;
      S->origin[d] = box[0][d];
      S->h[d]      = SceneFitSpacing(box[0][D + d] - box[0][d], sim->phys.dx, &n);
    }
  S->flow_measure = 1;
  for (PetscInt d = 0; d < D; d++) {
    S->flow_measure *= sim->dom_hi[d] - sim->dom_lo[d];
    S->lo[d] = sim->dom_lo[d];
    S->hi[d] = sim->dom_hi[d];
  }
  for (PetscInt i = 0; i < S->n; i++) {
    Shape           *s  = &S->s[i];
    const GeomShape *g  = &s->g;
    PetscBool        in = PETSC_TRUE;
    for (PetscInt d = 0; d < D; d++) {
      const PetscReal L = sim->dom_hi[d] - sim->dom_lo[d];
      if (g->lo[d] >= sim->dom_lo[d] && g->hi[d] <= sim->dom_hi[d]) continue;
      if (!sim->periodic[d]) { in = PETSC_FALSE; continue; }
      /* across a periodic boundary: its particles beyond it are placed on the other side, on the lattice */
      PetscCheck(g->hi[d] - g->lo[d] < L, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s is wider than the periodic domain in %c (%g m against %g m)", s->name, "xyz"[d], (double)(g->hi[d] - g->lo[d]), (double)L);
      PetscCheck(!s->own && PetscAbsReal(L / S->h[d] - RoundToInt(L / S->h[d])) < 1e-9, sim->comm, PETSC_ERR_ARG_INCOMP, "%s crosses the periodic boundary in %c: the period %g m must hold whole lattice spacings (%g m)%s", s->name, "xyz"[d], (double)L, (double)S->h[d], s->own ? " and the surface the shared lattice (-stl_K_lattice shared)" : "");
      s->period[d] = L;
      s->wraps     = PETSC_TRUE;
    }
    PetscCheck(in, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s reaches outside the domain (it spans x %g to %g, y %g to %g): move it, or widen -domain (or make the domain periodic there)", s->name, (double)g->lo[0], (double)g->hi[0], (double)g->lo[1], (double)g->hi[1]);
  }
  /* points shared: bodies with bodies (but a clamp with a solid), water shapes with water; each rank
   * tests its share of a shape's points, and all raise the error of the first point in the walk */
  for (PetscInt i = 0; i < S->n; i++) {
    ShapeWalk  w   = {.own = PETSC_FALSE}; /* the shared lattice, for every shape */
    PetscInt64 bad = INT64_MAX;
    char       msg[256];
    LatticeRange(S, &S->s[i].g, D, w.lo, w.hi);
    WalkCount(&w);
    for (PetscInt64 l = 0; l < w.n && bad == INT64_MAX; l++)
      if (WalkMine(sim, l) && Overlap(S, i, &w, l, nbox, box, bodies, D, msg, sizeof(msg))) bad = l;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT64, MPI_MIN, sim->comm));
    if (bad < INT64_MAX) {
      (void)Overlap(S, i, &w, bad, nbox, box, bodies, D, msg, sizeof(msg));
      SETERRQ(sim->comm, PETSC_ERR_ARG_INCOMP, "%s", msg);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every point's code (PointCode) on every rank: each rank tests its share, an allreduce joins them. */
static PetscErrorCode WalkCodes(Sim sim, const struct _n_Shapes *S, PetscInt si, const ShapeWalk *w, unsigned char **code)
{
  PetscFunctionBeginUser;
  PetscCheck(w->n < PETSC_MPI_INT_MAX, sim->comm, PETSC_ERR_SUP, "%s spans %" PetscInt64_FMT " lattice points, more than %d: split it", S->s[si].name, w->n, (int)PETSC_MPI_INT_MAX);
  PetscCall(PetscCalloc1(w->n + 1, code));
  for (PetscInt64 l = 0; l < w->n; l++)
    if (WalkMine(sim, l)) (*code)[l] = PointCode(S, si, w, l, sim->phys.dim);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, *code, (PetscMPIInt)w->n, MPI_UNSIGNED_CHAR, MPI_MAX, sim->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShapesPopulate(Sim sim, Shapes S)
{
  const PetscInt D  = sim->phys.dim;
  const PetscInt n0 = sim->P->n;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  for (PetscInt pass = 0; pass < 2; pass++) /* water first, then the bodies in the order given */
    for (PetscInt i = 0; i < S->n; i++) {
      const Shape   *s = &S->s[i];
      ShapeWalk      w;
      unsigned char *code;
      PetscInt       first = sim->P->n;
      PetscReal      top   = -PETSC_MAX_REAL; /* water: the highest point's top */
      if ((pass == 0) != (s->kind == SHAPE_FLUID)) continue;
      S->s[i].ids[0] = SimNextId(sim);
      const PetscReal *h;
      WalkSetUp(sim, S, s, &w);
      h = s->own ? w.sp : S->h; /* the points' spacings */
      PetscCall(WalkCodes(sim, S, i, &w, &code));
      for (PetscInt64 l = 0; l < w.n; l++) { /* every rank adds the same points in the same order: the ids */
        const ParticleKind kind = (ParticleKind)(code[l] - 1);
        PetscReal          p[3];
        if (!code[l]) continue;
        WalkPoint(S, &w, l, D, p);
        Wrap(S, s, p, D);
        top = PetscMax(top, p[D - 1] + 0.5 * h[D - 1]);
        PetscCall(SceneAddPoint(sim, kind, p, h, sim->phys.dx, KindIsSolid(kind) ? sim->phys.sl.rho0 : sim->phys.fl.rho0));
      }
      PetscCall(PetscFree(code));
      S->s[i].ids[1] = SimNextId(sim);
      if (s->kind == SHAPE_FLUID) {
        PetscCall(ShapesCutWater(sim, S, first, NULL, NULL, 0));
        PetscCall(SceneHydrostaticDensity(sim, first, top));
      }
    }
  PetscCall(PetscTime(&t1));
  if (S->n) PetscCall(PetscInfo(NULL, "shapes: %d particles on this rank in %g s\n", (int)(sim->P->n - n0), (double)(t1 - t0)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShapesCutWater(Sim sim, Shapes S, PetscInt first, const PetscReal lo[], const PetscReal hi[], PetscReal spacing)
{
  Particles  P = sim->P;
  const PetscInt D = sim->phys.dim;
  PetscReal  gap = 0, *x = PField(P, FIELD_X);
  PetscBool *drop, any = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (lo) { /* a water box: on the shapes' lattice, or half a spacing of clearance */
    for (PetscInt d = 0; d < D; d++) {
      PetscInt  n;
      PetscReal h = SceneFitSpacing(hi[d] - lo[d], spacing, &n), f = (lo[d] - S->origin[d]) / S->h[d];
      if (PetscAbsReal(h - S->h[d]) > 1e-9 * h || PetscAbsReal(f - RoundToInt(f)) > 1e-6) gap = 0.5 * spacing;
    }
  }
  PetscCall(PetscCalloc1(P->n, &drop));
  for (PetscInt a = first; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    for (PetscInt i = 0; i < S->n && !drop[a]; i++) {
      const GeomShape *g   = &S->s[i].g;
      PetscBool        box = PETSC_TRUE;
      if (!IsBody(S->s[i].kind)) continue;
      for (PetscInt d = 0; d < D; d++) box = (PetscBool)(box && x[D * a + d] >= g->lo[d] - gap && x[D * a + d] <= g->hi[d] + gap);
      if ((box || S->s[i].wraps) && ShapeDistance(&S->s[i], x + D * a, 2 * gap, D) <= gap) drop[a] = any = PETSC_TRUE;
    }
  }
  if (any) PetscCall(ParticlesRemove(P, drop));
  PetscCall(PetscFree(drop));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShapesCreate(Shapes *S)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(S));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt ShapesCount(Shapes S) { return S->n; }

PetscErrorCode ShapesGetShape(Shapes S, PetscInt i, ShapeKind *kind, PetscReal lo[], PetscReal hi[])
{
  PetscFunctionBeginUser;
  PetscCheck(i >= 0 && i < S->n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Shape %" PetscInt_FMT " of %" PetscInt_FMT, i, S->n);
  if (kind) *kind = S->s[i].kind;
  for (PetscInt d = 0; d < 3; d++) {
    if (lo) lo[d] = S->s[i].g.lo[d];
    if (hi) hi[d] = S->s[i].g.hi[d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt ShapesGetBody(Shapes S, PetscInt i, PetscInt ids[])
{
  if (ids) {
    ids[0] = S->s[i].ids[0];
    ids[1] = S->s[i].ids[1];
  }
  return S->s[i].body;
}

PetscErrorCode ShapesDestroy(Shapes *S)
{
  PetscFunctionBeginUser;
  if (!*S) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt i = 0; i < (*S)->n; i++) PetscCall(GeomDestroy(&(*S)->s[i].g));
  PetscCall(SeriesDestroy(&(*S)->drag));
  PetscCall(PetscFree(*S));
  PetscFunctionReturn(PETSC_SUCCESS);
}
