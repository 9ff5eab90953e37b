#include <sphfsi/halo.h>
#include <sphfsi/exchange.h>

PetscErrorCode HaloCreate(MPI_Comm comm, Halo *h)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(h));
  (*h)->comm = comm;
  for (PetscInt w = 1; w <= 25; w++) {
    PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)w, MPIU_REAL, &(*h)->unit[w]));
    PetscCallMPI(MPI_Type_commit(&(*h)->unit[w]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HaloDestroy(Halo *h)
{
  PetscFunctionBeginUser;
  if (!*h) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSFDestroy(&(*h)->sf));
  PetscCall(PetscFree((*h)->shift));
  for (PetscInt w = 1; w <= 25; w++) PetscCallMPI(MPI_Type_free(&(*h)->unit[w]));
  PetscCall(PetscFree(*h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Ghost record: root index, shift code, id, kind, halo fields (positions shifted). */
static PetscInt GhostRecordSize(Particles P)
{
  PetscInt s = 4;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on && P->f[f].halo) s += P->f[f].width;
  return s;
}

static inline void ShiftOf(const Grid *g, PetscInt code, PetscReal s[2])
{
  s[0] = (code % 3 - 1) * (g->hi[0] - g->lo[0]);
  s[1] = (code / 3 - 1) * (g->hi[1] - g->lo[1]);
}

PetscErrorCode HaloBuild(Halo h, Decomp d, Particles P)
{
  const Grid  *g = d->grid;
  PetscMPIInt  size = d->size, rank = d->rank, *scnt, *rcnt, *sdisp, *rdisp, *fill;
  PetscInt     rs = GhostRecordSize(P), n = P->n, nsend = 0, nrecv, npair = 0, cap_pair;
  PetscInt    *pa, *pr, *pc; /* (particle, rank, shift code) to send */
  PetscReal   *sbuf, *rbuf, *x = PField(P, FIELD_X);
  PetscSFNode *remote;

  PetscFunctionBeginUser;
  P->ng    = 0;
  cap_pair = n + 16;
  h->period[0] = g->hi[0] - g->lo[0];
  h->period[1] = g->hi[1] - g->lo[1];
  PetscCall(PetscMalloc3(cap_pair, &pa, cap_pair, &pr, cap_pair, &pc));
  PetscCall(PetscCalloc4(size, &scnt, size, &rcnt, size + 1, &sdisp, size + 1, &rdisp));
  for (PetscInt a = 0; a < n; a++) {
    PetscInt i = GridCoord(g, x[2 * a], 0), j = GridCoord(g, x[2 * a + 1], 1), first = npair;
    for (PetscInt dj = -1; dj <= 1; dj++)
      for (PetscInt di = -1; di <= 1; di++) {
        PetscInt    ii = i + di, jj = j + dj, sx = 0, sy = 0, code;
        PetscMPIInt r;
        PetscBool   dup = PETSC_FALSE;
        if (g->periodic[0]) { if (ii < 0) { ii += g->n[0]; sx = 1; } else if (ii >= g->n[0]) { ii -= g->n[0]; sx = -1; } }
        if (g->periodic[1]) { if (jj < 0) { jj += g->n[1]; sy = 1; } else if (jj >= g->n[1]) { jj -= g->n[1]; sy = -1; } }
        if (ii < 0 || jj < 0 || ii >= g->n[0] || jj >= g->n[1]) continue;
        r    = d->owner[jj * g->n[0] + ii];
        code = 3 * (sy + 1) + (sx + 1);
        if (r == rank && code == 4) continue;
        for (PetscInt k = first; k < npair; k++)
          if (pr[k] == r && pc[k] == code) dup = PETSC_TRUE;
        if (dup) continue;
        if (npair == cap_pair) {
          PetscInt *na, *nr, *nc;
          cap_pair *= 2;
          PetscCall(PetscMalloc3(cap_pair, &na, cap_pair, &nr, cap_pair, &nc));
          PetscCall(PetscArraycpy(na, pa, npair)); PetscCall(PetscArraycpy(nr, pr, npair)); PetscCall(PetscArraycpy(nc, pc, npair));
          PetscCall(PetscFree3(pa, pr, pc));
          pa = na; pr = nr; pc = nc;
        }
        pa[npair] = a; pr[npair] = r; pc[npair] = code; npair++;
        scnt[r]++;
      }
  }
  nsend = npair;
  for (PetscMPIInt r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scnt[r];
  PetscCall(PetscMalloc1(nsend * rs + 1, &sbuf));
  PetscCall(PetscMalloc1(size, &fill));
  for (PetscMPIInt r = 0; r < size; r++) fill[r] = sdisp[r];
  for (PetscInt k = 0; k < npair; k++) {
    PetscReal *rec_ = sbuf + (fill[pr[k]]++) * rs, s[2];
    PetscInt   a = pa[k], q = 0;
    ShiftOf(g, pc[k], s);
    rec_[q++] = (PetscReal)a; rec_[q++] = (PetscReal)pc[k];
    rec_[q++] = (PetscReal)P->id[a]; rec_[q++] = (PetscReal)P->kind[a];
    for (PetscInt f = 0; f < FIELD_COUNT; f++) {
      if (!P->f[f].on || !P->f[f].halo) continue;
      for (PetscInt w = 0; w < P->f[f].width; w++) rec_[q++] = P->f[f].a[a * P->f[f].width + w] + (f == FIELD_X ? s[w] : 0.0);
    }
  }
  PetscCall(PetscFree(fill));
  h->nghost_sent = nsend;
  PetscCall(ExchangeRecords(d->comm, d->sparse, rs, scnt, sdisp, sbuf, rcnt, rdisp, &rbuf, &nrecv));

  PetscCall(ParticlesReserve(P, n + nrecv));
  if (nrecv > h->cap_shift) {
    PetscCall(PetscFree(h->shift));
    h->cap_shift = (3 * nrecv) / 2 + 16;
    PetscCall(PetscMalloc1(h->cap_shift, &h->shift));
  }
  PetscCall(PetscMalloc1(nrecv, &remote));
  for (PetscMPIInt r = 0; r < size; r++)
    for (PetscInt k = rdisp[r]; k < rdisp[r + 1]; k++) {
      const PetscReal *rec_ = rbuf + k * rs;
      PetscInt         b = n + k, q = 4;
      remote[k].rank  = r;
      remote[k].index = (PetscInt)rec_[0];
      h->shift[k]     = (PetscInt)rec_[1];
      P->id[b]        = (PetscInt)rec_[2];
      P->kind[b]      = (PetscInt)rec_[3];
      for (PetscInt f = 0; f < FIELD_COUNT; f++) {
        if (!P->f[f].on) continue;
        if (!P->f[f].halo) { PetscCall(PetscArrayzero(P->f[f].a + b * P->f[f].width, P->f[f].width)); continue; }
        for (PetscInt w = 0; w < P->f[f].width; w++) P->f[f].a[b * P->f[f].width + w] = rec_[q++];
      }
    }
  P->ng = nrecv;
  PetscCall(PetscSFDestroy(&h->sf));
  PetscCall(PetscSFCreate(d->comm, &h->sf));
  /* leaves are contiguous: leafdata starts at the first ghost, never aliasing the roots */
  PetscCall(PetscSFSetGraph(h->sf, n, nrecv, NULL, PETSC_COPY_VALUES, remote, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(h->sf));
  PetscCall(PetscFree(sbuf));
  PetscCall(PetscFree(rbuf));
  PetscCall(PetscFree3(pa, pr, pc));
  PetscCall(PetscFree4(scnt, rcnt, sdisp, rdisp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HaloRefresh(Halo h, Particles P, PetscInt nf, const FieldId f[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < nf; k++) {
    Field *F = &P->f[f[k]];
    PetscCheck(F->on, h->comm, PETSC_ERR_ARG_WRONGSTATE, "Halo refresh of field %s, which this scene does not allocate", F->name);
    PetscCall(PetscSFBcastBegin(h->sf, h->unit[F->width], F->a, F->a + P->n * F->width, MPI_REPLACE));
  }
  for (PetscInt k = 0; k < nf; k++) {
    Field *F = &P->f[f[k]];
    PetscCall(PetscSFBcastEnd(h->sf, h->unit[F->width], F->a, F->a + P->n * F->width, MPI_REPLACE));
    if (f[k] == FIELD_X) {
      /* periodic images: the same shift the build applied */
      for (PetscInt j = 0; j < P->ng; j++) {
        PetscInt code = h->shift[j];
        if (code == 4) continue;
        F->a[2 * (P->n + j)] += h->period[0] * (code % 3 - 1);
        F->a[2 * (P->n + j) + 1] += h->period[1] * (code / 3 - 1);
      }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
