/* Common includes and compatibility across PETSc versions (3.18 and newer). */
#pragma once
#include <petscsys.h>
#ifndef PETSC_SUCCESS
  #define PETSC_SUCCESS 0
#endif
#include <petscviewer.h>

/* nearest integer */
static inline PetscInt RoundToInt(PetscReal x) { return (PetscInt)PetscFloorReal(x + 0.5); }
