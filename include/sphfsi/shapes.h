/* Shapes beyond boxes (docs/geometry.md), as -case boxes reads them from its options: circles (2D),
 * spheres (3D), closed polygons (2D) and closed STL surfaces, each water, an obstacle of wall
 * particles, an elastic solid or a clamp, made on one lattice with the water so that water and
 * obstacle interlock as at a flat wall. */
#ifndef SPHFSI_SHAPES_H
#define SPHFSI_SHAPES_H
#include <sphfsi/scene.h>

SPHFSI_EXTERN_C_BEGIN

#define SHAPES_MAX 8 /* of each type: -cylinder_K (-sphere_K in 3D), -polygon_K, K = 1..8 */
#define SHAPES_MAX_BODIES 4 /* -NAME_body (and -case boxes' -wall_box_K_body ...): 1..4, 0 none */

typedef enum { SHAPE_WALL = 0, SHAPE_FLUID, SHAPE_SOLID, SHAPE_CLAMP } ShapeKind;
extern const char *const ShapeKinds[];

/* A scene's set of shapes (opaque). */
typedef struct _n_Shapes *Shapes;
PetscErrorCode ShapesCreate(Shapes *S);
PetscErrorCode ShapesDestroy(Shapes *S);
/* How many shapes were read, and shape i's kind and bounding box (3 coordinates each). */
PetscInt       ShapesCount(Shapes S);
PetscErrorCode ShapesGetShape(Shapes S, PetscInt i, ShapeKind *kind, PetscReal lo[], PetscReal hi[]);
/* Shape i's body (-NAME_body: whose force -body_force gives; 0: none, water's always), and, if ids is
 * not NULL, the ids its particles were given, [ids[0], ids[1]) (empty before ShapesPopulate). */
PetscInt       ShapesGetBody(Shapes S, PetscInt i, PetscInt ids[]);

/* In the boxes' options block: -cylinder_K / -sphere_K, -polygon_K (or -polygon_K_file) with
 * _kind, _scale, _rotate, _translate, _body; -flow_probe.  rows: the obstacles' wall rows. */
PetscErrorCode ShapesRead(Sim sim, PetscOptionItems *PetscOptionsObject, Shapes S, PetscInt rows);
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
PetscErrorCode ShapesSetUp(Sim sim, Shapes S, PetscInt nbox, const PetscReal (*box)[6], const PetscReal *spacing, const ShapesBoxes *bodies);
/* The boxes that other walls fill (x0,y0,z0,x1,y1,z1), at most 6 * SHAPES_MAX: the faces of an STL
 * obstacle against them meet no water, and its rows there are dummies (as a wall box's faces not given). */
PetscErrorCode ShapesSetDry(Sim sim, Shapes S, PetscInt n, const PetscReal (*box)[6]);
/* Add the shapes' particles: water shapes (each at the hydrostatic density below its top), then
 * obstacles, solids and clamps in the order given. */
PetscErrorCode ShapesPopulate(Sim sim, Shapes S);
/* Remove this rank's water particles from index first on that lie in or on an obstacle, solid or
 * clamp shape.  lo, hi, spacing: the water box they fill (NULL: the shapes' lattice); a box off the
 * shapes' lattice also loses the water within half its spacing outside the shapes. */
PetscErrorCode ShapesCutWater(Sim sim, Shapes S, PetscInt first, const PetscReal lo[], const PetscReal hi[], PetscReal spacing);
/* The probe columns -flow_probe adds (u_mean, drag) and their values (collective). */
PetscInt       ShapesFlowColumns(Shapes S);
PetscErrorCode ShapesFlowProbe(Sim sim, Shapes S, PetscReal *vals);
/* summary.json members: the drag against the reference (Sangani & Acrivos 1982, 2D). */
PetscErrorCode ShapesFlowErrors(Sim sim, Shapes S, FILE *f);

SPHFSI_EXTERN_C_END
#endif
