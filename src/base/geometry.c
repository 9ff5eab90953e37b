#include "base/geometry.h"

const char *const GeomFaults[] = {"ok", "fewer than 3 vertices", "two consecutive vertices are equal", "two edges cross or touch (the polygon is not simple)", "zero area", "GeomFault", "GEOM_", NULL};

/* (b - a) x (c - a) */
static PetscReal Orient(const PetscReal a[], const PetscReal b[], const PetscReal c[])
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* c on the segment ab, given that it is on the line */
static PetscBool OnSegment(const PetscReal a[], const PetscReal b[], const PetscReal c[])
{
  return (PetscBool)(c[0] >= PetscMin(a[0], b[0]) && c[0] <= PetscMax(a[0], b[0]) && c[1] >= PetscMin(a[1], b[1]) && c[1] <= PetscMax(a[1], b[1]));
}

/* The closed segments pq and rs meet. */
static PetscBool SegmentsMeet(const PetscReal p[], const PetscReal q[], const PetscReal r[], const PetscReal s[])
{
  PetscReal o1 = Orient(p, q, r), o2 = Orient(p, q, s), o3 = Orient(r, s, p), o4 = Orient(r, s, q);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return PETSC_TRUE;
  return (PetscBool)((o1 == 0 && OnSegment(p, q, r)) || (o2 == 0 && OnSegment(p, q, s)) || (o3 == 0 && OnSegment(r, s, p)) || (o4 == 0 && OnSegment(r, s, q)));
}

/* Two edges that share the vertex v, its other ends a and b: they overlap (the boundary folds back
 * along itself) when a and b lie on the same ray from v. */
static PetscBool Folds(const PetscReal v[], const PetscReal a[], const PetscReal b[])
{
  return (PetscBool)(Orient(v, a, b) == 0 && (a[0] - v[0]) * (b[0] - v[0]) + (a[1] - v[1]) * (b[1] - v[1]) > 0);
}

/* twice the signed area (> 0 counter-clockwise) */
static PetscReal Area2(PetscInt n, const PetscReal xy[])
{
  PetscReal a = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscInt j = (i + 1) % n;
    a += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
  }
  return a;
}

GeomFault GeomPolygonCheck(PetscInt n, const PetscReal xy[], PetscInt e[2])
{
  e[0] = e[1] = -1;
  if (n < 3) return GEOM_FEW_VERTICES;
  for (PetscInt i = 0; i < n; i++) {
    PetscInt j = (i + 1) % n;
    if (xy[2 * i] == xy[2 * j] && xy[2 * i + 1] == xy[2 * j + 1]) { e[0] = i; e[1] = j; return GEOM_REPEATED_VERTEX; }
  }
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = i + 1; j < n; j++) {
      const PetscReal *p = xy + 2 * i, *q = xy + 2 * ((i + 1) % n), *r = xy + 2 * j, *s = xy + 2 * ((j + 1) % n);
      PetscBool        meet;
      if (j == i + 1) meet = Folds(q, p, s);
      else if (i == 0 && j == n - 1) meet = Folds(p, q, r);
      else meet = SegmentsMeet(p, q, r, s);
      if (meet) { e[0] = i; e[1] = j; return GEOM_SELF_INTERSECTING; }
    }
  if (Area2(n, xy) == 0) return GEOM_ZERO_AREA;
  return GEOM_OK;
}

