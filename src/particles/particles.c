#include "particles/particles.h"

const char *const ParticleKindNames[] = {"fluid", "wall", "dummy", "solid", "clamp"};

/* The field table (particles.h), indexed by FieldId. */
const FieldDesc FieldTable[FIELD_COUNT] = {
#define PARTICLE_FIELD_DESC(id, name, width, snapshot, checkpoint, xdmf) [id] = {name, width, snapshot, checkpoint, xdmf},
  PARTICLE_FIELDS(PARTICLE_FIELD_DESC)
#undef PARTICLE_FIELD_DESC
};

/* The table's rules that the compiler cannot check: each snapshot place once, a snapshot field
 * carried by checkpoints and shown in the XDMF as something (x: the geometry). */
static PetscErrorCode CheckTable(MPI_Comm comm)
{
  PetscBool placed[FIELD_COUNT + 1] = {PETSC_FALSE};
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    const FieldDesc *d = &FieldTable[f];
    if (!d->snapshot) continue;
    PetscCheck(d->snapshot > 0 && d->snapshot <= FIELD_COUNT && !placed[d->snapshot], comm, PETSC_ERR_PLIB, "Field table (particles.h): field %s has snapshot place %d, which is out of 1..%d or taken: give it the next free one", d->name, (int)d->snapshot, (int)FIELD_COUNT);
    PetscCheck(d->checkpoint, comm, PETSC_ERR_PLIB, "Field table (particles.h): field %s is in snapshots but not in checkpoints: last_good.xmf reads it from a checkpoint, so carry it", d->name);
    PetscCheck(d->xdmf != XDMF_NONE || f == FIELD_X, comm, PETSC_ERR_PLIB, "Field table (particles.h): field %s is in snapshots without an XDMF type: give it XDMF_SCALAR, XDMF_VECTOR or XDMF_SYM", d->name);
    placed[d->snapshot] = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscInt FieldWidth(PetscInt w, PetscInt dim)
{
  switch (w) {
  case WIDTH_VECTOR: return dim;
  case WIDTH_SYM: return dim * (dim + 1) / 2;
  case WIDTH_TENSOR: return dim * dim;
  default: return w;
  }
}

PetscErrorCode ParticlesCreate(MPI_Comm comm, Particles *P)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(P));
  (*P)->comm = comm;
  PetscCall(CheckTable(comm));
  for (PetscInt f = 0; f < FIELD_COUNT; f++) (*P)->f[f].name = FieldTable[f].name;
  PetscCall(ParticlesSetDimension(*P, 2));
  /* every scene needs these */
  PetscCall(ParticlesEnableField(*P, FIELD_X, PETSC_TRUE));
  PetscCall(ParticlesEnableField(*P, FIELD_V, PETSC_TRUE));
  PetscCall(ParticlesEnableField(*P, FIELD_RHO, PETSC_TRUE));
  PetscCall(ParticlesEnableField(*P, FIELD_P, PETSC_FALSE)); /* ghosts: from their density or a refresh */
  PetscCall(ParticlesEnableField(*P, FIELD_M, PETSC_TRUE));
  PetscCall(ParticlesEnableField(*P, FIELD_H, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesDestroy(Particles *P)
{
  PetscFunctionBeginUser;
  if (!*P) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt f = 0; f < FIELD_COUNT; f++) PetscCall(PetscFree((*P)->f[f].a));
  PetscCall(PetscFree2((*P)->id, (*P)->kind));
  PetscCall(PetscFree(*P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesEnableField(Particles P, FieldId f, PetscBool halo)
{
  PetscFunctionBeginUser;
  PetscCheck(!P->setup, P->comm, PETSC_ERR_ARG_WRONGSTATE, "Field %s enabled after ParticlesSetUp", P->f[f].name);
  P->f[f].on   = PETSC_TRUE;
  P->f[f].halo = (PetscBool)(P->f[f].halo || halo);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesSetDimension(Particles P, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCheck(!P->setup, P->comm, PETSC_ERR_ARG_WRONGSTATE, "The dimension is set before ParticlesSetUp");
  PetscCheck(dim == 2 || dim == 3, P->comm, PETSC_ERR_ARG_OUTOFRANGE, "Dimension %" PetscInt_FMT " must be 2 or 3", dim);
  P->dim = dim;
  for (PetscInt f = 0; f < FIELD_COUNT; f++) P->f[f].width = FieldWidth(FieldTable[f].width, dim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesSetUp(Particles P)
{
  PetscFunctionBeginUser;
  P->setup = PETSC_TRUE;
  PetscCall(ParticlesReserve(P, PetscMax(P->cap, 64)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesReserve(Particles P, PetscInt cap)
{
  PetscInt  *id, *kind, ntot = P->n + P->ng;
  PetscFunctionBeginUser;
  if (cap <= P->cap && P->id) PetscFunctionReturn(PETSC_SUCCESS);
  cap = PetscMax(cap, (3 * P->cap) / 2);
  PetscCall(PetscMalloc2(cap, &id, cap, &kind));
  if (ntot) {
    PetscCall(PetscArraycpy(id, P->id, ntot));
    PetscCall(PetscArraycpy(kind, P->kind, ntot));
  }
  PetscCall(PetscFree2(P->id, P->kind));
  P->id = id; P->kind = kind;
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    PetscReal *a;
    if (!P->f[f].on) continue;
    PetscCall(PetscCalloc1(cap * P->f[f].width, &a));
    if (ntot) PetscCall(PetscArraycpy(a, P->f[f].a, ntot * P->f[f].width));
    PetscCall(PetscFree(P->f[f].a));
    P->f[f].a = a;
  }
  P->cap = cap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesAdd(Particles P, PetscInt id, ParticleKind kind, const PetscReal x[], PetscReal m, PetscReal h, PetscReal rho)
{
  PetscInt i = P->n, D = P->dim;
  PetscFunctionBeginUser;
  PetscCheck(P->ng == 0, P->comm, PETSC_ERR_ARG_WRONGSTATE, "Particles added while ghosts exist");
  PetscCall(ParticlesReserve(P, i + 1));
  P->id[i] = id; P->kind[i] = kind;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on) PetscCall(PetscArrayzero(P->f[f].a + i * P->f[f].width, P->f[f].width));
  PetscCall(PetscArraycpy(P->f[FIELD_X].a + D * i, x, D));
  if (P->f[FIELD_X0].on) PetscCall(PetscArraycpy(P->f[FIELD_X0].a + D * i, x, D));
  P->f[FIELD_M].a[i] = m; P->f[FIELD_H].a[i] = h; P->f[FIELD_RHO].a[i] = rho;
  P->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesRemove(Particles P, const PetscBool *drop)
{
  PetscInt k = 0;
  PetscFunctionBeginUser;
  P->ng = 0;
  for (PetscInt i = 0; i < P->n; i++) {
    if (drop[i]) continue;
    if (k != i) {
      P->id[k] = P->id[i]; P->kind[k] = P->kind[i];
      for (PetscInt f = 0; f < FIELD_COUNT; f++)
        if (P->f[f].on) PetscCall(PetscArraycpy(P->f[f].a + k * P->f[f].width, P->f[f].a + i * P->f[f].width, P->f[f].width));
    }
    k++;
  }
  P->n = k;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesPermute(Particles P, const PetscInt *perm)
{
  PetscInt  n = P->n, *itmp, wmax = 1;
  PetscReal *rtmp;
  PetscFunctionBeginUser;
  P->ng = 0;
  for (PetscInt f = 0; f < FIELD_COUNT; f++) wmax = PetscMax(wmax, P->f[f].width);
  PetscCall(PetscMalloc2(n, &itmp, wmax * n, &rtmp));
  for (PetscInt i = 0; i < n; i++) itmp[i] = P->id[perm[i]];
  PetscCall(PetscArraycpy(P->id, itmp, n));
  for (PetscInt i = 0; i < n; i++) itmp[i] = P->kind[perm[i]];
  PetscCall(PetscArraycpy(P->kind, itmp, n));
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    PetscInt w = P->f[f].width;
    PetscReal *a = P->f[f].a;
    if (!P->f[f].on) continue;
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt k = 0; k < w; k++) rtmp[i * w + k] = a[perm[i] * w + k];
    PetscCall(PetscArraycpy(a, rtmp, n * w));
  }
  PetscCall(PetscFree2(itmp, rtmp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt ParticlesBytesPerParticle(Particles P)
{
  PetscInt b = 2 * (PetscInt)sizeof(PetscInt);
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on) b += P->f[f].width * (PetscInt)sizeof(PetscReal);
  return b;
}

PetscInt ParticlesSnapshotFields(Particles P, FieldId out[FIELD_COUNT])
{
  PetscInt n = 0;
  for (PetscInt k = 1; k <= FIELD_COUNT; k++)
    for (PetscInt f = 0; f < FIELD_COUNT; f++)
      if (FieldTable[f].snapshot == k && P->f[f].on) out[n++] = (FieldId)f;
  return n;
}

PetscErrorCode ParticlesGlobalCount(Particles P, PetscInt *N)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&P->n, N, 1, MPIU_INT, MPI_SUM, P->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesView(Particles P, PetscViewer v)
{
  PetscInt N, cnt[KIND_COUNT] = {0}, gcnt[KIND_COUNT];
  PetscFunctionBeginUser;
  PetscCall(ParticlesGlobalCount(P, &N));
  for (PetscInt i = 0; i < P->n; i++) cnt[P->kind[i]]++;
  PetscCall(MPIU_Allreduce(cnt, gcnt, KIND_COUNT, MPIU_INT, MPI_SUM, P->comm));
  PetscCall(PetscViewerASCIIPrintf(v, "Particles: %" PetscInt_FMT " (", N));
  for (PetscInt k = 0; k < KIND_COUNT; k++)
    if (gcnt[k]) PetscCall(PetscViewerASCIIPrintf(v, " %s %" PetscInt_FMT, ParticleKindNames[k], gcnt[k]));
  PetscCall(PetscViewerASCIIPrintf(v, " ), %" PetscInt_FMT " bytes/particle in fields:", ParticlesBytesPerParticle(P)));
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on) PetscCall(PetscViewerASCIIPrintf(v, " %s", P->f[f].name));
  PetscCall(PetscViewerASCIIPrintf(v, "\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
