/* The simulation: owns the particles and every module, and is the only place that knows the order
 * of a time step. */
#pragma once
#include "particles/grid.h"
#include "physics/physics.h"
#include "base/refdata.h"
#include "io/output.h"
#include <sphfsi/scene.h> /* Sim, SceneOps: the scene's view of the run (its accessors: sim_scene.c) */

typedef enum { STAGE_NEIGHBOUR, STAGE_HALO, STAGE_PHYSICS, STAGE_PPE_ASSEMBLY, STAGE_PPE_SOLVE, STAGE_SOLID, STAGE_OUTPUT, STAGE_GUARD, STAGE_COUNT } SimStage;

typedef struct _p_Guard *Guard;     /* guard.h */
typedef struct _n_SizeGuard *SizeGuard; /* size_guard.h */
#define SIM_MAX_KEEP OUTPUT_MAX_KEPT /* scene histories and scalars a checkpoint carries (SceneKeep*; output.h) */

struct _p_Sim {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  /* scene and scheme */
  const SceneOps *scene;
  void           *scene_ctx;
  /* machinery */
  Grid      grid;
  Particles P;
  Cells     cells;
  Decomp    decomp;
  Halo      halo;
  Neighbourhood nbhd; /* brings the machinery up to date after particles move; counts the particles */
  Physics       phys;       /* the model, the step and the fluid and solid modules (physics.h) */
  PetscReal     dom_lo[3], dom_hi[3];
  PetscBool     periodic[3];
  PetscBool     outflow;    /* fluid leaving the domain box is removed (open boundary) */
  PetscReal     start_jitter; /* -fluid_start_jitter: random displacement of the fluid's start lattice (dx) */
  struct { PetscInt n; PetscReal z0, dz; } extrude; /* a 3D slab built from a 2D layout (SceneExtrudeBegin) */
  /* time */
  PetscReal t_end, dt_fixed;
  struct { PetscBool on; PetscReal g[3], t0, t1, g_base[3]; } pulse; /* -gravity_pulse: gravity g_base + g over the steps that start in [t0, t1) */
  PetscInt  max_steps;
  /* output */
  Output    out;            /* the output's state: directory, intervals, snapshots, probe rows, checkpoints (output.h) */
  PetscBool help;           /* -help: list the options and stop before the particles are made */
  PetscBool ready;          /* SimSetUp completed (a stop during set-up leaves it false) */
  PetscInt  progress_every;
  /* statistics */
  PetscLogDouble wall_start, wall_loop;
  PetscReal      t_start; /* simulated time when this run's loop began (after a restart, not 0) */
  PetscReal      particle_steps, mass0, mass;
  PetscLogStage  stage[STAGE_COUNT];
  PetscInt       next_id; /* global ids handed out by the scene */
  PetscReal      wall_used; /* time-loop wall time of the runs before a restart */
  /* checkpoint, restart, early stops and faults (checkpoint.h, guard.h) */
  RefData   refdata;                     /* where the scenes' reference files are, and those missing (refdata.h) */
  PetscInt  ckpt_step;                   /* step of the last complete checkpoint */
  Guard     guard;
  SizeGuard size_guard;                  /* the memory estimate against the node's (size_guard.h) */
  struct {                               /* the scenes' builders count what they add through these (the driver wires the size guard) */
    PetscErrorCode (*add)(Sim sim, ParticleKind kind, PetscInt64 n); /* n particles of a kind: counted, or checked against the memory */
    PetscBool (*counting)(Sim sim);                                  /* a dry count: count, add nothing */
  } counter;
  PetscInt  exit_status;                 /* 0, or SIM_EXIT_STOPPED / SIM_EXIT_FAULT (guard.h) */
  /* scene state that changes during a run (probe histories, running extremes): SceneKeep* */
  Series    *keep_series[SIM_MAX_KEEP];
  PetscReal *keep_reals[SIM_MAX_KEEP];
  PetscInt   nkeep_series, nkeep_reals;
};

PetscErrorCode SimCreate(MPI_Comm comm, Sim *sim);
PetscErrorCode SimSetFromOptions(Sim sim);
PetscErrorCode SimSetUp(Sim sim);
PetscErrorCode SimRun(Sim sim);
PetscErrorCode SimDestroy(Sim *sim);
/* summary.json with how the run ended, as the guard says (io.h: IOSummary; collective). */
PetscErrorCode SimWriteSummary(Sim sim);
/* The driver's wiring of the output's context sim->out (sim_output.c): its handles, in SimCreate;
 * the scene's name, probes, errors and kept state and the end time, after the scene's create. */
PetscErrorCode SimWireOutput(Sim sim);
PetscErrorCode SimWireOutputToScene(Sim sim);
/* Total mass of owned fluid and solid particles, plus the fluid that left (collective). */
PetscErrorCode SimTotalMass(Sim sim, PetscReal *M);
