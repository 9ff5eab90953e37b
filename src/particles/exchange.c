#include "particles/exchange.h"

static PetscErrorCode ExchangeDense(MPI_Comm comm, PetscMPIInt size, PetscInt rs, const PetscMPIInt scnt[], const PetscMPIInt sdisp[], const PetscReal *sbuf, PetscMPIInt rcnt[], PetscMPIInt rdisp[], PetscReal **rbuf, PetscInt *nrecv)
{
  MPI_Datatype rec;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Alltoall(scnt, 1, MPI_INT, rcnt, 1, MPI_INT, comm));
  rdisp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) rdisp[r + 1] = rdisp[r] + rcnt[r];
  *nrecv = rdisp[size];
  PetscCall(PetscMalloc1(*nrecv * rs + 1, rbuf));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)rs, MPIU_REAL, &rec));
  PetscCallMPI(MPI_Type_commit(&rec));
  PetscCallMPI(MPI_Alltoallv(sbuf, scnt, sdisp, rec, *rbuf, rcnt, rdisp, rec, comm));
  PetscCallMPI(MPI_Type_free(&rec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ExchangeRecords(MPI_Comm comm, PetscBool sparse, PetscInt rs, const PetscMPIInt scnt[], const PetscMPIInt sdisp[], const PetscReal *sbuf, PetscMPIInt rcnt[], PetscMPIInt rdisp[], PetscReal **rbuf, PetscInt *nrecv)
{
  PetscMPIInt  size, nto = 0, nfrom, *to, *tocnt, *from = NULL, *fromcnt = NULL, tag;
  MPI_Comm     icomm;
  MPI_Request *req;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!sparse) {
    PetscCall(ExchangeDense(comm, size, rs, scnt, sdisp, sbuf, rcnt, rdisp, rbuf, nrecv));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscCommDuplicate(comm, &icomm, &tag));
  for (PetscMPIInt r = 0; r < size; r++) nto += scnt[r] > 0;
  PetscCall(PetscMalloc2(nto, &to, nto, &tocnt));
  nto = 0;
  for (PetscMPIInt r = 0; r < size; r++)
    if (scnt[r] > 0) { to[nto] = r; tocnt[nto++] = scnt[r]; }
  PetscCall(PetscCommBuildTwoSided(icomm, 1, MPI_INT, nto, to, tocnt, &nfrom, &from, &fromcnt));
  PetscCall(PetscArrayzero(rcnt, size));
  for (PetscMPIInt k = 0; k < nfrom; k++) rcnt[from[k]] = fromcnt[k];
  rdisp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) rdisp[r + 1] = rdisp[r] + rcnt[r];
  *nrecv = rdisp[size];
  PetscCall(PetscMalloc1(*nrecv * rs + 1, rbuf));
  PetscCall(PetscMalloc1(nfrom + nto, &req));
  for (PetscMPIInt k = 0; k < nfrom; k++) PetscCallMPI(MPI_Irecv(*rbuf + (size_t)rs * rdisp[from[k]], (PetscMPIInt)(rs * rcnt[from[k]]), MPIU_REAL, from[k], tag, icomm, &req[k]));
  for (PetscMPIInt k = 0; k < nto; k++) PetscCallMPI(MPI_Isend(sbuf + (size_t)rs * sdisp[to[k]], (PetscMPIInt)(rs * scnt[to[k]]), MPIU_REAL, to[k], tag, icomm, &req[nfrom + k]));
  PetscCallMPI(MPI_Waitall(nfrom + nto, req, MPI_STATUSES_IGNORE));
  PetscCall(PetscFree(req));
  PetscCall(PetscFree(from));
  PetscCall(PetscFree(fromcnt));
  PetscCall(PetscFree2(to, tocnt));
  PetscCall(PetscCommDestroy(&icomm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
