/* Exchange of particle records between ranks (migration, ghosts).  Sparse: each rank names the
 * ranks it sends to, who sends to it is found by PETSc's two-sided set-up (PetscCommBuildTwoSided:
 * an allreduce of counts, or with -build_twosided ibarrier a non-blocking consensus), then only
 * those pairs exchange; MPI_Alltoallv costs P - 1 latencies per call in Open MPI even for empty
 * messages.  Dense (MPI_Alltoall + MPI_Alltoallv): one round fewer, faster on a few ranks. */
#pragma once
#include "base/base.h"

/* Send scnt[r] records of rs reals, sbuf + rs sdisp[r], to every rank r with scnt[r] > 0 (itself
 * included); receive into *rbuf (allocated here, free with PetscFree) the records of every sender
 * in increasing rank order, as MPI_Alltoallv would place them: rcnt[r] and rdisp[r] (size P and
 * P + 1) are filled, *nrecv = rdisp[P].  Both ways give the same buffer. */
PetscErrorCode ExchangeRecords(MPI_Comm comm, PetscBool sparse, PetscInt rs, const PetscMPIInt scnt[], const PetscMPIInt sdisp[], const PetscReal *sbuf, PetscMPIInt rcnt[], PetscMPIInt rdisp[], PetscReal **rbuf, PetscInt *nrecv);
