/* A closed triangulated surface (3D), read from an STL file (binary or ASCII): its inside test (ray
 * parity along +z over a grid of columns, with a tie rule that counts a ray through a shared edge or
 * vertex once) and its unsigned distance (the nearest triangle, searched over a uniform grid of cells
 * in shells of growing radius).  Used by base/geometry.c as the shape GEOM_MESH (docs/geometry.md). */
#pragma once
#include "base/base.h"

typedef struct {
  PetscInt   nt;            /* triangles */
  PetscReal *t;             /* 9 numbers per triangle: its three vertices */
  PetscReal  lo[3], hi[3];  /* bounding box */
  PetscInt   n[3];          /* grid cells per direction, over the bounding box */
  PetscReal  g0[3], gh[3];  /* the grid's low corner and cell size */
  PetscInt  *cell, *cells;  /* 3D cells: triangles of cell c are cells[cell[c] .. cell[c + 1]) */
  PetscInt  *col, *cols;    /* xy columns: triangles of column c are cols[col[c] .. col[c + 1]) */
  PetscBool *dry;           /* per triangle, or NULL: dry triangles (GeomMeshSetDry) */
} GeomMesh;

/* Read an STL file: binary (84-byte header and count, 50 bytes a triangle) or ASCII ("solid" ...
 * "vertex x y z" ...).  opt names the option in the messages.  Refused (bad input): no such file, a
 * binary file whose size does not match its count, an ASCII facet without three vertices or a number
 * that does not parse, no triangles, a surface that is not closed (the count of its open edges: edges
 * used by one triangle, or by an odd number). */
PetscErrorCode GeomMeshReadSTL(MPI_Comm comm, const char *opt, const char *file, GeomMesh *m);
/* A mesh of nt triangles t (9 numbers each, copied); open: its count of open edges (0: closed). */
PetscErrorCode GeomMeshCreate(PetscInt nt, const PetscReal t[], GeomMesh *m, PetscInt *open);
/* x -> Rz Ry Rx (scale x) + t, angles in radians, then the grids again. */
PetscErrorCode GeomMeshTransform(GeomMesh *m, PetscReal scale, const PetscReal ang[3], const PetscReal t[3]);
PetscErrorCode GeomMeshDestroy(GeomMesh *m);
/* Whether x is inside (ray parity; a point on the surface may fall either way: use the distance). */
PetscBool GeomMeshInside(const GeomMesh *m, const PetscReal x[]);
/* The distance from x to the surface, and its nearest point q (may be NULL) and that point's triangle;
 * when the distance is dmax or more, the search may stop and return a value >= dmax. */
PetscReal GeomMeshDistance(const GeomMesh *m, const PetscReal x[], PetscReal dmax, PetscReal q[], PetscInt *tri);
/* Mark the triangles whose centroid moved eps outwards satisfies dry(p, ctx) (e.g. faces resting on a
 * tank's floor); returns their count. */
PetscErrorCode GeomMeshSetDry(GeomMesh *m, PetscReal eps, PetscBool (*dry)(const PetscReal p[], void *ctx), void *ctx, PetscInt *ndry);
/* The distance from x to the triangles that are not dry, searched up to dmax (a value >= dmax beyond). */
PetscReal GeomMeshDistanceWet(const GeomMesh *m, const PetscReal x[], PetscReal dmax);
/* The enclosed volume (divergence theorem, either orientation). */
PetscReal GeomMeshVolume(const GeomMesh *m);
/* The unit normal of triangle k (its vertices' order; may point in or out). */
void GeomMeshTriangleNormal(const GeomMesh *m, PetscInt k, PetscReal n[3]);
