/* The physics' context: what the fluids and the solid read and advance, and nothing of the driver.
 * The driver (src/run/sim.c) owns one, embedded in the run as sim->phys, wires the particles and the
 * machinery into it (handles: the driver creates and destroys them), and hands it to every physics
 * entry point; the scene sets its model (materials, gravity, dimension) before the set-up.  Physics
 * brings the neighbour lists up to date through the neighbourhood (nb), never through the driver. */
#pragma once
#include "particles/particles.h"
#include "particles/cells.h"
#include "particles/halo.h"
#include "particles/decomp.h"
#include "particles/neighbourhood.h"
#include "base/material.h"
#include "base/kernel.h"
#include "base/dim.h"
#include <petscviewer.h>

typedef enum { FLUID_WCSPH = 0, FLUID_ISPH } FluidScheme;
extern const char *const FluidSchemes[];

typedef struct _p_ISPH  *ISPH;  /* fluid/isph.h */
typedef struct _p_Solid *Solid; /* solid/solid.h */
typedef struct _n_Open  *Open;  /* fluid/open_boundary.h */

typedef struct {
  MPI_Comm comm;
  /* the particles and the machinery (handles wired by the driver) */
  Particles      P;
  Cells          cells;
  Halo           halo;
  Decomp         decomp;
  Neighbourhood *nb; /* brings the machinery up to date after particles move */
  /* the model: the scene says which media it has and sets the materials and gravity */
  PetscInt      dim; /* 2 or 3: set by the scene's create (default 2) */
  PetscBool     has_fluid, has_solid;
  FluidScheme   fluid;
  FluidMaterial fl;
  SolidMaterial sl;
  PetscReal     g[3];
  SPHKernel     kernel;    /* -kernel, -h_factor: the smoothing kernel of every pair */
  PetscReal     dx, h_max; /* finest spacing, largest smoothing length */
  PetscReal     v_ref;     /* expected maximum speed: c0 = 10 v_ref when -fluid_c0 is not given */
  PetscBool     confined;  /* the fluid has no free surface (Taylor-Green, Poiseuille) */
  ISPH          isph;      /* NULL unless -fluid isph */
  Solid         solid;     /* NULL unless the scene has solids */
  Open          open;      /* NULL unless the scene has open boundaries (inlets, outlets) */
  /* the step */
  PetscReal t, dt, cfl;
  PetscInt  step;
  /* the scene's prescribed motion, called in each solid step after the first half kick (the driver
   * wires the scene's prescribe here; NULL: none) */
  PetscErrorCode (*prescribe)(void *ctx);
  void *prescribe_ctx;
} Physics;
