/* How a run ends early, agreed by all ranks.
 *  - Stop requests: SIGTERM, SIGINT or SIGUSR1 on any rank, or -max_wall_time.  Each step ends with
 *    one small reduction in which every rank learns of them; the run then writes a checkpoint and
 *    ends with SIM_EXIT_STOPPED.
 *  - Faults: NaN/Inf in any field, a particle outside the domain, dt below its floor (-dt_min), a
 *    pressure solve that does not converge.  The run names what, where (particle id, position) and
 *    when (step, t), writes the last good state (a restartable checkpoint) and ends with
 *    SIM_EXIT_FAULT. */
#pragma once
#include "run/sim.h"
#include "io/checkpoint.h"

#define GUARD_KEEP_EVERY 10 /* steps between copies of the last good state (a copy of every field: a fraction of a step) */

typedef enum { GUARD_RUNNING = 0, GUARD_STOP, GUARD_FAULT, GUARD_IO } GuardState;

struct _p_Guard {
  GuardState     state;
  char           msg[1024];       /* why the run ended early */
  PetscReal      max_wall;        /* -max_wall_time (s since start); 0 = none */
  PetscReal      dt_min;          /* -dt_min (s); 0 = 1e-3 of the first adaptive step of each medium */
  PetscReal      dt_first[2];     /* first adaptive fluid and solid steps */
  PetscLogDouble t0, step_start, step_max; /* process start; start and longest wall time of a step */
  SimState       good;            /* the last good state */
  PetscBool      have_good;
};

/* Handlers for SIGTERM, SIGINT, SIGUSR1 (after PetscInitialize; PETSc 3.18 keeps SEGV, FPE, ...). */
PetscErrorCode GuardInstallSignals(void);
PetscErrorCode GuardCreate(Guard *g);
PetscErrorCode GuardDestroy(Guard *g);
PetscErrorCode GuardSetFromOptions(Sim sim);
/* Before the first step: a non-finite value in the initial (or restarted) state is a fault. */
PetscErrorCode GuardCheckInitial(Sim sim);
/* Start of a step: keep a copy of the state every GUARD_KEEP_EVERY steps. */
PetscErrorCode GuardStepBegin(Sim sim);
/* One step through step(); a PETSc error of kind PETSC_ERR_NOT_CONVERGED raised inside it (particle
 * outside the domain, pressure solve) becomes a fault, any other error goes on as an error. */
PetscErrorCode GuardStep(Sim sim, PetscErrorCode (*step)(Sim));
/* Inside a step, before the state changes: dt of `medium` (0 fluid, 1 solid) against its floor. */
PetscErrorCode GuardCheckDt(Sim sim, PetscInt medium, PetscReal dt);
/* End of a step: NaN/Inf in any field of any owned particle, stop requests, and whether a progress
 * line is due (in: rank 0's view; out: agreed); one reduction. */
PetscErrorCode GuardStepEnd(Sim sim, PetscBool *progress);
/* Record a fault (collective; every rank passes the same message).  state_ok: the current state is
 * still good (nothing changed yet), so it becomes the last good state. */
PetscErrorCode GuardFault(Sim sim, PetscBool state_ok, const char *fmt, ...) PETSC_ATTRIBUTE_FORMAT(3, 4);
/* An I/O fault the output recorded (sim->out.fault, io_space.h) becomes the guard's state GUARD_IO:
 * the run ends with SIM_EXIT_IO (the driver asks after each output; GuardFinish asks too). */
PetscErrorCode GuardCheckIO(Sim sim);
/* During set-up, between its phases: a stop request (a signal on any rank) ends the set-up with
 * GUARD_STOP; `when` says where (collective). */
PetscErrorCode GuardCheckSetUp(Sim sim, const char *when);
/* The first thing a stopped run does: say so at once (flushed), before the checkpoint is written. */
PetscErrorCode GuardAnnounceStop(Sim sim);
/* After the loop of a run that ended early: checkpoint (stop) or last good state (fault), the
 * message, and the exit status in sim->exit_status. */
PetscErrorCode GuardFinish(Sim sim);
