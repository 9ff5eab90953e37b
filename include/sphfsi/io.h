/* Output: parallel HDF5 snapshots + XDMF, probes CSV, run summary JSON. */
#pragma once
#include <sphfsi/sim.h>

PetscErrorCode IOSetUp(Sim sim);      /* output dir, probes.csv header */
PetscErrorCode IOSnapshot(Sim sim);   /* particles_NNNNN.h5 (collective) and particles.xmf */
PetscErrorCode IOProbes(Sim sim);     /* one row of probes.csv */
PetscErrorCode IOSummary(Sim sim);    /* summary.json */
PetscErrorCode IOFinalize(Sim sim);
/* Write the snapshot to an explicit path (used by tests) */
PetscErrorCode IOWriteParticles(Sim sim, const char *path);
