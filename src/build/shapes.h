/* The shapes' internals (the interface: <sphfsi/shapes.h>).  The geometry itself (signed distance,
 * inside test, normals) is base/geometry.h. */
#pragma once
#include <sphfsi/shapes.h>
#include "run/sim.h"
#include "base/geometry.h"
#include "base/refdata.h"

#define SHAPES_MAX_VERTICES 512

typedef struct {
  GeomShape g;
  ShapeKind kind;
  char      name[32]; /* the option that gave it, e.g. -cylinder_1 */
  PetscBool own;      /* -stl_K_lattice own: its bounding box's lattice at -dx (as a wall box), not the shared one */
  PetscReal period[3]; /* the domain's period in the directions in which the shape crosses a periodic boundary, else 0 */
  PetscBool wraps;     /* it crosses one: its particles beyond the boundary go to the other side */
  PetscInt  body;      /* -NAME_body: the body whose force -body_force gives (0: none) */
  PetscInt  ids[2];    /* the ids its particles were given, [first, end) (ShapesPopulate) */
} Shape;

struct _n_Shapes {
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
};

