#include "base/csr.h"

/* Room for n entries in a block (j, a of capacity *cap, len of them in use). */
static PetscErrorCode Grow(PetscInt n, PetscInt len, PetscInt *cap, PetscInt **j, PetscScalar **a);

PetscErrorCode SplitCSRBegin(SplitCSR *S, PetscInt m, PetscInt rstart, PetscInt bound)
{
  PetscFunctionBeginUser;
  if (bound > S->cap_d) { /* at once: growing by copies would leave the old arrays in the heap;
                           * 1/8 room above the bound, since the pair count drifts from step to
                           * step and each new block goes on top of the heap (the room is never
                           * written, so it takes no memory) */
    PetscCall(PetscFree2(S->dj, S->da));
    S->cap_d = bound + bound / 8;
    PetscCall(PetscMalloc2(S->cap_d, &S->dj, S->cap_d, &S->da));
  }
  if (m + 1 > S->cap_m) {
    PetscCall(PetscFree2(S->di, S->oi));
    S->cap_m = (PetscInt)(1.2 * m) + 16;
    PetscCall(PetscMalloc2(S->cap_m, &S->di, S->cap_m, &S->oi));
  }
  S->m = m; S->rstart = rstart; S->nrow = 0;
  S->di[0] = S->oi[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Grow(PetscInt n, PetscInt len, PetscInt *cap, PetscInt **j, PetscScalar **a)
{
  PetscInt    *nj;
  PetscScalar *na;
  PetscFunctionBeginUser;
  if (n <= *cap) PetscFunctionReturn(PETSC_SUCCESS);
  *cap = (3 * n) / 2 + 64;
  PetscCall(PetscMalloc2(*cap, &nj, *cap, &na));
  PetscCall(PetscArraycpy(nj, *j, len));
  PetscCall(PetscArraycpy(na, *a, len));
  PetscCall(PetscFree2(*j, *a));
  *j = nj; *a = na;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Insertion sort: the columns come nearly sorted (particles and rows follow the cells). */
static void SortRow(PetscInt n, PetscInt *j, PetscScalar *a)
{
  for (PetscInt k = 1; k < n; k++) {
    PetscInt    c = j[k], l = k;
    PetscScalar v = a[k];
    for (; l > 0 && j[l - 1] > c; l--) { j[l] = j[l - 1]; a[l] = a[l - 1]; }
    j[l] = c; a[l] = v;
  }
}

PetscErrorCode SplitCSRAppendRow(SplitCSR *S, PetscInt nc, const PetscInt cols[], const PetscScalar vals[])
{
  PetscInt r = S->nrow, d = S->di[r], o = S->oi[r];
  PetscFunctionBeginUser;
  PetscCheck(r < S->m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Appending row %" PetscInt_FMT " of a matrix of %" PetscInt_FMT " local rows", r, S->m);
  PetscCall(Grow(d + nc, d, &S->cap_d, &S->dj, &S->da));
  PetscCall(Grow(o + nc, o, &S->cap_o, &S->oj, &S->oa));
  for (PetscInt k = 0; k < nc; k++) {
    PetscInt c = cols[k] - S->rstart;
    if (c >= 0 && c < S->m) { S->dj[d] = c; S->da[d++] = vals[k]; }
    else { S->oj[o] = cols[k]; S->oa[o++] = vals[k]; }
  }
  SortRow(d - S->di[r], S->dj + S->di[r], S->da + S->di[r]);
  SortRow(o - S->oi[r], S->oj + S->oi[r], S->oa + S->oi[r]);
  S->di[r + 1] = d; S->oi[r + 1] = o;
  S->nrow++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SplitCSRCreateMat(SplitCSR *S, MPI_Comm comm, PetscInt M, Mat *A)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCheck(S->nrow == S->m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " of %" PetscInt_FMT " rows appended", S->nrow, S->m);
  PetscCall(Grow(1, S->di[S->m], &S->cap_d, &S->dj, &S->da)); /* non-null arrays for an empty block */
  PetscCall(Grow(1, S->oi[S->m], &S->cap_o, &S->oj, &S->oa));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) PetscCall(MatCreateSeqAIJWithArrays(comm, S->m, S->m, S->di, S->dj, S->da, A));
  else PetscCall(MatCreateMPIAIJWithSplitArrays(comm, S->m, S->m, M, M, S->di, S->dj, S->da, S->oi, S->oj, S->oa, A));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SplitCSRDestroy(SplitCSR *S)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(S->di, S->oi));
  PetscCall(PetscFree2(S->dj, S->da));
  PetscCall(PetscFree2(S->oj, S->oa));
  PetscCall(PetscMemzero(S, sizeof(*S)));
  PetscFunctionReturn(PETSC_SUCCESS);
}
