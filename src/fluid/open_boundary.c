#include "fluid/open_boundary.h"
#include "particles/pair_loop.h"
#include <stdio.h>

static const char *const OpenNames[] = {"inlet", "outlet"};

PetscErrorCode OpenCreate(Open *open)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(open));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OpenDestroy(Open *open)
{
  PetscFunctionBeginUser;
  if (!*open) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt k = 0; k < (*open)->n; k++) PetscCall(SeriesDestroy(&(*open)->table[k]));
  PetscCall(PetscFree6((*open)->parent, (*open)->zone, (*open)->xnew, (*open)->mnew, (*open)->hnew, (*open)->rnew));
  PetscCall(PetscFree(*open));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A table "s u" a line ('#' comments), read on rank 0 and sent to all. */
static PetscErrorCode ReadTable(MPI_Comm comm, const char *file, PetscInt k, Series *s)
{
  PetscMPIInt rank;
  PetscInt    n   = 0;
  PetscReal  *buf = NULL;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE *f = fopen(file, "r");
    char  line[512];
    if (f) {
      while (fgets(line, sizeof(line), f)) {
        double a, b;
        if (line[0] == '#' || sscanf(line, "%lf%*[ ,\t]%lf", &a, &b) != 2) continue;
        PetscCall(SeriesAppend(s, (PetscReal)a, (PetscReal)b));
      }
      fclose(f);
      n = s->n;
    } else n = -1;
  }
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCheck(n >= 0, comm, PETSC_ERR_FILE_OPEN, "Open boundary %" PetscInt_FMT ": cannot read the profile table %s", k + 1, file);
  PetscCheck(n >= 2, comm, PETSC_ERR_FILE_UNEXPECTED, "Open boundary %" PetscInt_FMT ": the profile table %s has %" PetscInt_FMT " lines \"s u\"; it needs at least 2", k + 1, file, n);
  PetscCall(PetscMalloc1(2 * n, &buf));
  if (!rank)
    for (PetscInt i = 0; i < n; i++) { buf[2 * i] = s->t[i]; buf[2 * i + 1] = s->y[i]; }
  PetscCallMPI(MPI_Bcast(buf, 2 * n, MPIU_REAL, 0, comm));
  if (rank)
    for (PetscInt i = 0; i < n; i++) PetscCall(SeriesAppend(s, buf[2 * i], buf[2 * i + 1]));
  for (PetscInt i = 1; i < n; i++) PetscCheck(s->t[i] > s->t[i - 1], comm, PETSC_ERR_FILE_UNEXPECTED, "Open boundary %" PetscInt_FMT ": the profile table %s must list s increasing (line %" PetscInt_FMT ")", k + 1, file, i + 1);
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OpenAdd(Physics *ph, Open open, const OpenBoundarySpec *spec, const PetscReal dom_lo[], const PetscReal dom_hi[])
{
  const PetscInt k = open->n, D = ph->dim;
  PetscFunctionBeginUser;
  PetscCheck(k < OPEN_MAX, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "At most %d open boundaries", OPEN_MAX);
  PetscCheck(spec->kind == OPEN_INLET || spec->kind == OPEN_OUTLET, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT ": its kind must be an inlet or an outlet", k + 1);
  PetscCheck(spec->axis >= 0 && spec->axis < D, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT ": its axis %" PetscInt_FMT " must be 0 to %" PetscInt_FMT, k + 1, spec->axis, D - 1);
  PetscCheck(spec->side == -1 || spec->side == 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT ": its side must be -1 (the buffer below the plane) or +1", k + 1);
  PetscCheck(spec->rows >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT ": rows %" PetscInt_FMT " must be >= 0", k + 1, spec->rows);
  for (PetscInt d = 0; d < D; d++)
    if (d != spec->axis) PetscCheck(spec->hi[d] > spec->lo[d], ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT " (%s): its cross-section %g..%g in direction %" PetscInt_FMT " is empty", k + 1, OpenNames[spec->kind], (double)spec->lo[d], (double)spec->hi[d], d + 1);
  PetscCheck(spec->plane > dom_lo[spec->axis] && spec->plane < dom_hi[spec->axis], ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT " (%s): its plane %g is outside the domain %g..%g", k + 1, OpenNames[spec->kind], (double)spec->plane, (double)dom_lo[spec->axis], (double)dom_hi[spec->axis]);
  if (spec->kind == OPEN_INLET) {
    PetscCheck(spec->velocity > 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Inlet %" PetscInt_FMT ": its velocity %g points out of the domain; an inlet's mean speed into the domain must be > 0", k + 1, (double)spec->velocity);
    PetscCheck(spec->ramp >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Inlet %" PetscInt_FMT ": its ramp time %g must be >= 0", k + 1, (double)spec->ramp);
    PetscCheck(spec->profile >= PROFILE_UNIFORM && spec->profile <= PROFILE_TABLE, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Inlet %" PetscInt_FMT ": unknown profile", k + 1);
    if (spec->profile == PROFILE_TABLE) {
      PetscCheck(D == 2, ph->comm, PETSC_ERR_ARG_INCOMP, "Inlet %" PetscInt_FMT ": a profile table is for 2D inlets (3D: uniform or parabolic)", k + 1);
      PetscCall(ReadTable(ph->comm, spec->table, k, &open->table[k]));
      for (PetscInt i = 0; i < open->table[k].n; i++) PetscCheck(open->table[k].y[i] >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Inlet %" PetscInt_FMT ": the profile table %s has u = %g < 0 at s = %g: the profile points out of the domain", k + 1, spec->table, (double)open->table[k].y[i], (double)open->table[k].t[i]);
    }
  }
  open->b[k] = *spec;
  open->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether point x lies in boundary k's buffer: beyond the plane on its side, within depth of it and
 * inside the cross-section (tol: the margin around the section and the far end). */
static PetscBool InBuffer(const OpenBoundarySpec *b, const PetscReal *x, PetscReal depth, PetscReal tol, PetscInt D)
{
  const PetscReal s = (x[b->axis] - b->plane) * b->side;
  if (s <= 0 || s > depth + tol) return PETSC_FALSE;
  for (PetscInt d = 0; d < D; d++)
    if (d != b->axis && (x[d] < b->lo[d] - tol || x[d] > b->hi[d] + tol)) return PETSC_FALSE;
  return PETSC_TRUE;
}

/* Inside the cross-section (the buffer's or the plane's) */
static PetscBool InSection(const OpenBoundarySpec *b, const PetscReal *x, PetscReal tol, PetscInt D)
{
  for (PetscInt d = 0; d < D; d++)
    if (d != b->axis && (x[d] < b->lo[d] - tol || x[d] > b->hi[d] + tol)) return PETSC_FALSE;
  return PETSC_TRUE;
}

PetscErrorCode OpenSetUp(Physics *ph)
{
  Open             open = ph->open;
  Particles        P    = ph->P;
  const PetscInt   D    = ph->dim;
  const PetscReal *x    = PField(P, FIELD_X), tol = 0.25 * ph->dx;
  PetscReal       *zone = PField(P, FIELD_OPEN);
  PetscInt         bad[2] = {-1, -1}; /* a wall particle in a buffer: its boundary, and that of an overlap */
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < open->n; k++) {
    OpenBoundarySpec *b = &open->b[k];
    if (b->rows == 0) b->rows = KernelSupportRows(&ph->kernel);
    PetscCheck(b->rows * ph->dx >= 2 * ph->kernel.h_factor * ph->dx * (1 - 1e-9), ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "Open boundary %" PetscInt_FMT " (%s): its buffer of %" PetscInt_FMT " rows (%g m) is thinner than the kernel's reach 2h = %g m: give at least %" PetscInt_FMT " rows", k + 1, OpenNames[b->kind], b->rows, (double)(b->rows * ph->dx), (double)(2 * ph->kernel.h_factor * ph->dx), KernelSupportRows(&ph->kernel));
    for (PetscInt j = 0; j < k; j++) { /* two buffers sharing space */
      const OpenBoundarySpec *c = &open->b[j];
      PetscBool               apart = PETSC_FALSE;
      for (PetscInt d = 0; d < D; d++) {
        PetscReal lo1 = b->lo[d], hi1 = b->hi[d], lo2 = c->lo[d], hi2 = c->hi[d];
        if (d == b->axis) { lo1 = PetscMin(b->plane, b->plane + b->side * b->rows * ph->dx); hi1 = PetscMax(b->plane, b->plane + b->side * b->rows * ph->dx); }
        if (d == c->axis) { lo2 = PetscMin(c->plane, c->plane + c->side * c->rows * ph->dx); hi2 = PetscMax(c->plane, c->plane + c->side * c->rows * ph->dx); }
        if (hi1 <= lo2 + tol || hi2 <= lo1 + tol) apart = PETSC_TRUE;
      }
      PetscCheck(apart, ph->comm, PETSC_ERR_ARG_INCOMP, "Open boundary %" PetscInt_FMT " (%s) overlaps open boundary %" PetscInt_FMT " (%s): their buffers share space", k + 1, OpenNames[b->kind], j + 1, OpenNames[c->kind]);
    }
  }
  for (PetscInt a = 0; a < P->n; a++) {
    zone[a] = 0;
    for (PetscInt k = 0; k < open->n; k++) {
      if (!InBuffer(&open->b[k], x + D * a, open->b[k].rows * ph->dx, -tol, D)) continue;
      if (KindIsFluid(P->kind[a])) zone[a] = k + 1;
      else bad[0] = k;
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bad, 1, MPIU_INT, MPI_MAX, ph->comm));
  PetscCheck(bad[0] < 0, ph->comm, PETSC_ERR_ARG_INCOMP, "Open boundary %" PetscInt_FMT " (%s) overlaps a wall or a solid: its buffer (%" PetscInt_FMT " rows beyond its plane, across its cross-section) must hold fluid only", bad[0] + 1, OpenNames[open->b[bad[0]].kind], open->b[bad[0]].rows);
  PetscCall(OpenImpose(ph, ph->t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The inlet's normal speed at x, time t */
static PetscReal InletSpeed(const Open open, PetscInt k, const PetscReal *x, PetscReal t, PetscInt D)
{
  const OpenBoundarySpec *b = &open->b[k];
  PetscReal               u = b->velocity;
  for (PetscInt d = 0; d < D; d++) {
    PetscReal s;
    if (d == b->axis) continue;
    s = PetscClipInterval((x[d] - b->lo[d]) / (b->hi[d] - b->lo[d]), 0, 1);
    if (b->profile == PROFILE_PARABOLIC) u *= 6 * s * (1 - s); /* mean 1 over the section in each direction */
    else if (b->profile == PROFILE_TABLE) u = SeriesAt(&open->table[k], x[d]);
  }
  if (b->ramp > 0 && t < b->ramp) u *= 0.5 * (1 - PetscCosReal(PETSC_PI * t / b->ramp));
  return u;
}

PetscErrorCode OpenImpose(Physics *ph, PetscReal t)
{
  Open             open = ph->open;
  Particles        P    = ph->P;
  const PetscInt   D    = ph->dim;
  const PetscReal *x = PField(P, FIELD_X), *zone = PField(P, FIELD_OPEN);
  PetscReal       *v = PField(P, FIELD_V), *vs = P->f[FIELD_VSTAR].on ? PField(P, FIELD_VSTAR) : NULL;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    const PetscInt k = (PetscInt)zone[a] - 1;
    if (k < 0 || open->b[k].kind != OPEN_INLET || !KindIsFluid(P->kind[a])) continue;
    for (PetscInt d = 0; d < D; d++) v[D * a + d] = 0;
    v[D * a + open->b[k].axis] = -open->b[k].side * InletSpeed(open, k, x + D * a, t, D); /* into the domain */
    if (vs)
      for (PetscInt d = 0; d < D; d++) vs[D * a + d] = v[D * a + d]; /* ISPH: the predicted velocity too */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What a buffer particle gathers over its pairs: a field of its fluid neighbours nearer the plane
 * (the fluid's, or the buffer's between it and the plane), Shepard-weighted, the weight W rising
 * to its full value over the first hundredth of a spacing nearer, min(1, (depth_a - depth_b) /
 * (dx / 100)): a's row-mates (the buffer keeps its lattice's columns, to round-off) are not counted
 * in or out by the round-off of their positions, which differs with the number of ranks under
 * ISPH's solver tolerance */
typedef struct {
  const PetscReal        *x, *f;
  const PetscInt         *kind;
  const OpenBoundarySpec *b;
  PetscInt                w_f; /* the field's width */
  PetscReal               depth, ramp, w, fw[3];
} NearerSum;

SPH_INLINE void NearerPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  NearerSum *s = (NearerSum *)ctx;
  PetscInt   b = p.b;
  PetscReal  c;
  if (!KindIsFluid(s->kind[b])) return;
  c = (s->depth - (s->x[D * b + s->b->axis] - s->b->plane) * s->b->side) / s->ramp;
  if (c <= 0) return;
  c = PetscMin(c, 1.0) * p.W;
  s->w += c;
  for (PetscInt i = 0; i < s->w_f; i++) s->fw[i] += c * s->f[s->w_f * b + i];
}

/* A zero normal gradient in the buffers of one kind: field f (width w_f) of each of their particles
 * becomes the Shepard mean of its fluid neighbours nearer the plane, from their values before this
 * update (the same on any number of ranks), so that it marches down the buffer a row or more a
 * step; one with no such neighbour keeps its own. */
SPH_INLINE PetscErrorCode ExtrapolateD(Physics *ph, OpenBoundaryKind kind, FieldId field, const PetscInt D)
{
  Particles        P    = ph->P;
  const PetscReal *zone = PField(P, FIELD_OPEN), *x = PField(P, FIELD_X);
  PetscReal       *f = PField(P, field), *fn;
  const PetscInt   w_f = P->f[field].width;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(w_f * P->n, &fn));
  PetscCall(PetscArraycpy(fn, f, w_f * P->n));
  for (PetscInt a = 0; a < P->n; a++) {
    const OpenBoundarySpec *b = zone[a] > 0 ? &ph->open->b[(PetscInt)zone[a] - 1] : NULL;
    if (!b || b->kind != kind || !KindIsFluid(P->kind[a])) continue;
    {
      NearerSum s = {.x = x, .f = f, .kind = P->kind, .b = b, .w_f = w_f, .depth = (x[D * a + b->axis] - b->plane) * b->side, .ramp = 0.01 * ph->dx};
      SPHPairsW(ph->cells, P, a, PETSC_TRUE, NearerPair, &s, D);
      if (s.w > 0)
        for (PetscInt i = 0; i < w_f; i++) fn[w_f * a + i] = s.fw[i] / s.w;
    }
  }
  PetscCall(PetscArraycpy(f, fn, w_f * P->n));
  PetscCall(PetscFree(fn));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Extrapolate(Physics *ph, OpenBoundaryKind kind, FieldId field) { return SPH_DIM_DISPATCH(ph->dim, ExtrapolateD, ph, kind, field); }

/* Whether any boundary is of this kind */
static PetscBool HasKind(const Open open, OpenBoundaryKind kind)
{
  for (PetscInt k = 0; k < open->n; k++)
    if (open->b[k].kind == kind) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode OpenState(Physics *ph)
{
  Particles        P    = ph->P;
  const PetscReal *zone = PField(P, FIELD_OPEN);
  PetscReal       *rho  = PField(P, FIELD_RHO);
  const FieldId    f[]  = {FIELD_RHO};
  PetscFunctionBeginUser;
  if (HasKind(ph->open, OPEN_INLET)) PetscCall(Extrapolate(ph, OPEN_INLET, FIELD_RHO));
  for (PetscInt a = 0; a < P->n; a++)
    if (zone[a] > 0 && KindIsFluid(P->kind[a]) && ph->open->b[(PetscInt)zone[a] - 1].kind == OPEN_OUTLET) rho[a] = EOSDensity(&ph->fl, ph->open->b[(PetscInt)zone[a] - 1].pressure);
  PetscCall(HaloRefresh(ph->halo, P, 1, f)); /* the buffers' ghosts */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Inlets' and outlets' buffers feel no acceleration; an outlet's velocity is the fluid's upstream of
 * it (Extrapolate).  The momentum equation would let an outlet's particles run away (their
 * neighbours upstream push and nothing downstream holds them), and a frozen velocity would keep the
 * start's rest in the buffer's last rows, which no fluid reaches. */
PetscErrorCode OpenRates(Physics *ph)
{
  Particles        P    = ph->P;
  const PetscInt   D    = ph->dim;
  const PetscReal *zone = PField(P, FIELD_OPEN);
  PetscReal       *acc  = PField(P, FIELD_ACC);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (zone[a] > 0 && KindIsFluid(P->kind[a]))
      for (PetscInt d = 0; d < D; d++) acc[D * a + d] = 0;
  if (HasKind(ph->open, OPEN_OUTLET)) PetscCall(Extrapolate(ph, OPEN_OUTLET, FIELD_V));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OpenNoShift(Physics *ph)
{
  Particles        P    = ph->P;
  const PetscInt   D    = ph->dim;
  const PetscReal *zone = PField(P, FIELD_OPEN);
  PetscReal       *xs   = P->f[FIELD_XSPH].on ? PField(P, FIELD_XSPH) : NULL;
  PetscFunctionBeginUser;
  if (!xs) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt a = 0; a < P->n; a++)
    if (zone[a] > 0 && KindIsFluid(P->kind[a]))
      for (PetscInt d = 0; d < D; d++) xs[D * a + d] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One particle to make at the next rebuild */
static PetscErrorCode MarkNew(Open open, PetscInt parent, PetscInt zone, const PetscReal *x, PetscReal m, PetscReal h, PetscReal rho, PetscInt D)
{
  PetscFunctionBeginUser;
  if (open->nnew == open->capnew) {
    PetscInt   cap = PetscMax(64, 2 * open->capnew), *pa, *zo;
    PetscReal *xn, *mn, *hn, *rn;
    PetscCall(PetscMalloc6(cap, &pa, cap, &zo, 3 * cap, &xn, cap, &mn, cap, &hn, cap, &rn));
    PetscCall(PetscArraycpy(pa, open->parent, open->nnew));
    PetscCall(PetscArraycpy(zo, open->zone, open->nnew));
    PetscCall(PetscArraycpy(xn, open->xnew, 3 * open->nnew));
    PetscCall(PetscArraycpy(mn, open->mnew, open->nnew));
    PetscCall(PetscArraycpy(hn, open->hnew, open->nnew));
    PetscCall(PetscArraycpy(rn, open->rnew, open->nnew));
    PetscCall(PetscFree6(open->parent, open->zone, open->xnew, open->mnew, open->hnew, open->rnew));
    open->parent = pa; open->zone = zo; open->xnew = xn; open->mnew = mn; open->hnew = hn; open->rnew = rn;
    open->capnew = cap;
  }
  open->parent[open->nnew] = parent;
  open->zone[open->nnew]   = zone;
  for (PetscInt d = 0; d < 3; d++) open->xnew[3 * open->nnew + d] = d < D ? x[d] : 0;
  open->mnew[open->nnew] = m;
  open->hnew[open->nnew] = h;
  open->rnew[open->nnew] = rho;
  open->nnew++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OpenAfterDrift(Physics *ph)
{
  Open             open = ph->open;
  Particles        P    = ph->P;
  const PetscInt   D    = ph->dim;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), tol = 0.25 * ph->dx;
  PetscReal       *zone = PField(P, FIELD_OPEN), *rho = PField(P, FIELD_RHO);
  PetscInt         nnew;
  PetscFunctionBeginUser;
  open->nnew = 0;
  for (PetscInt a = 0; a < P->n; a++) {
    const PetscInt k = (PetscInt)zone[a] - 1;
    if (!KindIsFluid(P->kind[a])) continue;
    if (k >= 0 && open->b[k].kind == OPEN_INLET) {
      const OpenBoundarySpec *b = &open->b[k];
      if ((x[D * a + b->axis] - b->plane) * b->side <= 0) { /* crossed into the fluid: a new one behind it */
        PetscReal xn[3];
        for (PetscInt d = 0; d < D; d++) xn[d] = x[D * a + d];
        xn[b->axis] += b->side * b->rows * ph->dx;
        PetscCall(MarkNew(open, P->id[a], k + 1, xn, m[a], h[a], rho[a], D));
        zone[a] = 0;
      }
    } else if (k < 0) {
      for (PetscInt j = 0; j < open->n; j++) { /* fluid crossing an outlet's plane joins its buffer */
        const OpenBoundarySpec *b = &open->b[j];
        if (b->kind == OPEN_OUTLET && (x[D * a + b->axis] - b->plane) * b->side > 0 && InSection(b, x + D * a, tol, D)) zone[a] = j + 1;
      }
    }
  }
  PetscCall(MPIU_Allreduce(&open->nnew, &nnew, 1, MPIU_INT, MPI_SUM, ph->comm));
  if (nnew) ph->nb->rebuild = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The marked particles, ids from the run's counter in the order of their parents' ids (every rank's
 * the same), their mass summed in that order into mass_in. */
PetscErrorCode OpenInflow(void *ctx)
{
  Physics        *ph   = (Physics *)ctx;
  Open            open = ph->open;
  Particles       P    = ph->P;
  PetscMPIInt     size, n = (PetscMPIInt)open->nnew, *counts, *displs;
  PetscInt        total = 0, *ids, *order;
  PetscReal      *mass, *mall;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(ph->comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, ph->comm));
  for (PetscMPIInt r = 0; r < size; r++) { displs[r] = (PetscMPIInt)total; total += counts[r]; }
  if (!total) {
    PetscCall(PetscFree2(counts, displs));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscMalloc4(total, &ids, total, &order, total, &mall, PetscMax(open->nnew, 1), &mass));
  for (PetscInt i = 0; i < open->nnew; i++) mass[i] = open->mnew[i];
  PetscCallMPI(MPI_Allgatherv(open->parent, n, MPIU_INT, ids, counts, displs, MPIU_INT, ph->comm));
  PetscCallMPI(MPI_Allgatherv(mass, n, MPIU_REAL, mall, counts, displs, MPIU_REAL, ph->comm));
  for (PetscInt i = 0; i < total; i++) order[i] = i;
  PetscCall(PetscSortIntWithArray(total, ids, order)); /* parents' ids are unique */
  {
    PetscMPIInt rank;
    PetscInt   *newid;
    PetscCallMPI(MPI_Comm_rank(ph->comm, &rank));
    PetscCall(PetscMalloc1(PetscMax(open->nnew, 1), &newid));
    for (PetscInt i = 0; i < total; i++) { /* the i-th parent in id order gets next_id + i */
      const PetscInt j = order[i] - displs[rank];
      if (j >= 0 && j < open->nnew) newid[j] = *open->next_id + i;
      open->mass_in += mall[order[i]];
    }
    for (PetscInt j = 0; j < open->nnew; j++) {
      const PetscInt a = P->n;
      PetscCall(ParticlesAdd(P, newid[j], KIND_FLUID, open->xnew + 3 * j, open->mnew[j], open->hnew[j], open->rnew[j]));
      PField(P, FIELD_OPEN)[a] = open->zone[j];
    }
    PetscCall(PetscFree(newid));
  }
  *open->next_id += total;
  ph->nb->nparticles += total;
  open->nnew = 0;
  PetscCall(PetscFree4(ids, order, mall, mass));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(OpenImpose(ph, ph->t + ph->dt)); /* the new ones' velocities (and the others', as the step will end) */
  PetscFunctionReturn(PETSC_SUCCESS);
}

void OpenPressureRows(const Physics *ph, PetscInt a, PetscReal *fs, PetscReal *src)
{
  const PetscReal z = PField(ph->P, FIELD_OPEN)[a];
  if (z <= 0) return;
  if (ph->open->b[(PetscInt)z - 1].kind == OPEN_OUTLET) *fs = 1; /* p = 0: the PPE's Dirichlet rows */
  else { *fs = 0; *src = 0; }
}
