/* The output's context: what snapshots, probes, the summary, checkpoints and the output directory
 * read and keep, and nothing of the driver, the scene or the guard.  The driver (src/run/sim.c)
 * owns one, embedded in the run as sim->out, sets its options (-output_dir, -output_interval, ...),
 * wires its handles (the physics' context, through which it reaches the particles and the
 * machinery; the grid; the driver's counters that checkpoints carry) and hands it the scene as data
 * and callbacks (its name, its probes, its errors and the state it keeps), as the scene's prescribed
 * motion reaches the solid through Physics.  How a run ended (the guard's verdict) reaches
 * summary.json as arguments of IOSummary (io.h). */
#pragma once
#include "physics/physics.h"
#include "particles/grid.h"
#include "base/refdata.h"

/* The next output time after t: next + k interval, the least k with it past t.  Stepped by
 * repeated addition as the schedule always was; an interval far below the step (e.g. a snapshot at
 * every step with -output_interval 1e-9) first skips the whole intervals at once: the loop alone
 * took a billion additions a step there. */
static inline PetscReal OutputNextTime(PetscReal next, PetscReal interval, PetscReal t)
{
  PetscReal behind;
  if (!(interval > 0)) return next; /* no schedule */
  behind = PetscFloorReal((t - next) / interval);
  if (behind > 1000) next += (behind - 1) * interval;
  while (next <= t) next += interval;
  return next;
}

#define OUTPUT_MAX_PROBES 16 /* probe columns of a scene besides t (the driver checks the scene's) */
#define OUTPUT_MAX_KEPT   16 /* scene histories and values a checkpoint carries (SceneKeep*) */

typedef struct {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  /* handles wired by the driver */
  Physics      *phys;    /* the particles (P), the machinery (decomp, halo, cells, nb), the model and the step */
  const Grid   *grid;    /* the cells and the domain box */
  RefData      *refdata; /* the reference files the scene's errors lacked (summary.json) */
  PetscLogStage stage;   /* the Output stage of -log_view */
  PetscReal     t_end;   /* the run's end time (set after the scene's create, which may choose it) */
  /* the driver's counters (handles): checkpoints save them, a restart restores them, summary.json
   * reports them */
  struct {
    PetscReal      *mass0, *mass;      /* total mass at the start and now (SimTotalMass) */
    PetscReal      *particle_steps;    /* particles times steps, over the runs before a restart too */
    PetscReal      *wall_used;         /* time-loop wall time of the runs before a restart */
    PetscLogDouble *wall_start;        /* when this run's time loop began (0: not yet) */
    PetscLogDouble *wall_loop;         /* this run's time-loop wall time */
    PetscReal      *dt_first;          /* [2]: the first adaptive fluid and solid steps (the guard's floor of dt) */
    PetscInt       *next_id;           /* the ids the scene handed out are 0..next_id-1 */
  } run;
  /* the scene's (wired by the driver after the scene's create) */
  struct {
    const char        *name;
    PetscInt           nprobes;     /* probe columns besides t */
    const char *const *probe_names; /* their names, the header of probes.csv */
    /* probe values (collective; every rank gets them) */
    PetscErrorCode (*probe)(void *ctx, PetscReal vals[]);
    /* errors against the scene's references as JSON members ("name": value, ...), written by rank 0
     * to json (collective; NULL on the other ranks); NULL: the scene has none */
    PetscErrorCode (*errors)(void *ctx, FILE *json);
    void *ctx;
    /* state that changes during a run (probe histories, running extremes), which checkpoints save
     * and a restart restores, in the order the scene registered it (SceneKeep*) */
    Series   **kept_series;
    PetscReal **kept_reals;
    PetscInt    nkept_series, nkept_reals;
  } scene;
  /* the output directory (outdir.h) */
  char           dir[PETSC_MAX_PATH_LEN];
  PetscBool      overwrite; /* -overwrite: a new run may replace an earlier run's output */
  PetscBool      lock_held; /* rank 0 holds DIR/sphfsi.lock */
  PetscLogDouble lock_beat; /* when the lock was last refreshed */
  char           restart[PETSC_MAX_PATH_LEN]; /* -restart FILE: the checkpoint this run continues; empty: a fresh start */
  /* snapshots: particles_NNNNN.h5 */
  PetscReal  snap_interval, next_snap; /* physical time between snapshots (0: none), time of the next */
  PetscInt   nsnap, snap_cap;          /* snapshots so far, room in snaps */
  PetscReal *snaps;                    /* (t, particles) of each snapshot: the outflow removes particles */
  /* probes: every row so far (t and the scene's columns; rank 0), rewritten to probes.csv */
  PetscReal  probe_interval, next_probe; /* 0: a row every step */
  PetscReal *probe_rows;
  PetscInt   nprobe_rows, cap_probe_rows;
  /* checkpoints: DIR/checkpoint.h5 */
  PetscReal ckpt_interval, next_ckpt; /* physical time between checkpoints; 0 = none */
  PetscInt  nckpt;                    /* checkpoints written by this run */
  PetscReal ckpt_t;                   /* time of the state checkpoint.h5 holds (-1: none) */
  /* output that could not be written (io_space.h: IOFault) */
  struct {
    PetscBool set;
    char      msg[2 * PETSC_MAX_PATH_LEN];
  } fault;
} Output;
