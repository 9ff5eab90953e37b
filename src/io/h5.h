/* The collective HDF5 dataset: every write and read of snapshots (io.c) and checkpoints
 * (checkpoint.c) goes through here, by PETSc's HDF5 viewer.  Each rank passes its own block of
 * n entries (n = 0 for none); the blocks, in rank order, make the dataset.  Reals of block size bs
 * make a dataset of bs columns (a field's components); integers are PetscInt. */
#pragma once
#include "base/base.h"

PetscErrorCode DatasetWriteInts(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, const PetscInt *a);
PetscErrorCode DatasetWriteReals(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt bs, const PetscReal *a);
/* This rank's n entries (rows of bs) of dataset `name`; the ranks' n must add up to its length. */
PetscErrorCode DatasetReadInts(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt *out);
PetscErrorCode DatasetReadReals(PetscViewer v, MPI_Comm comm, const char *name, PetscInt n, PetscInt bs, PetscReal *out);
