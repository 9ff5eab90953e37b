/* A matrix's local rows as two CSR arrays, the diagonal block (columns local to the rank) and the
 * off-diagonal block (global columns), appended row by row and handed to PETSc without a copy
 * (MatCreateMPIAIJWithSplitArrays).  Cheaper than preallocating and calling MatSetValues, which
 * searches the row for every entry it inserts; the arrays stay ours and must outlive the matrix. */
#pragma once
#include "base/base.h"
#include <petscmat.h>

typedef struct {
  PetscInt     m, rstart, nrow;      /* local rows, first global row (= first local column), rows appended */
  PetscInt    *di, *oi, *dj, *oj;    /* row pointers and columns of the two blocks */
  PetscScalar *da, *oa;
  PetscInt     cap_m, cap_d, cap_o;  /* the entry arrays keep their size from step to step, growing when needed */
} SplitCSR;

/* Start a matrix of m local rows from global row rstart (the arrays of the last one are reused),
 * with room for bound entries in the diagonal block (an upper bound spares copies as it grows). */
PetscErrorCode SplitCSRBegin(SplitCSR *S, PetscInt m, PetscInt rstart, PetscInt bound);
/* Append the next row: nc entries with global columns, each block's columns then sorted. */
PetscErrorCode SplitCSRAppendRow(SplitCSR *S, PetscInt nc, const PetscInt cols[], const PetscScalar vals[]);
/* The assembled matrix (AIJ: sequential on one rank) of the m rows, M global rows and columns. */
PetscErrorCode SplitCSRCreateMat(SplitCSR *S, MPI_Comm comm, PetscInt M, Mat *A);
/* The same rows as hypre's ParCSR matrix (MATHYPRE) that shares the column and value arrays: no
 * copy, and BoomerAMG takes a MATHYPRE preconditioner matrix as it is (an AIJ one it converts,
 * i.e. copies, at every set-up).  Rearranges S into hypre's layout (each row's diagonal entry
 * first, off-diagonal columns numbered through a sorted map of their global numbers), so S then
 * makes no other matrix until the next SplitCSRBegin.  Every row must hold its diagonal.  Only
 * where SplitCSRSharesWithHypre(). */
PetscErrorCode SplitCSRCreateHypreMat(SplitCSR *S, MPI_Comm comm, PetscInt M, Mat *A);
/* Whether SplitCSRCreateHypreMat can share the arrays (PETSc has hypre, on the host, with PETSc's
 * integer and scalar types). */
PetscBool SplitCSRSharesWithHypre(void);
PetscErrorCode SplitCSRDestroy(SplitCSR *S);
