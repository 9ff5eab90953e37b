/* Geometry (base/geometry.h): signed distances, inside tests and normals of a circle, a sphere and
 * closed polygons of both orientations, convex and not; a 720-gon against the circle it is inscribed
 * in; the normal against the signed distance's finite-difference gradient; areas by lattice counts;
 * scale, rotation and translation; the polygons that are refused (too few vertices, a repeated
 * vertex, crossing or touching edges, an edge folding back, zero area). */
#include "base/geometry.h"

#define CHECK(cond, ...) PetscCheck(cond, PETSC_COMM_SELF, PETSC_ERR_PLIB, __VA_ARGS__)

static PetscErrorCode CheckSpheres(void)
{
  GeomShape       c, s;
  const PetscReal c2[2] = {1, 2}, c3[3] = {1, 2, 3};
  PetscReal       n[3];
  PetscFunctionBeginUser;
  PetscCall(GeomSphere(2, c2, 0.5, &c));
  CHECK(PetscAbsReal(GeomSignedDistance(&c, (PetscReal[]){1, 2}) + 0.5) < 1e-15, "circle: centre");
  CHECK(PetscAbsReal(GeomSignedDistance(&c, (PetscReal[]){4, 6}) - 4.5) < 1e-14, "circle: outside");
  CHECK(GeomInside(&c, (PetscReal[]){1.3, 2.3}) && !GeomInside(&c, (PetscReal[]){1.4, 2.4}), "circle: inside test");
  CHECK(PetscAbsReal(GeomNormal(&c, (PetscReal[]){1, 1.7}, n) + 0.2) < 1e-15 && n[0] == 0 && n[1] == -1, "circle: normal");
  CHECK(PetscAbsReal(GeomMeasure(&c) - PETSC_PI * 0.25) < 1e-15, "circle: area");
  PetscCall(GeomSphere(3, c3, 2, &s));
  CHECK(PetscAbsReal(GeomSignedDistance(&s, (PetscReal[]){1, 2, 0}) - 1) < 1e-15, "sphere: distance");
  CHECK(PetscAbsReal(GeomNormal(&s, (PetscReal[]){1, 3, 3}, n) + 1) < 1e-15 && n[0] == 0 && n[1] == 1 && n[2] == 0, "sphere: normal");
  CHECK(!GeomInside(&s, (PetscReal[]){3.1, 2, 3}) && GeomInside(&s, (PetscReal[]){2.9, 2, 3}), "sphere: inside test");
  PetscCall(GeomTransform(&s, 2, 0, (PetscReal[]){1, 0, 0}));
  CHECK(s.r == 4 && s.c[0] == 3 && s.c[1] == 4 && s.c[2] == 6, "sphere: transform");
  PetscCall(GeomTransform(&c, 1, PETSC_PI / 2, (PetscReal[]){0, 0}));
  CHECK(PetscAbsReal(c.c[0] + 2) < 1e-15 && PetscAbsReal(c.c[1] - 1) < 1e-15, "circle: rotation about the origin");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The lattice points of spacing h in the shape's bounding box that are inside, times h^2. */
static PetscReal LatticeArea(const GeomShape *s, PetscReal h)
{
  PetscReal a = 0;
  for (PetscReal x = s->lo[0] + h / 2; x < s->hi[0]; x += h)
    for (PetscReal y = s->lo[1] + h / 2; y < s->hi[1]; y += h) a += GeomInside(s, (PetscReal[]){x, y}) ? h * h : 0;
  return a;
}

static PetscErrorCode CheckPolygons(void)
{
  /* an L: the unit square less its upper right quarter, counter-clockwise; the same clockwise */
  const PetscReal L[12] = {0, 0, 1, 0, 1, 0.5, 0.5, 0.5, 0.5, 1, 0, 1};
  PetscReal       Lcw[12], n[2];
  GeomShape       p, q;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 6; i++) { Lcw[2 * i] = L[2 * (5 - i)]; Lcw[2 * i + 1] = L[2 * (5 - i) + 1]; }
  PetscCall(GeomPolygon(6, L, &p));
  PetscCall(GeomPolygon(6, Lcw, &q));
  for (PetscInt k = 0; k < 2; k++) {
    const GeomShape *s = k ? &q : &p;
    CHECK(PetscAbsReal(GeomMeasure(s) - 0.75) < 1e-15, "L: area %g", (double)GeomMeasure(s));
    CHECK(PetscAbsReal(LatticeArea(s, 0.01) - 0.75) < 1e-9, "L: lattice area %g", (double)LatticeArea(s, 0.01));
    CHECK(GeomInside(s, (PetscReal[]){0.25, 0.75}) && !GeomInside(s, (PetscReal[]){0.75, 0.75}) && !GeomInside(s, (PetscReal[]){-0.1, 0.5}), "L: inside test");
    CHECK(PetscAbsReal(GeomSignedDistance(s, (PetscReal[]){0.25, 0.25}) + 0.25) < 1e-15, "L: distance inside");
    CHECK(PetscAbsReal(GeomSignedDistance(s, (PetscReal[]){0.4, 0.7}) + 0.1) < 1e-15, "L: distance to the notch's edge");
    CHECK(PetscAbsReal(GeomSignedDistance(s, (PetscReal[]){0.8, 0.9}) - 0.3) < 1e-15, "L: distance in the notch");
    CHECK(PetscAbsReal(GeomSignedDistance(s, (PetscReal[]){2, 0.25}) - 1) < 1e-15, "L: distance outside");
    CHECK(PetscAbsReal(GeomNormal(s, (PetscReal[]){0.5, 0}, n)) < 1e-15 && n[0] == 0 && n[1] == -1, "L: normal on the floor (%g, %g)", (double)n[0], (double)n[1]);
    CHECK(GeomNormal(s, (PetscReal[]){0.5, 0.5}, n) == 0 && PetscAbsReal(n[0] - n[1]) < 1e-15 && PetscAbsReal(n[0] - PetscSqrtReal(0.5)) < 1e-15, "L: normal at the re-entrant vertex (%g, %g)", (double)n[0], (double)n[1]);
  }
  PetscCall(GeomDestroy(&p));
  PetscCall(GeomDestroy(&q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A 720-gon inscribed in the unit circle: its signed distance is the circle's to within 1 - cos(pi / 720) < 1e-5,
 * and its normal agrees with the gradient of its signed distance (central differences) away from the vertices. */
static PetscErrorCode CheckRoundPolygon(void)
{
  const PetscInt  nv = 720;
  PetscReal      *xy, worst = 0, worst_n = 0;
  GeomShape       p, c;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 * nv, &xy));
  for (PetscInt i = 0; i < nv; i++) { xy[2 * i] = PetscCosReal(2 * PETSC_PI * i / nv); xy[2 * i + 1] = PetscSinReal(2 * PETSC_PI * i / nv); }
  PetscCall(GeomPolygon(nv, xy, &p));
  PetscCall(GeomSphere(2, (PetscReal[]){0, 0}, 1, &c));
  for (PetscInt k = 0; k < 2000; k++) {
    const PetscReal r = 0.05 + 1.9 * ((k * 7919) % 2000) / 2000.0, t = 2 * PETSC_PI * ((k * 104729) % 2000 + 0.37) / 2000.0, e = 1e-7;
    PetscReal       x[2] = {r * PetscCosReal(t), r * PetscSinReal(t)}, n[2], g[2];
    worst = PetscMax(worst, PetscAbsReal(GeomSignedDistance(&p, x) - GeomSignedDistance(&c, x)));
    (void)GeomNormal(&p, x, n);
    for (PetscInt d = 0; d < 2; d++) {
      PetscReal xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
      xp[d] += e; xm[d] -= e;
      g[d] = (GeomSignedDistance(&p, xp) - GeomSignedDistance(&p, xm)) / (2 * e);
    }
    if (PetscAbsReal(r - 1) > 1e-3) worst_n = PetscMax(worst_n, PetscAbsReal(g[0] - n[0]) + PetscAbsReal(g[1] - n[1]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "720-gon against its circle: signed distance within %.2e (bound %.2e), normal against the distance's gradient within %.1e\n", (double)worst, (double)(1 - PetscCosReal(PETSC_PI / nv)), (double)worst_n));
  CHECK(worst <= 1 - PetscCosReal(PETSC_PI / nv) + 1e-12 && worst_n < 1e-6, "720-gon: distance %g, normal %g", (double)worst, (double)worst_n);
  /* scaled by 2, turned by a quarter, moved by (3, 0): the area is 4 x, the point (3, 1.9) inside */
  PetscCall(GeomTransform(&p, 2, PETSC_PI / 2, (PetscReal[]){3, 0}));
  CHECK(PetscAbsReal(GeomMeasure(&p) - 4 * 0.5 * nv * PetscSinReal(2 * PETSC_PI / nv)) < 1e-12 && GeomInside(&p, (PetscReal[]){3, 1.99}) && !GeomInside(&p, (PetscReal[]){0.99, 0}), "transformed 720-gon");
  PetscCall(GeomDestroy(&p));
  PetscCall(PetscFree(xy));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckFaults(void)
{
  struct {
    PetscInt  n;
    PetscReal xy[10];
    GeomFault want;
  } bad[] = {
    {2, {0, 0, 1, 0}, GEOM_FEW_VERTICES},
    {4, {0, 0, 1, 0, 1, 0, 0, 1}, GEOM_REPEATED_VERTEX},
    {4, {0, 0, 1, 1, 1, 0, 0, 1}, GEOM_SELF_INTERSECTING},          /* a bow tie */
    {5, {0, 0, 2, 0, 2, 2, 1, 0, 0, 2}, GEOM_SELF_INTERSECTING},    /* a vertex on another edge */
    {3, {0, 0, 1, 0, 2, 0}, GEOM_SELF_INTERSECTING},                /* collinear: the last edge runs back over the others */
    {4, {0, 0, 2, 0, 1, 0, 1, 1}, GEOM_SELF_INTERSECTING},          /* an edge folding back */
    {4, {0, 0, 1, 0, 1, 1, 0, 1}, GEOM_OK},
  };
  PetscFunctionBeginUser;
  for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
    PetscInt  e[2];
    GeomFault f = GeomPolygonCheck(bad[k].n, bad[k].xy, e);
    CHECK(f == bad[k].want, "polygon %d: %s, expected %s", (int)k, GeomFaults[f], GeomFaults[bad[k].want]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CheckSpheres());
  PetscCall(CheckPolygons());
  PetscCall(CheckRoundPolygon());
  PetscCall(CheckFaults());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_geometry: ok\n"));
  PetscCall(PetscFinalize());
  return 0;
}
