/* Checkpoint and restart.  A checkpoint is the whole state of a run at the end of a step, in one
 * HDF5 file written collectively by all ranks under a temporary name and renamed when complete:
 * every owned particle with its id, kind and every allocated field that the field table has
 * checkpoints carry (particles.h; all of them today); the time loop's counters (t, step, dt, next
 * output/probe/checkpoint times, first adaptive steps); the cell partition; every probe row so far;
 * the snapshots' times and sizes; the scene's kept histories and values (SceneKeep*); solver and
 * outflow counters.  Its datasets of a snapshot's fields (id, kind and the table's snapshot
 * fields) have the names and shapes of a snapshot's (datasets: h5.h).
 *
 * A restart on the same number of ranks continues bit for bit: it restores the partition and
 * repeats the run's last rebuild at the positions it had then (FIELD_XREB: solids move after it,
 * and WCSPH's Verlet skin keeps a list over steps), then computes the pairs where the run last did
 * (FIELD_XLIST, with solids and a skin), so neighbour lists, their order and every sum are the same.  On another number of ranks the
 * partition is made anew; neighbour sums do not depend on it (cells.h), so WCSPH and solids still
 * agree bit for bit, ISPH to the solver tolerance.
 *
 * Each takes the output's context (output.h): the live state is the physics' (out->phys), the
 * output's own (tables, next output times), the driver's counters it points to (out->run: mass,
 * particle steps, wall time, the guard's first steps, the next id) and the scene's kept state
 * (out->scene). */
#pragma once
#include "io/output.h"

enum { STATE_NREAL = 12, STATE_NINT = 12 };

/* The state at the end of a step.  A view points into the live run; a copy (the last good state,
 * guard.h) owns its arrays.  Histories only grow, so a state keeps their lengths, not their data. */
typedef struct {
  PetscBool    copy;
  PetscInt     n, cap;             /* owned particles, capacity of a copy */
  PetscInt    *id, *kind;
  PetscReal   *f[FIELD_COUNT];     /* owned part of every field checkpoints carry (else NULL) */
  PetscInt     ncell;
  PetscMPIInt *owner;              /* cell partition */
  PetscReal    r[STATE_NREAL];     /* scalars, named in checkpoint.c */
  PetscInt     i[STATE_NINT];
  PetscInt     nrows, nsnap;       /* probe rows and snapshots so far */
  PetscInt     series_n[OUTPUT_MAX_KEPT];
  PetscReal    kept[OUTPUT_MAX_KEPT]; /* the scene's kept values */
} SimState;

/* The live state (no copy). */
PetscErrorCode StateView(Output *out, SimState *s);
/* A copy of the live state, reusing the buffers of *s. */
PetscErrorCode StateCopy(Output *out, SimState *s);
PetscErrorCode StateDestroy(SimState *s);

/* Write a state to path (collective; path.part first, renamed when complete). */
PetscErrorCode CheckpointWrite(Output *out, const SimState *s, const char *path);
/* The run's regular checkpoint: OUTDIR/checkpoint.h5 from the live state. */
PetscErrorCode CheckpointSave(Output *out);
/* Before the options are read (SimSetFromOptions): with -restart FILE, check that FILE is a whole
 * checkpoint (one line naming what is wrong: missing, not HDF5, truncated, unreadable datasets) and
 * add every option it was written with that the command line does not give (restart_file.c). */
PetscErrorCode CheckpointInheritOptions(MPI_Comm comm);
/* In SimSetUp, after the scene populated and the grid was set up: replace the particles and the
 * run's state by those of -restart FILE and rebuild as the run had.  Errors name what does not
 * match (scene, scheme, fields, dx, options). */
PetscErrorCode CheckpointRestart(Output *out);
