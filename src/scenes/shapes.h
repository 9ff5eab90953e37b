/* Shapes of -case boxes beyond boxes (docs/geometry.md): circles (2D) and spheres (3D) and closed
 * polygons (2D), each water, an obstacle of wall particles, an elastic solid or a clamp, made on one
 * lattice with the water so that water and obstacle interlock as at a flat wall.  The geometry itself
 * (signed distance, inside test, normals) is base/geometry.h. */
#pragma once
#include "scenes/scene.h"
#include "base/geometry.h"
#include "base/refdata.h"

#define SHAPES_MAX 8        /* of each type: -cylinder_K (-sphere_K in 3D), -polygon_K, K = 1..8 */
#define SHAPES_MAX_VERTICES 512

typedef enum { SHAPE_WALL = 0, SHAPE_FLUID, SHAPE_SOLID, SHAPE_CLAMP } ShapeKind;
extern const char *const ShapeKinds[];

typedef struct {
  GeomShape g;
  ShapeKind kind;
  char      name[32]; /* the option that gave it, e.g. -cylinder_1 */
  PetscBool own;      /* -stl_K_lattice own: its bounding box's lattice at -dx (as a wall box), not the shared one */
  PetscReal period[3]; /* the domain's period in the directions in which the shape crosses a periodic boundary, else 0 */
  PetscBool wraps;     /* it crosses one: its particles beyond the boundary go to the other side */
} Shape;

typedef struct {
  Shape     s[2 * SHAPES_MAX];
  PetscInt  n;
  PetscInt  rows;           /* an obstacle's rows of wall + dummy particles inside its surface */
  PetscReal origin[3], h[3]; /* the lattice: points at origin + (i + 1/2) h */
  PetscReal lo[3], hi[3];    /* the domain */
  PetscBool flow;           /* -flow_probe: superficial velocity and drag columns */
  PetscReal flow_measure;   /* the domain's area (volume) */
  Series    drag;           /* the drag column's history (for its mean over the run's last tenth) */
  PetscInt  ndry;           /* boxes of wall particles (tanks' walls, wall boxes): an STL obstacle's */
  PetscReal dry[6 * SHAPES_MAX][6]; /* faces resting on them are dry, their rows dummies */
} Shapes;

/* In the boxes' options block: -cylinder_K / -sphere_K, -polygon_K (or -polygon_K_file) with
 * _kind, _scale, _rotate, _translate; -flow_probe.  rows: the obstacles' wall rows. */
PetscErrorCode ShapesRead(Sim sim, PetscOptionItems *PetscOptionsObject, Shapes *S, PetscInt rows);
/* The boxes of the scene a shape must not share space with, each the low corner, then the high one. */
#define SHAPES_MAX_BOXES 64
typedef struct {
  PetscInt  n;
  PetscReal b[SHAPES_MAX_BOXES][6];
  char      name[SHAPES_MAX_BOXES][48]; /* e.g. "-wall_box_2", "the walls of -tank_1" */
} ShapesBoxes;

/* After the domain is known: the lattice (that of the first water box when its spacing is -dx, else
 * the domain's corner at -dx), shapes inside the domain, no two solid shapes (wall, solid, clamp)
 * sharing a lattice point (a clamp takes the points it shares with a solid), water shapes sharing no
 * point with each other or with water boxes (box: the low corner, then the high corner of each of the
 * nbox water boxes; spacing: their nominal spacings), and no shape sharing a point with the boxes of
 * walls, solids and clamps (bodies; they may touch). */
PetscErrorCode ShapesSetUp(Sim sim, Shapes *S, PetscInt nbox, const PetscReal (*box)[6], const PetscReal *spacing, const ShapesBoxes *bodies);
/* The boxes that other walls fill (x0,y0,z0,x1,y1,z1), at most 6 * SHAPES_MAX: the faces of an STL
 * obstacle against them meet no water, and its rows there are dummies (as a wall box's faces not given). */
PetscErrorCode ShapesSetDry(Sim sim, Shapes *S, PetscInt n, const PetscReal (*box)[6]);
/* Add the shapes' particles: water shapes (each at the hydrostatic density below its top), then
 * obstacles, solids and clamps in the order given. */
PetscErrorCode ShapesPopulate(Sim sim, Shapes *S);
/* Remove this rank's water particles from index first on that lie in or on an obstacle, solid or
 * clamp shape.  lo, hi, spacing: the water box they fill (NULL: the shapes' lattice); a box off the
 * shapes' lattice also loses the water within half its spacing outside the shapes. */
PetscErrorCode ShapesCutWater(Sim sim, const Shapes *S, PetscInt first, const PetscReal lo[], const PetscReal hi[], PetscReal spacing);
/* The probe columns -flow_probe adds (u_mean, drag) and their values (collective). */
PetscInt       ShapesFlowColumns(const Shapes *S);
PetscErrorCode ShapesFlowProbe(Sim sim, Shapes *S, PetscReal *vals);
/* summary.json members: the drag against the reference (Sangani & Acrivos 1982, 2D). */
PetscErrorCode ShapesFlowErrors(Sim sim, Shapes *S, FILE *f);
PetscErrorCode ShapesDestroy(Shapes *S);
