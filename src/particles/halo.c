#include "particles/halo.h"
#include "particles/exchange.h"
#include "base/dim.h"

PetscErrorCode HaloCreate(MPI_Comm comm, Halo *h)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(h));
  (*h)->comm  = comm;
  (*h)->stage = -1;
  for (PetscInt w = 1; w <= HALO_MAX_WIDTH; w++) {
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
  PetscCall(PetscSFDestroy(&(*h)->sf_kinds));
  PetscCall(PetscFree((*h)->kinds_ghost));
  PetscCall(PetscFree((*h)->shift));
  for (PetscInt w = 1; w <= HALO_MAX_WIDTH; w++) PetscCallMPI(MPI_Type_free(&(*h)->unit[w]));
  PetscCall(PetscFree(*h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Fields that are positions, which a periodic image shifts: the current and the reference
 * configuration (a solid across a periodic boundary). */
static PetscBool IsPosition(PetscInt f) { return (PetscBool)(f == FIELD_X || f == FIELD_X0); }

/* Ghost record: root index, shift code, id, kind, halo fields (positions shifted). */
static PetscInt GhostRecordSize(Particles P)
{
  PetscInt s = 4;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on && P->f[f].halo) s += P->f[f].width;
  return s;
}

/* Periodic image code of the shifts (sx, sy, sz) in {-1, 0, 1}: 13 is no shift */
#define HALO_NO_SHIFT 13
static inline PetscInt ShiftCode(PetscInt sx, PetscInt sy, PetscInt sz) { return 9 * (sz + 1) + 3 * (sy + 1) + (sx + 1); }
static inline PetscInt ShiftComponent(PetscInt code, PetscInt d) { return (d == 0 ? code % 3 : d == 1 ? (code / 3) % 3 : code / 9) - 1; }

static inline void ShiftOf(const Grid *g, PetscInt code, PetscReal s[3])
{
  for (PetscInt d = 0; d < 3; d++) s[d] = ShiftComponent(code, d) * (g->hi[d] - g->lo[d]);
}

/* The (particle, rank, periodic image) triples of the owned particles whose cells neighbour a cell of
 * another rank (or an image), in D dimensions (a constant: the loops unroll); counts per rank in scnt. */
typedef struct {
  PetscInt *pa, *pr, *pc, n, cap;
} HaloPairs;

SPH_INLINE PetscErrorCode CollectPairsD(const Grid *g, const Decomp d, const PetscReal *x, PetscInt n, HaloPairs *hp, PetscMPIInt *scnt, const PetscInt D)
{
  const PetscMPIInt rank = d->rank;
  PetscInt         *pa = hp->pa, *pr = hp->pr, *pc = hp->pc, np = hp->n, cap = hp->cap; /* locals: no reload after each store */
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < n; a++) {
    const PetscInt first = np;
    PetscInt       cc[3][3], sh[3][3], nc[3] = {1, 1, 1}; /* per direction: the neighbouring cell coordinates in reach and their periodic shifts */
    cc[2][0] = 0; sh[2][0] = 0;
    for (PetscInt d = 0; d < D; d++) {
      PetscInt c = GridCoord(g, x[D * a + d], d);
      nc[d]      = 0;
      for (PetscInt o = -1; o <= 1; o++) {
        PetscInt q = c + o, s = 0;
        if (g->periodic[d]) {
          if (q < 0) { q += g->n[d]; s = 1; }
          else if (q >= g->n[d]) { q -= g->n[d]; s = -1; }
        }
        if (q < 0 || q >= g->n[d]) continue;
        cc[d][nc[d]] = q; sh[d][nc[d]] = s; nc[d]++;
      }
    }
    for (PetscInt kk = 0; kk < nc[2]; kk++)
      for (PetscInt jj = 0; jj < nc[1]; jj++)
        for (PetscInt ii = 0; ii < nc[0]; ii++) {
          PetscInt    code = ShiftCode(sh[0][ii], sh[1][jj], sh[2][kk]);
          PetscMPIInt r    = d->owner[GridIndex(g, cc[0][ii], cc[1][jj], cc[2][kk])];
          PetscBool   dup  = PETSC_FALSE;
          if (r == rank && code == HALO_NO_SHIFT) continue;
          for (PetscInt k = first; k < np; k++)
            if (pr[k] == r && pc[k] == code) dup = PETSC_TRUE;
          if (dup) continue;
          if (np == cap) {
            PetscInt *na, *nr, *ncp;
            cap *= 2;
            PetscCall(PetscMalloc3(cap, &na, cap, &nr, cap, &ncp));
            PetscCall(PetscArraycpy(na, pa, np)); PetscCall(PetscArraycpy(nr, pr, np)); PetscCall(PetscArraycpy(ncp, pc, np));
            PetscCall(PetscFree3(pa, pr, pc));
            pa = na; pr = nr; pc = ncp;
          }
          pa[np] = a; pr[np] = r; pc[np] = code; np++;
          scnt[r]++;
        }
  }
  hp->pa = pa; hp->pr = pr; hp->pc = pc; hp->n = np; hp->cap = cap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HaloBuild(Halo h, Decomp d, Particles P)
{
  const Grid  *g = d->grid;
  PetscMPIInt  size = d->size, *scnt, *rcnt, *sdisp, *rdisp, *fill;
  PetscInt     rs = GhostRecordSize(P), n = P->n, nsend = 0, nrecv, npair = 0, cap_pair;
  PetscInt    *pa, *pr, *pc; /* (particle, rank, shift code) to send */
  PetscReal   *sbuf, *rbuf, *x = PField(P, FIELD_X);
  PetscSFNode *remote;

  PetscFunctionBeginUser;
  P->ng    = 0;
  cap_pair = n + 16;
  for (PetscInt d = 0; d < 3; d++) h->period[d] = g->hi[d] - g->lo[d];
  PetscCall(PetscMalloc3(cap_pair, &pa, cap_pair, &pr, cap_pair, &pc));
  PetscCall(PetscCalloc4(size, &scnt, size, &rcnt, size + 1, &sdisp, size + 1, &rdisp));
  {
    HaloPairs hp = {pa, pr, pc, 0, cap_pair};
    PetscCall(SPH_DIM_DISPATCH(g->dim, CollectPairsD, g, d, x, n, &hp, scnt));
    pa = hp.pa; pr = hp.pr; pc = hp.pc; npair = hp.n;
  }
  nsend = npair;
  for (PetscMPIInt r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scnt[r];
  PetscCall(PetscMalloc1(nsend * rs + 1, &sbuf));
  PetscCall(PetscMalloc1(size, &fill));
  for (PetscMPIInt r = 0; r < size; r++) fill[r] = sdisp[r];
  for (PetscInt k = 0; k < npair; k++) {
    PetscReal *rec_ = sbuf + (fill[pr[k]]++) * rs, s[3];
    PetscInt   a = pa[k], q = 0;
    ShiftOf(g, pc[k], s);
    rec_[q++] = (PetscReal)a; rec_[q++] = (PetscReal)pc[k];
    rec_[q++] = (PetscReal)P->id[a]; rec_[q++] = (PetscReal)P->kind[a];
    for (PetscInt f = 0; f < FIELD_COUNT; f++) {
      if (!P->f[f].on || !P->f[f].halo) continue;
      for (PetscInt w = 0; w < P->f[f].width; w++) rec_[q++] = P->f[f].a[a * P->f[f].width + w] + (IsPosition(f) ? s[w] : 0.0);
    }
  }
  PetscCall(PetscFree(fill));
  h->nghost_sent = nsend;
  h->nbr_send     = 0;
  for (PetscMPIInt r = 0; r < size; r++) h->nbr_send += r != d->rank && scnt[r] > 0;
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
  PetscCall(PetscSFDestroy(&h->sf_kinds)); /* a new ghost set: the kinds' SF is rebuilt when used */
  h->kinds = NULL;
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

/* Bcast of the fields over sf, whose leaves are the ghosts ghost[0 .. n) (NULL: all ghosts, in
 * order), then the periodic shift of the positions among them. */
static PetscErrorCode Refresh(Halo h, Particles P, PetscSF sf, const PetscInt *ghost, PetscInt n, PetscInt nf, const FieldId f[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < nf; k++) {
    Field *F = &P->f[f[k]];
    PetscCheck(F->on, h->comm, PETSC_ERR_ARG_WRONGSTATE, "Halo refresh of field %s, which this scene does not allocate", F->name);
    PetscCall(PetscSFBcastBegin(sf, h->unit[F->width], F->a, F->a + P->n * F->width, MPI_REPLACE));
  }
  for (PetscInt k = 0; k < nf; k++) {
    Field *F = &P->f[f[k]];
    PetscCall(PetscSFBcastEnd(sf, h->unit[F->width], F->a, F->a + P->n * F->width, MPI_REPLACE));
    if (!IsPosition(f[k])) continue;
    for (PetscInt i = 0; i < n; i++) { /* periodic images: the same shift the build applied */
      PetscInt j = ghost ? ghost[i] : i, code = h->shift[j];
      if (code == HALO_NO_SHIFT) continue;
      for (PetscInt d = 0; d < P->dim; d++) F->a[P->dim * (P->n + j) + d] += h->period[d] * ShiftComponent(code, d);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode StagePush(Halo h)
{
  PetscFunctionBeginUser;
  if (h->stage >= 0) PetscCall(PetscLogStagePush(h->stage));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode StagePop(Halo h)
{
  PetscFunctionBeginUser;
  if (h->stage >= 0) PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HaloRefresh(Halo h, Particles P, PetscInt nf, const FieldId f[])
{
  PetscFunctionBeginUser;
  PetscCall(StagePush(h));
  PetscCall(Refresh(h, P, h->sf, NULL, P->ng, nf, f));
  PetscCall(StagePop(h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The SF from the owners to the ghosts of the kinds keep accepts. */
static PetscErrorCode KindsSF(Halo h, Particles P, PetscBool (*keep)(PetscInt))
{
  const PetscSFNode *all;
  PetscSFNode       *remote;
  PetscInt           n = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscSFDestroy(&h->sf_kinds));
  PetscCall(PetscFree(h->kinds_ghost));
  PetscCall(PetscSFGetGraph(h->sf, NULL, NULL, NULL, &all));
  PetscCall(PetscMalloc1(P->ng + 1, &h->kinds_ghost));
  PetscCall(PetscMalloc1(P->ng + 1, &remote));
  for (PetscInt j = 0; j < P->ng; j++)
    if (keep(P->kind[P->n + j])) { h->kinds_ghost[n] = j; remote[n++] = all[j]; }
  PetscCall(PetscSFCreate(h->comm, &h->sf_kinds));
  PetscCall(PetscSFSetGraph(h->sf_kinds, P->n, n, h->kinds_ghost, PETSC_COPY_VALUES, remote, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(h->sf_kinds));
  h->nkinds = n;
  h->kinds  = keep;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HaloRefreshKinds(Halo h, Particles P, PetscBool (*keep)(PetscInt), PetscInt nf, const FieldId f[])
{
  PetscFunctionBeginUser;
  PetscCall(StagePush(h));
  if (!h->sf_kinds || h->kinds != keep) PetscCall(KindsSF(h, P, keep));
  PetscCall(Refresh(h, P, h->sf_kinds, h->kinds_ghost, h->nkinds, nf, f));
  PetscCall(StagePop(h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Compact arrays that only some particles carry (slot[a] >= 0; the owned ones' slots first, then the
 * ghosts'): the SF from each owner's slot to its ghosts' slots, whose leaves index the array past
 * the nown owned slots.  The owners' slots reach the ghosts over the halo's own SF. */
PetscErrorCode HaloSlotSF(Halo h, Particles P, const PetscInt *slot, PetscInt nown, PetscSF *sf)
{
  const PetscSFNode *all;
  PetscSFNode       *remote;
  PetscInt          *ghost_slot, *ilocal, n = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscSFDestroy(sf));
  PetscCall(PetscSFGetGraph(h->sf, NULL, NULL, NULL, &all));
  PetscCall(PetscMalloc3(P->ng + 1, &ghost_slot, P->ng + 1, &ilocal, P->ng + 1, &remote));
  PetscCall(PetscSFBcastBegin(h->sf, MPIU_INT, slot, ghost_slot, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(h->sf, MPIU_INT, slot, ghost_slot, MPI_REPLACE));
  for (PetscInt j = 0; j < P->ng; j++) {
    if (slot[P->n + j] < 0) continue;
    PetscCheck(ghost_slot[j] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Ghost %" PetscInt_FMT " has a slot but its owner has none", j);
    ilocal[n]         = slot[P->n + j] - nown;
    remote[n].rank    = all[j].rank;
    remote[n++].index = ghost_slot[j];
  }
  PetscCall(PetscSFCreate(h->comm, sf));
  PetscCall(PetscSFSetGraph(*sf, nown, n, ilocal, PETSC_COPY_VALUES, remote, PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(*sf));
  PetscCall(PetscFree3(ghost_slot, ilocal, remote));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The owners' values of compact arrays a[k] (width[k] reals a slot, at most HALO_MAX_WIDTH) into
 * their ghosts' slots, over an SF of HaloSlotSF. */
PetscErrorCode HaloRefreshSlots(Halo h, PetscSF sf, PetscInt nown, PetscInt na, const PetscInt width[], PetscReal *const a[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < na; k++) PetscCheck(width[k] >= 1 && width[k] <= HALO_MAX_WIDTH, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Halo refresh of %" PetscInt_FMT " reals a slot: raise HALO_MAX_WIDTH (%d)", width[k], HALO_MAX_WIDTH);
  PetscCall(StagePush(h));
  for (PetscInt k = 0; k < na; k++) PetscCall(PetscSFBcastBegin(sf, h->unit[width[k]], a[k], a[k] + nown * width[k], MPI_REPLACE));
  for (PetscInt k = 0; k < na; k++) PetscCall(PetscSFBcastEnd(sf, h->unit[width[k]], a[k], a[k] + nown * width[k], MPI_REPLACE));
  PetscCall(StagePop(h));
  PetscFunctionReturn(PETSC_SUCCESS);
}
