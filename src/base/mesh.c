/* Closed triangulated surfaces from STL files (mesh.h; docs/geometry.md, "STL surfaces"). */
#include "base/mesh.h"
#include <stdio.h>
#include <string.h>
#include <ctype.h>

#define MESH_GRID_MAX 128 /* cells per direction at most */

/* ---- reading ---- */

static PetscErrorCode Grow(PetscReal **t, PetscInt *cap, PetscInt need)
{
  PetscFunctionBeginUser;
  if (need <= *cap) PetscFunctionReturn(PETSC_SUCCESS);
  *cap = PetscMax(2 * *cap, need + 64);
  PetscCall(PetscRealloc(sizeof(PetscReal) * 9 * (size_t)*cap, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ASCII: the numbers after each "vertex", three to a facet; the keywords are otherwise not checked. */
static PetscErrorCode ReadAscii(MPI_Comm comm, const char *opt, const char *file, char *buf, PetscReal **t, PetscInt *nt)
{
  PetscInt cap = 0, nv = 0, line = 1;
  char    *c   = buf;
  PetscFunctionBeginUser;
  *nt = 0;
  while (*c) {
    char *w = c, *end;
    while (*c && !isspace((unsigned char)*c)) c++;
    if (c == w) { line += *c == '\n'; c++; continue; }
    if (c - w == 6 && !strncmp(w, "vertex", 6)) {
      PetscCall(Grow(t, &cap, *nt + 1));
      for (PetscInt d = 0; d < 3; d++) {
        double v = strtod(c, &end);
        PetscCheck(end != c && nv < 3, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s, line %d: %s", opt, file, (int)line, nv < 3 ? "a vertex needs three numbers x y z" : "a facet with more than three vertices");
        (*t)[9 * *nt + 3 * nv + d] = v;
        c = end;
      }
      nv++;
    } else if (c - w == 8 && !strncmp(w, "endfacet", 8)) {
      PetscCheck(nv == 3, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s, line %d: a facet with %d vertices, not 3", opt, file, (int)line, (int)nv);
      (*nt)++;
      nv = 0;
    }
  }
  PetscCheck(nv == 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s ends inside a facet (truncated?)", opt, file);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomMeshReadSTL(MPI_Comm comm, const char *opt, const char *file, GeomMesh *m)
{
  FILE         *f = fopen(file, "rb");
  long          size;
  char         *buf;
  PetscReal    *t  = NULL;
  PetscInt      nt = 0, open;
  unsigned int  count = 0;
  PetscBool     ascii;
  PetscFunctionBeginUser;
  PetscCheck(f, comm, PETSC_ERR_FILE_OPEN, "%s: the STL file %s cannot be opened", opt, file);
  fseek(f, 0, SEEK_END);
  size = ftell(f);
  fseek(f, 0, SEEK_SET);
  PetscCall(PetscMalloc1(size + 1, &buf));
  if (size > 0 && fread(buf, 1, (size_t)size, f) != (size_t)size) size = -1;
  fclose(f);
  if (size < 0) PetscCall(PetscFree(buf));
  PetscCheck(size >= 0, comm, PETSC_ERR_FILE_READ, "%s: %s cannot be read", opt, file);
  buf[size] = 0;
  if (size >= 84) memcpy(&count, buf + 80, 4); /* little-endian, as the format */
  if (size >= 84 && (long)count * 50 + 84 == size) ascii = PETSC_FALSE; /* a binary file may begin with "solid" too */
  else {
    const char *c = buf;
    while (*c && isspace((unsigned char)*c)) c++;
    ascii = (PetscBool)(!strncmp(c, "solid", 5) && strlen(buf) == (size_t)size); /* no NUL bytes */
  }
  if (!ascii) {
    if (size < 84) PetscCall(PetscFree(buf));
    PetscCheck(size >= 84, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is neither an ASCII STL (\"solid ...\") nor a binary one (%ld bytes, under the 84 of a binary header)", opt, file, size);
    if ((long)count * 50 + 84 != size) PetscCall(PetscFree(buf));
    PetscCheck((long)count * 50 + 84 == size, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is a binary STL of %u triangles by its header, which takes %ld bytes, but has %ld (truncated?)", opt, file, count, (long)count * 50 + 84, size);
    nt = (PetscInt)count;
    PetscCall(PetscMalloc1(9 * (size_t)PetscMax(nt, 1), &t));
    for (PetscInt k = 0; k < nt; k++)
      for (PetscInt j = 0; j < 9; j++) {
        float v;
        memcpy(&v, buf + 84 + 50 * k + 12 + 4 * j, 4); /* after the facet's normal */
        t[9 * k + j] = v;
      }
  } else {
    PetscErrorCode ierr = ReadAscii(comm, opt, file, buf, &t, &nt);
    if (ierr) { PetscCall(PetscFree(buf)); PetscCall(PetscFree(t)); }
    PetscCall(ierr);
  }
  PetscCall(PetscFree(buf));
  if (nt == 0) PetscCall(PetscFree(t));
  PetscCheck(nt > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has no triangles", opt, file);
  PetscCall(GeomMeshCreate(nt, t, m, &open));
  PetscCall(PetscFree(t));
  if (open) PetscCall(GeomMeshDestroy(m));
  PetscCheck(!open, comm, PETSC_ERR_ARG_WRONG, "%s: the surface in %s is not closed: %d open edges (used by one triangle, or an odd number): close it (every edge shared by two triangles)", opt, file, (int)open);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- closedness: vertices welded where their coordinates are equal, edges counted ---- */

typedef struct { PetscReal x[3]; PetscInt i; } Vtx;
typedef struct { PetscInt a, b; } Edge;

static int CmpVtx(const void *p, const void *q)
{
  const Vtx *u = (const Vtx *)p, *v = (const Vtx *)q;
  for (int d = 0; d < 3; d++)
    if (u->x[d] != v->x[d]) return u->x[d] < v->x[d] ? -1 : 1;
  return 0;
}

static int CmpEdge(const void *p, const void *q)
{
  const Edge *u = (const Edge *)p, *v = (const Edge *)q;
  if (u->a != v->a) return u->a < v->a ? -1 : 1;
  return u->b < v->b ? -1 : (u->b > v->b);
}

static PetscErrorCode OpenEdges(PetscInt nt, const PetscReal t[], PetscInt *open)
{
  Vtx      *v;
  Edge     *e;
  PetscInt *id, n = 3 * nt;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(n, &v, n, &e, n, &id));
  for (PetscInt k = 0; k < n; k++) {
    for (PetscInt d = 0; d < 3; d++) v[k].x[d] = t[3 * k + d];
    v[k].i = k;
  }
  qsort(v, (size_t)n, sizeof(Vtx), CmpVtx);
  for (PetscInt k = 0, w = -1; k < n; k++) {
    if (k == 0 || CmpVtx(&v[k - 1], &v[k])) w++;
    id[v[k].i] = w;
  }
  for (PetscInt k = 0; k < nt; k++)
    for (PetscInt j = 0; j < 3; j++) {
      PetscInt a = id[3 * k + j], b = id[3 * k + (j + 1) % 3];
      e[3 * k + j].a = PetscMin(a, b);
      e[3 * k + j].b = PetscMax(a, b);
    }
  qsort(e, (size_t)n, sizeof(Edge), CmpEdge);
  *open = 0;
  for (PetscInt k = 0; k < n;) {
    PetscInt j = k;
    while (j < n && !CmpEdge(&e[k], &e[j])) j++;
    if ((j - k) % 2) (*open)++;
    k = j;
  }
  PetscCall(PetscFree3(v, e, id));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- the grids ---- */

static PetscInt CellOf(const GeomMesh *m, PetscInt d, PetscReal x)
{
  PetscReal f = PetscFloorReal((x - m->g0[d]) / m->gh[d]);
  return f < 0 ? 0 : (f >= m->n[d] ? m->n[d] - 1 : (PetscInt)f);
}

/* The cells (dims 3) or columns (dims 2) each triangle's bounding box meets: CSR lists. */
static PetscErrorCode Bucket(GeomMesh *m, PetscInt dims, PetscInt **start, PetscInt **list)
{
  const PetscInt nc = m->n[0] * m->n[1] * (dims == 3 ? m->n[2] : 1);
  PetscInt      *fill;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nc + 1, start));
  PetscCall(PetscCalloc1(nc, &fill));
  for (PetscInt pass = 0; pass < 2; pass++) {
    for (PetscInt k = 0; k < m->nt; k++) {
      const PetscReal *p = m->t + 9 * k;
      PetscInt         lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
      for (PetscInt d = 0; d < dims; d++) {
        lo[d] = CellOf(m, d, PetscMin(p[d], PetscMin(p[3 + d], p[6 + d])));
        hi[d] = CellOf(m, d, PetscMax(p[d], PetscMax(p[3 + d], p[6 + d])));
      }
      for (PetscInt c2 = lo[2]; c2 <= hi[2]; c2++)
        for (PetscInt c1 = lo[1]; c1 <= hi[1]; c1++)
          for (PetscInt c0 = lo[0]; c0 <= hi[0]; c0++) {
            const PetscInt c = c0 + m->n[0] * (c1 + m->n[1] * c2);
            if (pass == 0) (*start)[c + 1]++;
            else (*list)[(*start)[c] + fill[c]++] = k;
          }
    }
    if (pass == 0) {
      for (PetscInt c = 0; c < nc; c++) (*start)[c + 1] += (*start)[c];
      PetscCall(PetscMalloc1(PetscMax((*start)[nc], 1), list));
    }
  }
  PetscCall(PetscFree(fill));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Bounding box, and cells of about one triangle each (at most MESH_GRID_MAX a direction). */
static PetscErrorCode Grids(GeomMesh *m)
{
  PetscReal ext[3], vol = 1, c;
  PetscFunctionBeginUser;
  PetscCall(PetscFree(m->cell));
  PetscCall(PetscFree(m->cells));
  PetscCall(PetscFree(m->col));
  PetscCall(PetscFree(m->cols));
  for (PetscInt d = 0; d < 3; d++) { m->lo[d] = PETSC_MAX_REAL; m->hi[d] = -PETSC_MAX_REAL; }
  for (PetscInt k = 0; k < 3 * m->nt; k++)
    for (PetscInt d = 0; d < 3; d++) { m->lo[d] = PetscMin(m->lo[d], m->t[3 * k + d]); m->hi[d] = PetscMax(m->hi[d], m->t[3 * k + d]); }
  for (PetscInt d = 0; d < 3; d++) { ext[d] = PetscMax(m->hi[d] - m->lo[d], 1e-12 * (1 + PetscAbsReal(m->lo[d]))); vol *= ext[d]; }
  c = PetscCbrtReal(vol / m->nt);
  for (PetscInt d = 0; d < 3; d++) {
    m->n[d]  = PetscMax(1, PetscMin(MESH_GRID_MAX, (PetscInt)PetscCeilReal(ext[d] / c)));
    m->gh[d] = ext[d] / m->n[d];
    m->g0[d] = m->lo[d];
  }
  PetscCall(Bucket(m, 3, &m->cell, &m->cells));
  PetscCall(Bucket(m, 2, &m->col, &m->cols));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomMeshCreate(PetscInt nt, const PetscReal t[], GeomMesh *m, PetscInt *open)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscCheck(nt > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "A mesh needs triangles");
  m->nt = nt;
  PetscCall(PetscMalloc1(9 * (size_t)nt, &m->t));
  PetscCall(PetscArraycpy(m->t, t, 9 * nt));
  PetscCall(OpenEdges(nt, t, open));
  PetscCall(Grids(m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomMeshTransform(GeomMesh *m, PetscReal scale, const PetscReal ang[3], const PetscReal t[3])
{
  PetscReal R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  PetscFunctionBeginUser;
  PetscCheck(scale > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "A mesh's scale %g must be > 0", (double)scale);
  for (PetscInt a = 0; a < 3; a++) { /* R = Rz Ry Rx: about x first */
    const PetscReal cs = PetscCosReal(ang[a]), sn = PetscSinReal(ang[a]);
    const PetscInt  i = (a + 1) % 3, j = (a + 2) % 3; /* the plane turned: y,z; z,x; x,y */
    for (PetscInt k = 0; k < 3; k++) {
      const PetscReal ri = R[i][k], rj = R[j][k];
      R[i][k] = cs * ri - sn * rj;
      R[j][k] = sn * ri + cs * rj;
    }
  }
  for (PetscInt k = 0; k < 3 * m->nt; k++) {
    PetscReal *x = m->t + 3 * k, y[3];
    for (PetscInt d = 0; d < 3; d++) y[d] = R[d][0] * scale * x[0] + R[d][1] * scale * x[1] + R[d][2] * scale * x[2] + t[d];
    for (PetscInt d = 0; d < 3; d++) x[d] = y[d];
  }
  PetscCall(Grids(m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomMeshDestroy(GeomMesh *m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(m->t));
  PetscCall(PetscFree(m->cell));
  PetscCall(PetscFree(m->cells));
  PetscCall(PetscFree(m->col));
  PetscCall(PetscFree(m->cols));
  PetscCall(PetscFree(m->dry));
  m->nt = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- queries ---- */

/* The edge function of p against the edge u -> v in the xy plane, computed from the edge's
 * lexicographically first end so that the two triangles sharing an edge get exactly opposite values. */
static PetscReal EdgeFn(const PetscReal u[], const PetscReal v[], const PetscReal p[])
{
  const PetscBool  swap = (PetscBool)(v[0] < u[0] || (v[0] == u[0] && v[1] < u[1]));
  const PetscReal *a = swap ? v : u, *b = swap ? u : v;
  const PetscReal  e = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  return swap ? -e : e;
}

/* Of an edge and its reverse exactly one owns the points on it (the top-left rule of rasterizers). */
static PetscBool Owns(const PetscReal u[], const PetscReal v[])
{
  return (PetscBool)(v[1] < u[1] || (v[1] == u[1] && v[0] > u[0]));
}

/* Whether the vertical ray from x upwards crosses triangle k strictly above x. */
static PetscBool Crosses(const GeomMesh *m, PetscInt k, const PetscReal x[])
{
  const PetscReal *a = m->t + 9 * k, *b = a + 3, *c = a + 6, *tmp;
  PetscReal        area = EdgeFn(a, b, c), w[3], z;
  if (area == 0) return PETSC_FALSE; /* vertical: its neighbours' edges decide */
  if (area < 0) { tmp = b; b = c; c = tmp; }
  w[0] = EdgeFn(b, c, x);
  w[1] = EdgeFn(c, a, x);
  w[2] = EdgeFn(a, b, x);
  if (w[0] < 0 || w[1] < 0 || w[2] < 0) return PETSC_FALSE;
  if ((w[0] == 0 && !Owns(b, c)) || (w[1] == 0 && !Owns(c, a)) || (w[2] == 0 && !Owns(a, b))) return PETSC_FALSE;
  z = (w[0] * a[2] + w[1] * b[2] + w[2] * c[2]) / (w[0] + w[1] + w[2]);
  return (PetscBool)(z > x[2]);
}

PetscBool GeomMeshInside(const GeomMesh *m, const PetscReal x[])
{
  PetscInt c, n = 0;
  for (PetscInt d = 0; d < 3; d++)
    if (x[d] < m->lo[d] || x[d] > m->hi[d]) return PETSC_FALSE;
  c = CellOf(m, 0, x[0]) + m->n[0] * CellOf(m, 1, x[1]);
  for (PetscInt j = m->col[c]; j < m->col[c + 1]; j++) n += Crosses(m, m->cols[j], x);
  return (PetscBool)(n % 2);
}

/* The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5). */
static void Closest(const PetscReal p[], const PetscReal a[], const PetscReal b[], const PetscReal c[], PetscReal q[])
{
  PetscReal ab[3], ac[3], ap[3], bp[3], cp[3], d1 = 0, d2 = 0, d3 = 0, d4 = 0, d5 = 0, d6 = 0, va, vb, vc, v, w, den;
  for (PetscInt d = 0; d < 3; d++) {
    ab[d] = b[d] - a[d]; ac[d] = c[d] - a[d]; ap[d] = p[d] - a[d]; bp[d] = p[d] - b[d]; cp[d] = p[d] - c[d];
    d1 += ab[d] * ap[d]; d2 += ac[d] * ap[d]; d3 += ab[d] * bp[d]; d4 += ac[d] * bp[d]; d5 += ab[d] * cp[d]; d6 += ac[d] * cp[d];
  }
  if (d1 <= 0 && d2 <= 0) { for (PetscInt d = 0; d < 3; d++) q[d] = a[d]; return; }
  if (d3 >= 0 && d4 <= d3) { for (PetscInt d = 0; d < 3; d++) q[d] = b[d]; return; }
  vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { v = d1 / (d1 - d3); for (PetscInt d = 0; d < 3; d++) q[d] = a[d] + v * ab[d]; return; }
  if (d6 >= 0 && d5 <= d6) { for (PetscInt d = 0; d < 3; d++) q[d] = c[d]; return; }
  vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { w = d2 / (d2 - d6); for (PetscInt d = 0; d < 3; d++) q[d] = a[d] + w * ac[d]; return; }
  va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) { w = (d4 - d3) / ((d4 - d3) + (d5 - d6)); for (PetscInt d = 0; d < 3; d++) q[d] = b[d] + w * (c[d] - b[d]); return; }
  den = 1 / (va + vb + vc);
  v   = vb * den;
  w   = vc * den;
  for (PetscInt d = 0; d < 3; d++) q[d] = a[d] + v * ab[d] + w * ac[d];
}

static PetscReal Distance(const GeomMesh *m, const PetscReal x[], PetscReal dmax, PetscReal q[], PetscInt *tri, PetscBool wet)
{
  const PetscReal hc = PetscMin(m->gh[0], PetscMin(m->gh[1], m->gh[2]));
  const PetscInt  rmax = PetscMax(m->n[0], PetscMax(m->n[1], m->n[2]));
  PetscInt        c0[3];
  PetscReal       best2 = PETSC_MAX_REAL;
  for (PetscInt d = 0; d < 3; d++) c0[d] = CellOf(m, d, x[d]);
  for (PetscInt r = 0; r <= rmax; r++) {
    PetscInt lo[3], hi[3], i[3];
    for (PetscInt d = 0; d < 3; d++) { lo[d] = PetscMax(0, c0[d] - r); hi[d] = PetscMin(m->n[d] - 1, c0[d] + r); }
    for (i[2] = lo[2]; i[2] <= hi[2]; i[2]++)
      for (i[1] = lo[1]; i[1] <= hi[1]; i[1]++)
        for (i[0] = lo[0]; i[0] <= hi[0]; i[0]++) {
          PetscInt c;
          if (PetscAbs(i[0] - c0[0]) < r && PetscAbs(i[1] - c0[1]) < r && PetscAbs(i[2] - c0[2]) < r) { i[0] = c0[0] + r - 1; continue; } /* the shell only */
          c = i[0] + m->n[0] * (i[1] + m->n[1] * i[2]);
          for (PetscInt j = m->cell[c]; j < m->cell[c + 1]; j++) {
            const PetscInt   k = m->cells[j];
            const PetscReal *a = m->t + 9 * k;
            PetscReal        p[3], d2 = 0;
            if (wet && m->dry && m->dry[k]) continue;
            Closest(x, a, a + 3, a + 6, p);
            for (PetscInt d = 0; d < 3; d++) d2 += (x[d] - p[d]) * (x[d] - p[d]);
            if (d2 < best2) {
              best2 = d2;
              if (q) for (PetscInt d = 0; d < 3; d++) q[d] = p[d];
              if (tri) *tri = k;
            }
          }
        }
    /* every triangle not yet seen lies in cells r + 1 or more away: at least r cells from x */
    if (best2 <= (r * hc) * (r * hc) || r * hc >= dmax) break;
  }
  return PetscSqrtReal(best2);
}

PetscReal GeomMeshDistance(const GeomMesh *m, const PetscReal x[], PetscReal dmax, PetscReal q[], PetscInt *tri)
{
  return Distance(m, x, dmax, q, tri, PETSC_FALSE);
}

PetscReal GeomMeshDistanceWet(const GeomMesh *m, const PetscReal x[], PetscReal dmax)
{
  return Distance(m, x, dmax, NULL, NULL, PETSC_TRUE);
}

PetscErrorCode GeomMeshSetDry(GeomMesh *m, PetscReal eps, PetscBool (*dry)(const PetscReal p[], void *ctx), void *ctx, PetscInt *ndry)
{
  const PetscReal o = GeomMeshVolume(m) > 0 ? 1 : -1; /* outwards */
  PetscFunctionBeginUser;
  if (!m->dry) PetscCall(PetscMalloc1(m->nt, &m->dry));
  *ndry = 0;
  for (PetscInt k = 0; k < m->nt; k++) {
    const PetscReal *a = m->t + 9 * k;
    PetscReal        n[3], p[3];
    GeomMeshTriangleNormal(m, k, n);
    for (PetscInt d = 0; d < 3; d++) p[d] = (a[d] + a[3 + d] + a[6 + d]) / 3 + o * eps * n[d];
    m->dry[k] = dry(p, ctx);
    *ndry += m->dry[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal GeomMeshVolume(const GeomMesh *m)
{
  PetscReal v = 0;
  for (PetscInt k = 0; k < m->nt; k++) {
    const PetscReal *a = m->t + 9 * k, *b = a + 3, *c = a + 6;
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6;
}

void GeomMeshTriangleNormal(const GeomMesh *m, PetscInt k, PetscReal n[3])
{
  const PetscReal *a = m->t + 9 * k;
  PetscReal        u[3], v[3], l;
  for (PetscInt d = 0; d < 3; d++) { u[d] = a[3 + d] - a[d]; v[d] = a[6 + d] - a[d]; }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  l    = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0) for (PetscInt d = 0; d < 3; d++) n[d] /= l;
}
