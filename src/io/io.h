/* Output: parallel HDF5 snapshots + XDMF, probes CSV, run summary JSON.  Each takes the output's
 * context (output.h), not the run. */
#pragma once
#include "io/output.h"

PetscErrorCode IOSetUp(Output *out);       /* probes.csv (the directory: outdir.h) */
PetscErrorCode IOSnapshot(Output *out);    /* particles_NNNNN.h5 (collective) and particles.xmf */
PetscErrorCode IOProbes(Output *out);      /* one probe row (kept in memory: IOWriteProbes) */
PetscErrorCode IOWriteProbes(Output *out); /* probes.csv from every row so far (temporary name, renamed) */
/* summary.json (collective).  How the run ended is the driver's verdict: status "completed",
 * "stopped" or "fault", and message why (NULL: it completed); an I/O fault the output recorded
 * (out->fault) is "io_error" with its own message instead.  The scene's errors are computed when
 * with_errors (the set-up completed: a run stopped during it has no state to measure). */
PetscErrorCode IOSummary(Output *out, const char *status, const char *message, PetscBool with_errors);
PetscErrorCode IOFinalize(Output *out); /* frees the probe rows and the snapshot table */
/* OUTDIR/particles.xmf over the snapshots so far */
PetscErrorCode IOWriteXDMF(Output *out);
/* OUTDIR/xmf for ParaView over the one particle file OUTDIR/h5 (a snapshot or a checkpoint). */
PetscErrorCode IOWriteXDMFOne(Output *out, const char *xmf, const char *h5, PetscReal t, PetscInt N);
/* Rank 0 renames tmp to path; every rank learns whether it worked (collective). */
PetscErrorCode IORenameOnRoot(Output *out, const char *tmp, const char *path);
/* Write the snapshot to an explicit path (used by tests) */
PetscErrorCode IOWriteParticles(Output *out, const char *path);
