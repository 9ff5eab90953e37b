/* Output: parallel HDF5 snapshots + XDMF, probes CSV, run summary JSON. */
#pragma once
#include "run/sim.h"

PetscErrorCode IOSetUp(Sim sim);      /* probes.csv (the directory: outdir.h) */
PetscErrorCode IOSnapshot(Sim sim);   /* particles_NNNNN.h5 (collective) and particles.xmf */
PetscErrorCode IOProbes(Sim sim);     /* one probe row (kept in memory: IOWriteProbes) */
PetscErrorCode IOWriteProbes(Sim sim); /* probes.csv from every row so far (temporary name, renamed) */
PetscErrorCode IOSummary(Sim sim);    /* summary.json */
PetscErrorCode IOFinalize(Sim sim);
/* OUTDIR/particles.xmf over the snapshots so far */
PetscErrorCode IOWriteXDMF(Sim sim);
/* OUTDIR/xmf for ParaView over the one particle file OUTDIR/h5 (a snapshot or a checkpoint). */
PetscErrorCode IOWriteXDMFOne(Sim sim, const char *xmf, const char *h5, PetscReal t, PetscInt N);
/* Rank 0 renames tmp to path; every rank learns whether it worked (collective). */
PetscErrorCode IORenameOnRoot(Sim sim, const char *tmp, const char *path);
/* Write the snapshot to an explicit path (used by tests) */
PetscErrorCode IOWriteParticles(Sim sim, const char *path);