PetscErrorCode GeomSphere(PetscInt dim, const PetscReal c[], PetscReal r, GeomShape *s)
{
  PetscFunctionBeginUser;
  PetscCheck(dim == 2 || dim == 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "A sphere in %" PetscInt_FMT " dimensions: 2 or 3", dim);
  PetscCheck(r > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "A sphere's radius %g must be > 0", (double)r);
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->type = GEOM_SPHERE;
  s->dim  = dim;
  s->r    = r;
  for (PetscInt d = 0; d < dim; d++) {
    s->c[d]  = c[d];
    s->lo[d] = c[d] - r;
    s->hi[d] = c[d] + r;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void PolygonBox(GeomShape *s)
{
  s->lo[0] = s->lo[1] = PETSC_MAX_REAL;
  s->hi[0] = s->hi[1] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < s->nv; i++)
    for (PetscInt d = 0; d < 2; d++) {
      s->lo[d] = PetscMin(s->lo[d], s->v[2 * i + d]);
      s->hi[d] = PetscMax(s->hi[d], s->v[2 * i + d]);
    }
}

PetscErrorCode GeomPolygon(PetscInt n, const PetscReal xy[], GeomShape *s)
{
  PetscInt  e[2];
  GeomFault f = GeomPolygonCheck(n, xy, e);
  PetscFunctionBeginUser;
  PetscCheck(f == GEOM_OK, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "A polygon of %" PetscInt_FMT " vertices: %s", n, GeomFaults[f]);
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->type = GEOM_POLYGON;
  s->dim  = 2;
  s->nv   = n;
  PetscCall(PetscMalloc1(2 * n, &s->v));
  PetscCall(PetscArraycpy(s->v, xy, 2 * n));
  PolygonBox(s);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomMeshShape(MPI_Comm comm, const char *opt, const char *file, GeomShape *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->type = GEOM_MESH;
  s->dim  = 3;
  PetscCall(PetscNew(&s->mesh));
  PetscCall(GeomMeshReadSTL(comm, opt, file, s->mesh));
  for (PetscInt d = 0; d < 3; d++) { s->lo[d] = s->mesh->lo[d]; s->hi[d] = s->mesh->hi[d]; }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomTransform3(GeomShape *s, PetscReal scale, const PetscReal ang[3], const PetscReal t[])
{
  PetscFunctionBeginUser;
  PetscCheck(s->type == GEOM_MESH, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "GeomTransform3 is for meshes");
  PetscCall(GeomMeshTransform(s->mesh, scale, ang, t));
  for (PetscInt d = 0; d < 3; d++) { s->lo[d] = s->mesh->lo[d]; s->hi[d] = s->mesh->hi[d]; }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomTransform(GeomShape *s, PetscReal scale, PetscReal angle, const PetscReal t[])
{
  const PetscReal cs = PetscCosReal(angle), sn = PetscSinReal(angle);
  PetscFunctionBeginUser;
  PetscCheck(scale > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "A shape's scale %g must be > 0", (double)scale);
  if (s->type == GEOM_MESH) { /* about z */
    const PetscReal ang[3] = {0, 0, angle};
    PetscCall(GeomTransform3(s, scale, ang, t));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (s->type == GEOM_SPHERE) {
    PetscReal c[3] = {0, 0, 0};
    for (PetscInt d = 0; d < s->dim; d++) c[d] = scale * s->c[d];
    if (s->dim == 2) { /* the centre turns about the origin */
      const PetscReal x = c[0], y = c[1];
      c[0] = cs * x - sn * y;
      c[1] = sn * x + cs * y;
    }
    for (PetscInt d = 0; d < s->dim; d++) c[d] += t[d];
    PetscCall(GeomSphere(s->dim, c, scale * s->r, s));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (PetscInt i = 0; i < s->nv; i++) {
    const PetscReal x = scale * s->v[2 * i], y = scale * s->v[2 * i + 1];
    s->v[2 * i]     = cs * x - sn * y + t[0];
    s->v[2 * i + 1] = sn * x + cs * y + t[1];
  }
  PolygonBox(s);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomDestroy(GeomShape *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(s->v));
  if (s->mesh) PetscCall(GeomMeshDestroy(s->mesh));
  PetscCall(PetscFree(s->mesh));
  s->nv = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Winding number of the polygon about x (Sunday 2001): non-zero inside, for either orientation. */
static PetscInt Winding(const GeomShape *s, const PetscReal x[])
{
  PetscInt w = 0;
  for (PetscInt i = 0; i < s->nv; i++) {
    const PetscReal *a = s->v + 2 * i, *b = s->v + 2 * ((i + 1) % s->nv);
    if (a[1] <= x[1]) {
      if (b[1] > x[1] && Orient(a, b, x) > 0) w++;
    } else if (b[1] <= x[1] && Orient(a, b, x) < 0) w--;
  }
  return w;
}

PetscBool GeomInside(const GeomShape *s, const PetscReal x[])
{
  if (s->type == GEOM_POLYGON) return (PetscBool)(Winding(s, x) != 0);
  if (s->type == GEOM_MESH) return (PetscBool)(GeomMeshDistance(s->mesh, x, 0, NULL, NULL) > 0 && GeomMeshInside(s->mesh, x));
  return (PetscBool)(GeomSignedDistance(s, x) < 0);
}

/* The polygon's point closest to x: its squared distance, the point q and the edge it lies on. */
static PetscReal PolygonClosest(const GeomShape *s, const PetscReal x[], PetscReal q[], PetscInt *edge)
{
  PetscReal best = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < s->nv; i++) {
    const PetscReal *a = s->v + 2 * i, *b = s->v + 2 * ((i + 1) % s->nv);
    PetscReal        e[2] = {b[0] - a[0], b[1] - a[1]}, ee = e[0] * e[0] + e[1] * e[1], t, p[2], d2;
    t    = PetscClipInterval(((x[0] - a[0]) * e[0] + (x[1] - a[1]) * e[1]) / ee, 0, 1);
    p[0] = a[0] + t * e[0];
    p[1] = a[1] + t * e[1];
    d2   = (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]);
    if (d2 < best) { best = d2; q[0] = p[0]; q[1] = p[1]; *edge = i; }
  }
  return best;
}

PetscReal GeomSignedDistanceNear(const GeomShape *s, const PetscReal x[], PetscReal dmax)
{
  if (s->type == GEOM_MESH) {
    const PetscReal d = GeomMeshDistance(s->mesh, x, dmax, NULL, NULL);
    return d > 0 && GeomMeshInside(s->mesh, x) ? -d : d; /* on the surface: 0 */
  }
  return GeomSignedDistance(s, x);
}

PetscReal GeomSignedDistance(const GeomShape *s, const PetscReal x[])
{
  if (s->type == GEOM_MESH) return GeomSignedDistanceNear(s, x, PETSC_MAX_REAL);
  if (s->type == GEOM_SPHERE) {
    PetscReal r2 = 0;
    for (PetscInt d = 0; d < s->dim; d++) r2 += (x[d] - s->c[d]) * (x[d] - s->c[d]);
    return PetscSqrtReal(r2) - s->r;
  } else {
    PetscReal q[2];
    PetscInt  e;
    PetscReal d = PetscSqrtReal(PolygonClosest(s, x, q, &e));
    return Winding(s, x) ? -d : d;
  }
}

PetscReal GeomNormal(const GeomShape *s, const PetscReal x[], PetscReal n[])
{
  PetscReal q[3] = {0, 0, 0}, dist, sd, len = 0;
  PetscInt  e = 0;
  if (s->type == GEOM_SPHERE) {
    for (PetscInt d = 0; d < s->dim; d++) q[d] = s->c[d];
    sd = GeomSignedDistance(s, x);
    for (PetscInt d = 0; d < s->dim; d++) { n[d] = x[d] - q[d]; len += n[d] * n[d]; }
    len = PetscSqrtReal(len);
    if (len > 0)
      for (PetscInt d = 0; d < s->dim; d++) n[d] /= len;
    else { /* the centre: any direction */
      for (PetscInt d = 0; d < s->dim; d++) n[d] = 0;
      n[0] = 1;
    }
    return sd;
  }
  if (s->type == GEOM_MESH) {
    const PetscReal o = GeomMeshVolume(s->mesh) > 0 ? 1 : -1; /* the triangles' orientation */
    dist = GeomMeshDistance(s->mesh, x, PETSC_MAX_REAL, q, &e);
    sd   = dist > 0 && GeomMeshInside(s->mesh, x) ? -dist : dist;
    if (dist > 1e-12 * (s->hi[0] - s->lo[0] + s->hi[1] - s->lo[1] + s->hi[2] - s->lo[2])) {
      for (PetscInt d = 0; d < 3; d++) n[d] = (sd < 0 ? -1 : 1) * (x[d] - q[d]) / dist;
    } else {
      GeomMeshTriangleNormal(s->mesh, e, n);
      for (PetscInt d = 0; d < 3; d++) n[d] *= o;
    }
    return sd;
  }
  dist = PetscSqrtReal(PolygonClosest(s, x, q, &e));
  sd   = Winding(s, x) ? -dist : dist;
  if (dist > 1e-12 * (s->hi[0] - s->lo[0] + s->hi[1] - s->lo[1])) { /* along the shortest path, outwards */
    const PetscReal sg = sd < 0 ? -1 : 1;
    n[0] = sg * (x[0] - q[0]) / dist;
    n[1] = sg * (x[1] - q[1]) / dist;
    return sd;
  }
  { /* on the surface: the edge's outward normal (mean of both edges' at a vertex) */
    const PetscReal  o = Area2(s->nv, s->v) > 0 ? 1 : -1;
    PetscInt         edges[2] = {e, e}, ne = 1;
    const PetscReal *a = s->v + 2 * e, *b = s->v + 2 * ((e + 1) % s->nv);
    if (x[0] == a[0] && x[1] == a[1]) { edges[1] = (e + s->nv - 1) % s->nv; ne = 2; }
    else if (x[0] == b[0] && x[1] == b[1]) { edges[1] = (e + 1) % s->nv; ne = 2; }
    n[0] = n[1] = 0;
    for (PetscInt k = 0; k < ne; k++) {
      const PetscReal *p = s->v + 2 * edges[k], *r = s->v + 2 * ((edges[k] + 1) % s->nv);
      PetscReal        t[2] = {r[0] - p[0], r[1] - p[1]}, l = PetscSqrtReal(t[0] * t[0] + t[1] * t[1]);
      n[0] += o * t[1] / l;
      n[1] -= o * t[0] / l;
    }
    len  = PetscSqrtReal(n[0] * n[0] + n[1] * n[1]);
    n[0] /= len;
    n[1] /= len;
  }
  return sd;
}

PetscReal GeomMeasure(const GeomShape *s)
{
  if (s->type == GEOM_SPHERE) return s->dim == 3 ? 4.0 / 3.0 * PETSC_PI * s->r * s->r * s->r : PETSC_PI * s->r * s->r;
  if (s->type == GEOM_MESH) return PetscAbsReal(GeomMeshVolume(s->mesh));
  return 0.5 * PetscAbsReal(Area2(s->nv, s->v));
}
