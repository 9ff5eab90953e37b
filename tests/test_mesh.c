/* Triangulated surfaces (base/mesh.h, GEOM_MESH of base/geometry.h): a unit cube (every lattice point
 * of a grid that puts points on its faces' diagonals, edges and corners in projection: inside, and the
 * signed distance against the box's exact one), a UV sphere of 64 x 32 against the sphere it is
 * inscribed in, the volume, the normals, a transform; STL files written here, binary and ASCII, read
 * back; zero-area triangles; an open cube (3 open edges), a truncated binary file, a missing file and an ASCII facet of two
 * vertices refused. */
#include "base/geometry.h"
#include <stdio.h>
#include <unistd.h>

#define CHECK(cond, ...) PetscCheck(cond, PETSC_COMM_SELF, PETSC_ERR_PLIB, __VA_ARGS__)

/* The 12 triangles of the box lo..hi, facing outwards. */
static void Cube(const PetscReal lo[], const PetscReal hi[], PetscReal t[108])
{
  const PetscInt q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  PetscReal      v[8][3];
  PetscInt       n = 0;
  for (PetscInt k = 0; k < 8; k++) { v[k][0] = k & 1 ? hi[0] : lo[0]; v[k][1] = k & 2 ? hi[1] : lo[1]; v[k][2] = k & 4 ? hi[2] : lo[2]; }
  for (PetscInt f = 0; f < 6; f++) {
    const PetscInt tri[2][3] = {{q[f][0], q[f][1], q[f][2]}, {q[f][0], q[f][2], q[f][3]}};
    for (PetscInt s = 0; s < 2; s++)
      for (PetscInt j = 0; j < 3; j++)
        for (PetscInt d = 0; d < 3; d++) t[n++] = v[tri[s][j]][d];
  }
}

/* The signed distance to the box 0..1 in each direction. */
static PetscReal BoxSD(const PetscReal x[])
{
  PetscReal out = 0, in = PETSC_MAX_REAL;
  for (PetscInt d = 0; d < 3; d++) {
    const PetscReal e = PetscMax(-x[d], x[d] - 1);
    if (e > 0) out += e * e;
    in = PetscMin(in, PetscMin(x[d], 1 - x[d]));
  }
  return out > 0 ? PetscSqrtReal(out) : (in > 0 ? -in : 0);
}

