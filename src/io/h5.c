#include "io/h5.h"
#include <petscvec.h>
#include <petscis.h>

PetscErrorCode DatasetWriteInts(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, const PetscInt *a)
{
  IS is;
  PetscFunctionBeginUser;
  PetscCall(ISCreateGeneral(comm, n, a, PETSC_USE_POINTER, &is));
  PetscCall(PetscObjectSetName((PetscObject)is, name));
  PetscCall(ISView(is, v));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DatasetWriteReals(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt bs, const PetscReal *a)
{
  Vec vec;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPIWithArray(comm, bs, n * bs, PETSC_DECIDE, a, &vec));
  PetscCall(PetscObjectSetName((PetscObject)vec, name));
  PetscCall(VecView(vec, v));
  PetscCall(VecDestroy(&vec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DatasetReadInts(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt *out)
{
  IS              is;
  PetscLayout     map;
  const PetscInt *a;
  PetscFunctionBeginUser;
  PetscCall(ISCreate(comm, &is));
  PetscCall(ISSetType(is, ISGENERAL));
  PetscCall(PetscObjectSetName((PetscObject)is, name));
  PetscCall(ISGetLayout(is, &map));
  PetscCall(PetscLayoutSetLocalSize(map, n));
  PetscCall(ISLoad(is, v));
  PetscCall(ISGetIndices(is, &a));
  PetscCall(PetscArraycpy(out, a, n));
  PetscCall(ISRestoreIndices(is, &a));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DatasetReadReals(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt bs, PetscReal *out)
{
  Vec                vec;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &vec));
  PetscCall(VecSetSizes(vec, n * bs, PETSC_DECIDE));
  PetscCall(VecSetBlockSize(vec, bs));
  PetscCall(VecSetType(vec, VECSTANDARD));
  PetscCall(PetscObjectSetName((PetscObject)vec, name));
  PetscCall(VecLoad(vec, v));
  PetscCall(VecGetArrayRead(vec, &a));
  PetscCall(PetscArraycpy(out, a, n * bs));
  PetscCall(VecRestoreArrayRead(vec, &a));
  PetscCall(VecDestroy(&vec));
  PetscFunctionReturn(PETSC_SUCCESS);
}
