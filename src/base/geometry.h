/* Shapes as geometry, without particles: a circle (2D) or sphere (3D), and a closed polygon (2D).
 * Each gives its signed distance (negative inside, positive outside, the distance to the surface in
 * either case), an inside test and the outward unit normal (the signed distance's gradient).  The
 * builders that turn a shape into particles are in src/build/shapes.c (<sphfsi/shapes.h>). */
#pragma once
#include "base/base.h"
#include "base/mesh.h"

typedef enum { GEOM_SPHERE = 0, GEOM_POLYGON, GEOM_MESH } GeomType;

typedef struct {
  GeomType   type;
  PetscInt   dim;          /* 2 or 3 (a polygon: 2) */
  PetscReal  c[3], r;      /* sphere: centre and radius */
  PetscInt   nv;           /* polygon: its vertices, x0,y0,x1,y1,...; the last joins the first */
  PetscReal *v;
  GeomMesh  *mesh;         /* mesh: a closed triangulated surface (3D) */
  PetscReal  lo[3], hi[3]; /* bounding box */
} GeomShape;

/* Why a polygon cannot be used (GeomPolygonCheck). */
typedef enum { GEOM_OK = 0, GEOM_FEW_VERTICES, GEOM_REPEATED_VERTEX, GEOM_SELF_INTERSECTING, GEOM_ZERO_AREA } GeomFault;
extern const char *const GeomFaults[];

/* A circle (dim 2) or sphere (dim 3) of centre c and radius r > 0. */
PetscErrorCode GeomSphere(PetscInt dim, const PetscReal c[], PetscReal r, GeomShape *s);
/* Whether n vertices xy make a simple closed polygon: at least 3, no two consecutive vertices equal,
 * no two edges crossing or touching except consecutive ones at their shared vertex (O(n^2)), a
 * non-zero area.  On a fault, e[0], e[1] name the vertices or edges involved (edge i joins vertex i
 * to i + 1). */
GeomFault GeomPolygonCheck(PetscInt n, const PetscReal xy[], PetscInt e[2]);
/* A polygon of n vertices xy (copied), of either orientation; it must pass GeomPolygonCheck. */
PetscErrorCode GeomPolygon(PetscInt n, const PetscReal xy[], GeomShape *s);
/* A closed triangulated surface from an STL file (base/mesh.h; bad input when not closed). */
PetscErrorCode GeomMeshShape(MPI_Comm comm, const char *opt, const char *file, GeomShape *s);
/* A mesh: x -> Rz Ry Rx (scale x) + t, angles (radians) about x, y, z. */
PetscErrorCode GeomTransform3(GeomShape *s, PetscReal scale, const PetscReal ang[3], const PetscReal t[]);
/* x -> R(angle) (scale x) + t: scale > 0, angle in radians about the origin (2D; a 3D sphere takes
 * the scale and translation only, angle ignored). */
PetscErrorCode GeomTransform(GeomShape *s, PetscReal scale, PetscReal angle, const PetscReal t[]);
PetscErrorCode GeomDestroy(GeomShape *s);
/* Signed distance of x: < 0 inside, > 0 outside (polygon: winding number for the sign). */
PetscReal GeomSignedDistance(const GeomShape *s, const PetscReal x[]);
/* The same where |d| < dmax; elsewhere a value of the right sign with |value| >= dmax (a mesh stops
 * searching for the nearest triangle there; a sphere or polygon gives the exact distance). */
PetscReal GeomSignedDistanceNear(const GeomShape *s, const PetscReal x[], PetscReal dmax);
PetscBool GeomInside(const GeomShape *s, const PetscReal x[]);
/* The outward unit normal at the surface point closest to x (the gradient of the signed distance
 * away from the medial axis); at a polygon's vertex, the direction from the vertex to x, or the mean
 * of its edges' normals for x on the vertex; a mesh on its surface: the triangle's outward normal.  Returns the signed distance. */
PetscReal GeomNormal(const GeomShape *s, const PetscReal x[], PetscReal n[]);
/* The enclosed area (2D) or volume (3D). */
PetscReal GeomMeasure(const GeomShape *s);
