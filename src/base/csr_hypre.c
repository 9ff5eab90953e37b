/* SplitCSR rows handed to hypre as a ParCSR matrix without a copy (csr.h). */
#include "base/csr.h"
#if defined(PETSC_HAVE_HYPRE)
  #include <petscmathypre.h>
  #include <_hypre_parcsr_mv.h>
#endif

#if defined(PETSC_HAVE_HYPRE) && !defined(HYPRE_USING_GPU)
/* Each row's diagonal entry first, where hypre's smoothers look for it, swapped with the row's first
 * entry as hypre's own assembly does (hypre_CSRMatrixReorder): the smoother then visits the entries
 * in the order it did when PETSc converted an AIJ matrix, so the runs are the same bit for bit. */
static PetscErrorCode DiagonalFirst(SplitCSR *S)
{
  PetscFunctionBeginUser;
  for (PetscInt r = 0; r < S->m; r++) {
    PetscInt    s = S->di[r], e = S->di[r + 1], k = s, c;
    PetscScalar v;
    while (k < e && S->dj[k] != r) k++;
    PetscCheck(k < e, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Row %" PetscInt_FMT " has no diagonal entry", S->rstart + r);
    c = S->dj[k]; v = S->da[k];
    S->dj[k] = S->dj[s]; S->da[k] = S->da[s];
    S->dj[s] = c; S->da[s] = v;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The off-diagonal block's global columns, sorted and without repeats, into a map that hypre owns
 * (allocated for every entry, then sorted in place: no scratch array); the block's columns become
 * indices into it.  HYPRE_BigInt is PetscInt here (SplitCSRCreateHypreMat). */
static PetscErrorCode OffDiagonalMap(SplitCSR *S, HYPRE_BigInt **map, PetscInt *ncol)
{
  PetscInt  no = S->oi[S->m], *cols;
  PetscFunctionBeginUser;
  *map = hypre_CTAlloc(HYPRE_BigInt, no, HYPRE_MEMORY_HOST);
  cols = (PetscInt *)*map;
  PetscCall(PetscArraycpy(cols, S->oj, no));
  *ncol = no;
  PetscCall(PetscSortRemoveDupsInt(ncol, cols));
  for (PetscInt k = 0; k < no; k++) PetscCall(PetscFindInt(S->oj[k], *ncol, cols, &S->oj[k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A block of the ParCSR matrix on our j and a arrays (hypre frees only its own row pointers). */
static void ShareBlock(hypre_CSRMatrix *B, PetscInt m, const PetscInt *i, PetscInt *j, PetscScalar *a)
{
  HYPRE_Int *hi = hypre_CTAlloc(HYPRE_Int, m + 1, HYPRE_MEMORY_HOST);
  for (PetscInt r = 0; r <= m; r++) hi[r] = (HYPRE_Int)i[r];
  hypre_CSRMatrixI(B)         = hi;
  hypre_CSRMatrixJ(B)         = (HYPRE_Int *)j;
  hypre_CSRMatrixData(B)      = (HYPRE_Complex *)a;
  hypre_CSRMatrixOwnsData(B)  = 0;
}
#endif

PetscBool SplitCSRSharesWithHypre(void)
{
#if defined(PETSC_HAVE_HYPRE) && !defined(HYPRE_USING_GPU)
  return (PetscBool)(sizeof(HYPRE_Int) == sizeof(PetscInt) && sizeof(HYPRE_BigInt) == sizeof(PetscInt) && sizeof(HYPRE_Complex) == sizeof(PetscScalar));
#else
  return PETSC_FALSE;
#endif
}

PetscErrorCode SplitCSRCreateHypreMat(SplitCSR *S, MPI_Comm comm, PetscInt M, Mat *A)
{
  PetscFunctionBeginUser;
  *A = NULL;
  PetscCheck(SplitCSRSharesWithHypre(), comm, PETSC_ERR_SUP, "hypre cannot share these arrays (no hypre, hypre on a GPU, or other integer/scalar types than PETSc's): use an AIJ matrix");
#if defined(PETSC_HAVE_HYPRE) && !defined(HYPRE_USING_GPU)
  {
    hypre_ParCSRMatrix *H;
    HYPRE_BigInt       *map = NULL, range[2] = {(HYPRE_BigInt)S->rstart, (HYPRE_BigInt)(S->rstart + S->m)};
    PetscInt            ncol;
    PetscCheck(S->nrow == S->m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " of %" PetscInt_FMT " rows appended", S->nrow, S->m);
    PetscCall(DiagonalFirst(S));
    PetscCall(OffDiagonalMap(S, &map, &ncol));
    H = hypre_ParCSRMatrixCreate(comm, (HYPRE_BigInt)M, (HYPRE_BigInt)M, range, range, (HYPRE_Int)ncol, (HYPRE_Int)S->di[S->m], (HYPRE_Int)S->oi[S->m]);
    PetscCheck(H, PETSC_COMM_SELF, PETSC_ERR_LIB, "hypre_ParCSRMatrixCreate failed");
    ShareBlock(hypre_ParCSRMatrixDiag(H), S->m, S->di, S->dj, S->da);
    ShareBlock(hypre_ParCSRMatrixOffd(H), S->m, S->oi, S->oj, S->oa);
    hypre_ParCSRMatrixColMapOffd(H) = map;
    PetscCallExternal(hypre_CSRMatrixSetRownnz, hypre_ParCSRMatrixOffd(H)); /* the matvec skips empty off-diagonal rows */
    PetscCallExternal(hypre_ParCSRMatrixSetNumNonzeros, H);
    PetscCallExternal(hypre_ParCSRMatrixSetDNumNonzeros, H);
    PetscCall(MatCreateFromParCSR(H, MATHYPRE, PETSC_OWN_POINTER, A));
  }
#endif
  PetscFunctionReturn(PETSC_SUCCESS);
}
