/* The output directory of a run: created on every rank's view, owned by one run at a time, and never
 * a mix of two runs' files.
 *  - A lock, OUTDIR/sphfsi.lock (host, PID, start), taken by rank 0 with O_EXCL and refreshed every
 *    OUTDIR_BEAT_S seconds of wall time.  A second run into a locked directory stops with one line
 *    (exit status 2).  A lock is stale when its process is gone (same host) or it has not been
 *    refreshed for OUTDIR_STALE_S (another host, whose processes cannot be seen): it is taken over
 *    with a note.
 *  - A new run (no -restart) into a directory that holds a run's output (snapshots, probes, summary,
 *    checkpoints) stops with one line unless -overwrite, which removes those files (and only those).
 *  - A restart continues in the directory its checkpoint belongs to; the snapshots the interrupted
 *    run wrote after its checkpoint are removed (the restart writes them again), and so are files
 *    left half-written (*.part) by a run that was killed. */
#pragma once
#include "io/output.h"

#define OUTDIR_LOCK    "sphfsi.lock"
#define OUTDIR_BEAT_S  60.0  /* s between refreshes of the lock */
#define OUTDIR_STALE_S 600.0 /* s without a refresh after which another host's lock is stale */

/* mkdir -p on rank 0, checked on every rank; the lock; an earlier run's files (collective). */
PetscErrorCode OutDirOpen(Output *out);
/* Rank 0 refreshes the lock when OUTDIR_BEAT_S have passed (not collective). */
PetscErrorCode OutDirBeat(Output *out);
/* After a restart has read its state: remove the snapshots numbered from out->nsnap on (collective). */
PetscErrorCode OutDirTidyRestart(Output *out);
/* Release the lock if this run holds it (not collective; safe to call twice). */
PetscErrorCode OutDirClose(Output *out);