static PetscErrorCode CheckCube(void)
{
  GeomShape s;
  GeomMesh *m;
  PetscReal t[108], n[3];
  PetscInt  open, wrong = 0;
  PetscFunctionBeginUser;
  Cube((PetscReal[]){0, 0, 0}, (PetscReal[]){1, 1, 1}, t);
  PetscCall(PetscMemzero(&s, sizeof(s)));
  s.type = GEOM_MESH;
  s.dim  = 3;
  PetscCall(PetscNew(&s.mesh));
  m = s.mesh;
  PetscCall(GeomMeshCreate(12, t, m, &open));
  CHECK(open == 0, "cube: %d open edges", (int)open);
  for (PetscInt d = 0; d < 3; d++) { s.lo[d] = m->lo[d]; s.hi[d] = m->hi[d]; }
  CHECK(PetscAbsReal(GeomMeasure(&s) - 1) < 1e-15, "cube: volume %g", (double)GeomMeasure(&s));
  /* points at multiples of 1/8 from -1/4 to 5/4: on the faces' diagonals (x = y), edges and corners */
  for (PetscInt i = -2; i <= 10; i++)
    for (PetscInt j = -2; j <= 10; j++)
      for (PetscInt k = -2; k <= 10; k++) {
        const PetscReal x[3] = {i / 8.0, j / 8.0, k / 8.0}, want = BoxSD(x), sd = GeomSignedDistance(&s, x);
        if (PetscAbsReal(sd - want) > 1e-15) wrong++;
        if (want < 0 && !GeomMeshInside(m, x)) wrong++;
        if (want > 0 && GeomMeshInside(m, x)) wrong++;
      }
  CHECK(wrong == 0, "cube: %d of 2197 lattice points with a wrong signed distance or inside test", (int)wrong);
  CHECK(PetscAbsReal(GeomNormal(&s, (PetscReal[]){0.5, 0.5, 0.9}, n) + 0.1) < 1e-15 && n[2] == 1, "cube: normal inside, near the top");
  { PetscReal sd = GeomNormal(&s, (PetscReal[]){0.3, 0.6, 0}, n); CHECK(PetscAbsReal(sd) < 1e-15 && n[2] == -1, "cube: normal on the bottom face: %g, %g %g %g", (double)sd, (double)n[0], (double)n[1], (double)n[2]); }
  CHECK(PetscAbsReal(GeomSignedDistanceNear(&s, (PetscReal[]){0.5, 0.5, 0.5}, 0.1) + 0.5) < 1e-15, "cube: bounded distance");
  PetscCall(GeomTransform3(&s, 2, (PetscReal[]){0, 0, PETSC_PI / 2}, (PetscReal[]){1, 0, 0}));
  CHECK(PetscAbsReal(s.lo[0] + 1) < 1e-15 && PetscAbsReal(s.hi[0] - 1) < 1e-15 && PetscAbsReal(s.hi[1] - 2) < 1e-15 && PetscAbsReal(s.hi[2] - 2) < 1e-15, "cube: transform");
  CHECK(GeomInside(&s, (PetscReal[]){0, 1, 1}) && !GeomInside(&s, (PetscReal[]){1.1, 1, 1}), "cube: inside after the transform");
  PetscCall(GeomDestroy(&s));
  t[107] = 0.5; /* a vertex moved: the last triangle no longer shares its edges */
  {
    GeomMesh o;
    PetscCall(GeomMeshCreate(11, t, &o, &open));
    CHECK(open == 3, "open cube: %d open edges, not 3", (int)open);
    PetscCall(GeomMeshDestroy(&o));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Triangles of zero area, as exporters leave them (slivers along an edge): the cube with two more,
 * a - m - c along its top face's diagonal, once each way (the surface stays closed), must give the
 * same inside test and signed distance at every lattice point as the cube alone. */
static PetscErrorCode CheckDegenerate(void)
{
  GeomShape s;
  PetscReal t[126];
  PetscInt  open, wrong = 0;
  const PetscReal a[3] = {0, 0, 1}, m[3] = {0.5, 0.5, 1}, c[3] = {1, 1, 1};
  PetscFunctionBeginUser;
  Cube((PetscReal[]){0, 0, 0}, (PetscReal[]){1, 1, 1}, t);
  for (PetscInt d = 0; d < 3; d++) {
    t[108 + d] = a[d]; t[111 + d] = m[d]; t[114 + d] = c[d];
    t[117 + d] = a[d]; t[120 + d] = c[d]; t[123 + d] = m[d];
  }
  PetscCall(PetscMemzero(&s, sizeof(s)));
  s.type = GEOM_MESH;
  s.dim  = 3;
  PetscCall(PetscNew(&s.mesh));
  PetscCall(GeomMeshCreate(14, t, s.mesh, &open));
  CHECK(open == 0, "cube with slivers: %d open edges", (int)open);
  for (PetscInt d = 0; d < 3; d++) { s.lo[d] = s.mesh->lo[d]; s.hi[d] = s.mesh->hi[d]; }
  for (PetscInt i = -2; i <= 10; i++)
    for (PetscInt j = -2; j <= 10; j++)
      for (PetscInt k = -2; k <= 10; k++) {
        const PetscReal x[3] = {i / 8.0, j / 8.0, k / 8.0}, want = BoxSD(x), sd = GeomSignedDistance(&s, x);
        if (!(PetscAbsReal(sd - want) <= 1e-15)) wrong++; /* NaN counts as wrong */
        if (want < 0 && !GeomMeshInside(s.mesh, x)) wrong++;
        if (want > 0 && GeomMeshInside(s.mesh, x)) wrong++;
      }
  CHECK(wrong == 0, "cube with slivers: %d of 2197 lattice points with a wrong signed distance or inside test", (int)wrong);
  CHECK(PetscAbsReal(GeomMeasure(&s) - 1) < 1e-15, "cube with slivers: volume %g", (double)GeomMeasure(&s));
  PetscCall(GeomDestroy(&s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A UV sphere of radius r: nl longitudes, nb latitude bands, poles as single vertices. */
static PetscErrorCode UVSphere(PetscReal r, PetscInt nl, PetscInt nb, PetscInt *nt, PetscReal **t)
{
  PetscReal (*v)[3];
  PetscInt  k = 0, nv = 2 + nl * (nb - 1);
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nv, &v));
  PetscCall(PetscMalloc1(9 * 2 * nl * (nb - 1), t));
  v[0][0] = v[0][1] = 0; v[0][2] = r;
  v[1][0] = v[1][1] = 0; v[1][2] = -r;
  for (PetscInt b = 1; b < nb; b++)
    for (PetscInt l = 0; l < nl; l++) {
      const PetscReal th = PETSC_PI * b / nb, ph = 2 * PETSC_PI * l / nl;
      PetscReal      *p  = v[2 + (b - 1) * nl + l];
      p[0] = r * PetscSinReal(th) * PetscCosReal(ph); p[1] = r * PetscSinReal(th) * PetscSinReal(ph); p[2] = r * PetscCosReal(th);
    }
  *nt = 0;
  for (PetscInt b = 0; b < nb; b++)
    for (PetscInt l = 0; l < nl; l++) {
      const PetscInt l1 = (l + 1) % nl;
      const PetscInt a = b == 0 ? 0 : 2 + (b - 1) * nl + l, a1 = b == 0 ? 0 : 2 + (b - 1) * nl + l1;
      const PetscInt c = b == nb - 1 ? 1 : 2 + b * nl + l, c1 = b == nb - 1 ? 1 : 2 + b * nl + l1;
      const PetscInt tri[2][3] = {{a, c, c1}, {a, c1, a1}};
      for (PetscInt s = 0; s < 2; s++) {
        if ((s == 1 && b == 0) || (s == 0 && b == nb - 1)) continue; /* the poles' fans */
        for (PetscInt j = 0; j < 3; j++)
          for (PetscInt d = 0; d < 3; d++) (*t)[k++] = v[tri[s][j]][d];
        (*nt)++;
      }
    }
  PetscCall(PetscFree(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckSphere(void)
{
  GeomMesh   m;
  PetscReal *t, err = 0, vol;
  PetscInt   nt = 0, open, wrong = 0;
  const PetscReal chord = 1 - PetscCosReal(PETSC_PI / 32); /* the sagitta of the coarser direction */
  PetscFunctionBeginUser;
  PetscCall(UVSphere(1, 64, 32, &nt, &t));
  PetscCall(GeomMeshCreate(nt, t, &m, &open));
  CHECK(open == 0, "sphere: %d open edges", (int)open);
  for (PetscInt i = 0; i < 24; i++)
    for (PetscInt j = 0; j < 24; j++)
      for (PetscInt k = 0; k < 24; k++) {
        const PetscReal x[3] = {-1.3 + 2.6 * (i + 0.37) / 24, -1.3 + 2.6 * (j + 0.61) / 24, -1.3 + 2.6 * (k + 0.23) / 24};
        const PetscReal rr = PetscSqrtReal(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), d = GeomMeshDistance(&m, x, PETSC_MAX_REAL, NULL, NULL);
        if (rr < 1 - 2 * chord && !GeomMeshInside(&m, x)) wrong++;
        if (rr > 1 && GeomMeshInside(&m, x)) wrong++;
        err = PetscMax(err, PetscAbsReal(d - PetscAbsReal(rr - 1)));
      }
  vol = GeomMeshVolume(&m);
  CHECK(wrong == 0, "sphere: %d points on the wrong side", (int)wrong);
  CHECK(err <= 2 * chord, "sphere: distance off by %g (chord error %g)", (double)err, (double)chord);
  CHECK(PetscAbsReal(vol / (4 * PETSC_PI / 3) - 1) < 0.01, "sphere: volume %g", (double)vol);
  PetscCall(GeomMeshDestroy(&m));
  PetscCall(PetscFree(t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether reading file fails (with the error handler that only returns). */
static PetscErrorCode ReadFails(const char *file, PetscBool *fails)
{
  GeomMesh       m;
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = GeomMeshReadSTL(PETSC_COMM_SELF, "-stl_1", file, &m);
  PetscCall(PetscPopErrorHandler());
  *fails = (PetscBool)(ierr != 0);
  if (!ierr) PetscCall(GeomMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* nt triangles t as an ASCII STL file. */
static PetscErrorCode WriteAscii(const char *file, PetscInt nt, const PetscReal t[])
{
  FILE *f = fopen(file, "w");
  PetscFunctionBeginUser;
  CHECK(f, "cannot write %s", file);
  fprintf(f, "solid cube\n");
  for (PetscInt k = 0; k < nt; k++) {
    fprintf(f, " facet normal 0 0 0\n  outer loop\n");
    for (PetscInt j = 0; j < 3; j++) fprintf(f, "   vertex %.17g %.17g %.17g\n", (double)t[9 * k + 3 * j], (double)t[9 * k + 3 * j + 1], (double)t[9 * k + 3 * j + 2]);
    fprintf(f, "  endloop\n endfacet\n");
  }
  fprintf(f, "endsolid cube\n");
  fclose(f);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckFiles(void)
{
  PetscReal t[108];
  char      bin[PETSC_MAX_PATH_LEN], asc[PETSC_MAX_PATH_LEN], bad[PETSC_MAX_PATH_LEN];
  FILE     *f;
  GeomMesh  a, b;
  PetscBool fails;
  PetscFunctionBeginUser;
  Cube((PetscReal[]){0.25, 0, -1}, (PetscReal[]){1.5, 2, 0.125}, t); /* numbers exact in float32 */
  PetscCall(PetscSNPrintf(bin, sizeof(bin), "/tmp/test_mesh_%d_b.stl", (int)getpid()));
  PetscCall(PetscSNPrintf(asc, sizeof(asc), "/tmp/test_mesh_%d_a.stl", (int)getpid()));
  PetscCall(PetscSNPrintf(bad, sizeof(bad), "/tmp/test_mesh_%d_x.stl", (int)getpid()));
  f = fopen(bin, "wb");
  CHECK(f, "cannot write %s", bin);
  {
    char         head[80] = "solid (a binary file may begin so)";
    unsigned int n = 12;
    fwrite(head, 1, 80, f);
    fwrite(&n, 4, 1, f);
    for (PetscInt k = 0; k < 12; k++) {
      float v[12] = {0};
      for (PetscInt j = 0; j < 9; j++) v[3 + j] = (float)t[9 * k + j];
      fwrite(v, 4, 12, f);
      fwrite("\0\0", 1, 2, f);
    }
  }
  fclose(f);
  PetscCall(WriteAscii(asc, 12, t));
  PetscCall(GeomMeshReadSTL(PETSC_COMM_SELF, "-stl_1", bin, &a));
  PetscCall(GeomMeshReadSTL(PETSC_COMM_SELF, "-stl_1", asc, &b));
  CHECK(a.nt == 12 && b.nt == 12, "read %d and %d triangles, not 12", (int)a.nt, (int)b.nt);
  for (PetscInt j = 0; j < 108; j++) CHECK(a.t[j] == t[j] && b.t[j] == t[j], "number %d read as %g and %g, not %g", (int)j, (double)a.t[j], (double)b.t[j], (double)t[j]);
  CHECK(PetscAbsReal(GeomMeshVolume(&a) - 1.25 * 2 * 1.125) < 1e-14, "volume from the file");
  PetscCall(GeomMeshDestroy(&a));
  PetscCall(GeomMeshDestroy(&b));
  PetscCall(ReadFails("/nonexistent/cube.stl", &fails));
  CHECK(fails, "a missing file is read");
  CHECK(!truncate(bin, 84 + 50 * 11 + 20), "cannot truncate %s", bin);
  PetscCall(ReadFails(bin, &fails));
  CHECK(fails, "a truncated binary file is read");
  f = fopen(bad, "w");
  fprintf(f, "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n  endloop\n endfacet\nendsolid x\n");
  fclose(f);
  PetscCall(ReadFails(bad, &fails));
  CHECK(fails, "a facet of two vertices is read");
  PetscCall(WriteAscii(bad, 11, t)); /* the cube without its last triangle: open */
  PetscCall(ReadFails(bad, &fails));
  CHECK(fails, "an open surface is read");
  remove(bin);
  remove(asc);
  remove(bad);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CheckCube());
  PetscCall(CheckDegenerate());
  PetscCall(CheckSphere());
  PetscCall(CheckFiles());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_mesh: ok\n"));
  PetscCall(PetscFinalize());
  return 0;
}
