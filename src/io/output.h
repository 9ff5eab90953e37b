/* The output's context: the state that snapshots, probes, the summary, checkpoints and the output
 * directory keep between calls.  The driver (src/run/sim.c) owns one, embedded in the run as
 * sim->out, and sets its options (-output_dir, -output_interval, ...). */
#pragma once
#include "base/base.h"

typedef struct {
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
