/* The builders and helpers of <sphfsi/scene.h>: lattices, boxes, tanks, zoned water, the hydrostatic
 * start, pressure probes and level gauges; the scenes' kept state and particle counts. */
#include "run/sim.h"
#include "base/kernel.h"

PetscErrorCode SceneCount(Sim sim, ParticleKind kind, PetscInt64 n)
{
  PetscFunctionBeginUser;
  PetscCall(sim->counter.add(sim, kind, n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscBool SceneCounting(Sim sim) { return sim->counter.counting(sim); }

/* One particle at p (coordinates of the layout) spaced s[d] along each of its directions: mass rho0
 * times their product (and dz when extruding); smoothing length from the nominal spacing dx; the next id. */
static PetscErrorCode AddPointSpaced(Sim sim, ParticleKind kind, const PetscReal p[], const PetscReal s[], PetscReal dx, PetscReal rho0)
{
  PetscReal m = rho0 * s[0] * s[1];
  PetscFunctionBeginUser;
  PetscCall(SceneCount(sim, kind, sim->extrude.n > 0 ? sim->extrude.n : 1)); /* counted, or checked against the memory */
  if (SceneCounting(sim)) PetscFunctionReturn(PETSC_SUCCESS);
  if (sim->extrude.n > 0) { /* p is a point of the 2D layout */
    m *= sim->extrude.dz;
    for (PetscInt k = 0; k < sim->extrude.n; k++) {
      PetscInt        id = sim->next_id++;
      const PetscReal q[3] = {p[0], p[1], sim->extrude.z0 + (k + 0.5) * sim->extrude.dz};
      if (id % sim->size == sim->rank) PetscCall(ParticlesAdd(sim->P, id, kind, q, m, sim->phys.kernel.h_factor * dx, rho0));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (sim->phys.dim == 3) m *= s[2];
  {
    PetscInt id = sim->next_id++;
    if (id % sim->size == sim->rank) PetscCall(ParticlesAdd(sim->P, id, kind, p, m, sim->phys.kernel.h_factor * dx, rho0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddPoint(Sim sim, ParticleKind kind, const PetscReal p[], const PetscReal s[], PetscReal dx, PetscReal rho0)
{
  PetscFunctionBeginUser;
  PetscCall(AddPointSpaced(sim, kind, p, s, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One particle at p of spacing dx in every direction: mass rho0 dx^dim. */
static PetscErrorCode AddPoint(Sim sim, ParticleKind kind, const PetscReal p[], PetscReal dx, PetscReal rho0)
{
  const PetscReal s[3] = {dx, dx, dx};
  PetscFunctionBeginUser;
  PetscCall(AddPointSpaced(sim, kind, p, s, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal SceneFitSpacing(PetscReal extent, PetscReal dx, PetscInt *n)
{
  *n = RoundToInt(extent / dx);
  if (*n < 1 || PetscAbsReal(*n * dx - extent) <= 1e-9 * extent) return dx;
  return extent / *n;
}

PetscErrorCode SceneExtrudeBegin(Sim sim, PetscInt n, PetscReal z0, PetscReal dz)
{
  PetscFunctionBeginUser;
  PetscCheck(sim->phys.dim == 3 && n >= 1 && dz > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "Extrusion needs a 3D scene, >= 1 layer and a spacing > 0");
  sim->extrude.n  = n;
  sim->extrude.z0 = z0;
  sim->extrude.dz = dz;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneExtrudeEnd(Sim sim)
{
  PetscFunctionBeginUser;
  sim->extrude.n = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt SceneLayoutDim(Sim sim) { return sim->extrude.n > 0 ? 2 : sim->phys.dim; }

static PetscErrorCode AddOne(Sim sim, ParticleKind kind, PetscReal x, PetscReal y, PetscReal dx, PetscReal rho0)
{
  const PetscReal p[2] = {x, y};
  PetscFunctionBeginUser;
  PetscCall(AddPoint(sim, kind, p, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A number in [-1, 1) from a particle id and a salt (splitmix64): the same on any number of ranks. */
static PetscReal IdUniform(PetscInt id, unsigned salt)
{
  uint64_t z = (uint64_t)id * 2u + salt + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return 2.0 * (PetscReal)(z >> 11) / 9007199254740992.0 - 1.0;
}

/* A lattice spaced s[d] along each direction of the layout; fluid lattices take -fluid_start_jitter: each
 * particle displaced by up to that fraction of dx in every direction. */
static PetscErrorCode AddBlockSpaced(Sim sim, ParticleKind kind, const PetscReal lo[], const PetscInt n[], const PetscReal s[], PetscReal dx, PetscReal rho0)
{
  const PetscReal jit = kind == KIND_FLUID ? sim->start_jitter * dx : 0;
  const PetscInt  D = SceneLayoutDim(sim), nz = D == 3 ? n[2] : 1;
  PetscFunctionBeginUser;
  if (SceneCounting(sim)) { /* the size guard's dry count: the whole block at once */
    const PetscInt64 pts = (PetscInt64)PetscMax(n[0], 0) * PetscMax(n[1], 0) * PetscMax(nz, 0);
    PetscCall(SceneCount(sim, kind, pts * (sim->extrude.n > 0 ? sim->extrude.n : 1)));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (PetscInt k = 0; k < nz; k++)
    for (PetscInt j = 0; j < n[1]; j++)
      for (PetscInt i = 0; i < n[0]; i++) {
        PetscInt  id = sim->next_id, idx[3] = {i, j, k}; /* the id AddPointSpaced hands out */
        PetscReal p[3];
        for (PetscInt d = 0; d < D; d++) p[d] = lo[d] + idx[d] * s[d] + jit * IdUniform(id, (unsigned)d);
        PetscCall(AddPointSpaced(sim, kind, p, s, dx, rho0));
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddBlock(Sim sim, ParticleKind kind, const PetscReal lo[], const PetscInt n[], PetscReal dx, PetscReal rho0)
{
  const PetscReal s[3] = {dx, dx, dx};
  PetscFunctionBeginUser;
  PetscCall(AddBlockSpaced(sim, kind, lo, n, s, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddLattice(Sim sim, ParticleKind kind, PetscReal x0, PetscReal y0, PetscInt nx, PetscInt ny, PetscReal dx, PetscReal rho0)
{
  PetscFunctionBeginUser;
  PetscCall(SceneAddBlock(sim, kind, (PetscReal[]){x0, y0, 0}, (PetscInt[]){nx, ny, 1}, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddBox(Sim sim, ParticleKind kind, const PetscReal b[], PetscReal dx, PetscReal rho0)
{
  const PetscInt D = SceneLayoutDim(sim);
  PetscReal      first[3] = {0, 0, 0}, s[3] = {dx, dx, dx};
  PetscInt       n[3]     = {1, 1, 1};
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < D; d++) {
    s[d]     = SceneFitSpacing(b[D + d] - b[d], dx, &n[d]);
    first[d] = b[d] + 0.5 * s[d];
  }
  PetscCall(AddBlockSpaced(sim, kind, first, n, s, dx, rho0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddWallBox(Sim sim, const PetscReal b[], PetscReal dx, const PetscBool faces[])
{
  const PetscInt D = SceneLayoutDim(sim);
  PetscInt       first = sim->P->n;
  PetscFunctionBeginUser;
  PetscCall(SceneAddBox(sim, KIND_WALL, b, dx, sim->phys.fl.rho0));
  for (PetscInt a = first; a < sim->P->n; a++) { /* this rank's share of the lattice */
    const PetscReal *x = PField(sim->P, FIELD_X) + sim->phys.dim * a;
    PetscBool        wet = PETSC_FALSE;
    for (PetscInt d = 0; d < D; d++) wet = (PetscBool)(wet || (faces[d] && x[d] < b[d] + dx) || (faces[D + d] && x[d] > b[D + d] - dx));
    if (!wet) sim->P->kind[a] = KIND_DUMMY;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddTank(Sim sim, PetscReal x0, PetscReal x1, PetscReal y0, PetscReal y1, PetscReal dx, PetscInt rows, PetscBool left, PetscBool right)
{
  PetscInt  nx = RoundToInt((x1 - x0) / dx), ny = RoundToInt((y1 - y0) / dx);
  PetscInt  il = left ? -rows : 0, ir = nx + (right ? rows : 0);
  PetscFunctionBeginUser;
  /* floor (with the corners) */
  for (PetscInt k = 0; k < rows; k++)
    for (PetscInt i = il; i < ir; i++) {
      PetscInt layer = PetscMax(k, PetscMax(i < 0 ? -i - 1 : 0, i >= nx ? i - nx : 0));
      PetscCall(AddOne(sim, layer ? KIND_DUMMY : KIND_WALL, x0 + (i + 0.5) * dx, y0 - (k + 0.5) * dx, dx, sim->phys.fl.rho0));
    }
  /* side walls */
  for (PetscInt j = 0; j < ny; j++)
    for (PetscInt k = 0; k < rows; k++) {
      if (left) PetscCall(AddOne(sim, k ? KIND_DUMMY : KIND_WALL, x0 - (k + 0.5) * dx, y0 + (j + 0.5) * dx, dx, sim->phys.fl.rho0));
      if (right) PetscCall(AddOne(sim, k ? KIND_DUMMY : KIND_WALL, x0 + (nx + k + 0.5) * dx, y0 + (j + 0.5) * dx, dx, sim->phys.fl.rho0));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SceneTankDomain(Sim sim, PetscReal L, PetscReal top, PetscInt rows)
{
  const PetscInt up = sim->phys.dim - 1;
  for (PetscInt d = 0; d < up; d++) { /* the horizontal directions: a square tank in 3D */
    sim->dom_lo[d] = -(rows + 0.5) * sim->phys.dx;
    sim->dom_hi[d] = L + (rows + 0.5) * sim->phys.dx;
  }
  sim->dom_lo[up] = -(rows + 0.5) * sim->phys.dx;
  sim->dom_hi[up] = top;
}

PetscErrorCode SceneAddTankBox(Sim sim, const PetscReal lo[], const PetscReal hi[], PetscReal top, PetscReal dx, PetscInt rows)
{
  const PetscInt D = sim->phys.dim, up = D - 1;
  PetscInt       n[3] = {1, 1, 1}, a[3], b[3];
  PetscReal      s[3] = {dx, dx, dx}; /* horizontally as the water's box fills (SceneAddBox); dx upwards */
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < D; d++) {
    if (d != up) s[d] = SceneFitSpacing(hi[d] - lo[d], dx, &n[d]);
    a[d] = -rows;
    b[d] = n[d] + rows;
  }
  b[up] = RoundToInt((top - lo[up]) / dx);
  if (D == 2) { a[2] = 0; b[2] = 1; }
  for (PetscInt k = a[2]; k < b[2]; k++)
    for (PetscInt j = a[1]; j < b[1]; j++)
      for (PetscInt i = a[0]; i < b[0]; i++) {
        PetscInt  idx[3] = {i, j, k}, layer = -1; /* cells outside the water, less one: 0 on its faces */
        PetscReal p[3];
        for (PetscInt d = 0; d < D; d++) {
          PetscInt out = idx[d] < 0 ? -idx[d] - 1 : (d != up && idx[d] >= n[d]) ? idx[d] - n[d] : -1;
          layer        = PetscMax(layer, out);
          p[d]         = lo[d] + (idx[d] + 0.5) * s[d];
        }
        if (layer < 0) continue; /* the water's box (and the open space above it) */
        PetscCall(AddPointSpaced(sim, layer ? KIND_DUMMY : KIND_WALL, p, s, dx, sim->phys.fl.rho0));
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddDamBreak(Sim sim, PetscReal w, PetscReal hgt, PetscReal L, PetscReal top, PetscInt rows)
{
  PetscReal dx = sim->phys.dx;
  PetscInt  nx = RoundToInt(w / dx), ny = RoundToInt(hgt / dx);
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dx, 0.5 * dx, nx, ny, dx, sim->phys.fl.rho0));
  PetscCall(SceneAddTank(sim, 0, L, 0, top - dx, dx, rows, PETSC_TRUE, PETSC_TRUE));
  PetscCall(SceneHydrostaticDensity(sim, 0, ny * dx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneZonesSetUp(Sim sim, PetscReal dc, PetscReal *W, PetscReal *fine, PetscReal *H)
{
  PetscInt nc;
  PetscFunctionBeginUser;
  PetscCheck(dc >= sim->phys.dx && dc <= 4 * sim->phys.dx, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dx_coarse %g must be between -dx %g and 4 dx", (double)dc, (double)sim->phys.dx);
  if (dc == sim->phys.dx) {
    *W    = RoundToInt(*W / sim->phys.dx) * sim->phys.dx;
    *H    = RoundToInt(*H / sim->phys.dx) * sim->phys.dx;
    *fine = *W;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  nc = RoundToInt((*W - *fine) / dc);
  PetscCheck(*fine > 0 && nc >= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fine_width %g must be in (0, -water_width %g) less a coarse column", (double)*fine, (double)*W);
  *fine = RoundToInt((*W - nc * dc) / sim->phys.dx) * sim->phys.dx;
  *W    = nc * dc + *fine;
  *H    = RoundToInt(*H / dc) * dc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneAddZonedWater(Sim sim, PetscReal dc, PetscReal W, PetscReal fine, PetscReal H, PetscReal top, PetscInt rows, PetscReal x_end, PetscBool right)
{
  PetscReal dx = sim->phys.dx, xf = W - fine;
  PetscInt  ncx = RoundToInt(xf / dc), rows_f = (PetscInt)PetscCeilReal(rows * dc / dx - 1e-9);
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_FLUID, xf + 0.5 * dx, 0.5 * dx, RoundToInt(fine / dx), RoundToInt(H / dx), dx, sim->phys.fl.rho0));
  if (ncx > 0) {
    PetscCall(SceneAddLattice(sim, KIND_FLUID, 0.5 * dc, 0.5 * dc, ncx, RoundToInt(H / dc), dc, sim->phys.fl.rho0));
    PetscCall(SceneAddTank(sim, 0, xf, 0, RoundToInt(top / dc) * dc, dc, rows, PETSC_TRUE, PETSC_FALSE));
    PetscCall(SceneAddTank(sim, xf, x_end, 0, right ? RoundToInt(top / dx) * dx : 0, dx, rows_f, PETSC_FALSE, right));
  } else PetscCall(SceneAddTank(sim, 0, x_end, 0, RoundToInt(top / dx) * dx, dx, rows, PETSC_TRUE, right));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneHydrostaticDensity(Sim sim, PetscInt first, PetscReal y_surface)
{
  Particles      P = sim->P;
  PetscReal     *x = PField(P, FIELD_X), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P);
  const PetscInt up = SceneLayoutDim(sim) - 1;
  PetscFunctionBeginUser;
  for (PetscInt a = first; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    p[a]   = sim->phys.fl.rho0 * (-sim->phys.g[up]) * (y_surface - x[P->dim * a + up]);
    rho[a] = EOSDensity(&sim->phys.fl, p[a]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneProbePressures(Sim sim, PetscInt n, const PetscReal x0[], PetscReal pval[])
{
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X), *p = PField(P, FIELD_P), *rho = PField(P, FIELD_RHO), *h = PField(P, FIELD_H), *m = PField(P, FIELD_M);
  const PetscInt   D = P->dim;
  PetscReal       *s, lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL}, reach = 2.01 * sim->phys.h_max;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(4 * n, &s)); /* per point: sum (p_b + rho_b g.d) W, sum W, the fluid's sum V_b W, the boundary's */
  for (PetscInt q = 0; q < n; q++)
    for (PetscInt i = 0; i < D; i++) { lo[i] = PetscMin(lo[i], x0[D * q + i]); hi[i] = PetscMax(hi[i], x0[D * q + i]); }
  for (PetscInt a = 0; a < P->n; a++) {
    PetscBool near = PETSC_TRUE; /* within the support of the points' box: one pass over the particles for all of them */
    for (PetscInt i = 0; i < D; i++) near = (PetscBool)(near && x[D * a + i] > lo[i] - reach && x[D * a + i] < hi[i] + reach);
    if (!near) continue;
    for (PetscInt q = 0; q < n; q++) {
      PetscReal d[3] = {0, 0, 0}, w, gd, r2, *sq = s + 4 * q;
      VSub(x0 + D * q, x + D * a, d, D);
      r2 = VDot(d, d, D);
      if (r2 > 4.01 * h[a] * h[a]) continue; /* beyond the support (W = 0), without the square root */
      w = KernelW(&sim->phys.kernel, PetscSqrtReal(r2), h[a]);
      if (w <= 0) continue;
      if (!KindIsFluid(P->kind[a])) {
        sq[3] += w * m[a] / rho[a];
        continue;
      }
      gd = VDot(sim->phys.g, d, D);
      sq[0] += w * (p[a] + SceneFluidDensity(sim, rho[a]) * gd);
      sq[1] += w;
      sq[2] += w * m[a] / rho[a];
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 4 * n, MPIU_REAL, MPI_SUM, sim->comm));
  for (PetscInt q = 0; q < n; q++) {
    const PetscReal *sq = s + 4 * q;
    pval[q] = sq[1] > 0 ? sq[0] / sq[1] : 0;
    if (sq[3] < 1) pval[q] *= PetscMin(1.0, sq[2] / (1.0 - sq[3])); /* the wetted fraction of the support outside the walls */
  }
  PetscCall(PetscFree(s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneProbePressure(Sim sim, const PetscReal x0[], PetscReal *pval) { return SceneProbePressures(sim, 1, x0, pval); }

PetscErrorCode SceneMaxSpeed(Sim sim, PetscReal *vmax)
{
  Particles  P = sim->P;
  PetscReal *v = PField(P, FIELD_V), m = 0;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a])) m = PetscMax(m, VDot(v + P->dim * a, v + P->dim * a, P->dim));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &m, 1, MPIU_REAL, MPIU_MAX, sim->comm));
  *vmax = PetscSqrtReal(m);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SceneColumnKernelInit(Sim sim, SceneColumnKernel *ck)
{
  /* h^(d-1) W_col(S h) = int W(sqrt(S^2 + T^2), 1) dT, S in [0, 2] */
  for (PetscInt k = 0; k <= SCENE_NCOLUMN; k++) {
    PetscReal S = 2.0 * k / SCENE_NCOLUMN, T = PetscSqrtReal(PetscMax(4.0 - S * S, 0.0)), s = 0;
    const PetscInt nq = 400;
    for (PetscInt q = 0; q < nq; q++) {
      PetscReal t = -T + (q + 0.5) * 2 * T / nq;
      s += KernelW(&sim->phys.kernel, PetscSqrtReal(S * S + t * t), 1.0) * 2 * T / nq;
    }
    ck->w[k] = s;
  }
  ck->dim = sim->phys.kernel.dim;
}

/* W_col(s, h) from the table (linear in s / h) */
static inline PetscReal ColumnKernel(const SceneColumnKernel *ck, PetscReal s, PetscReal h)
{
  PetscReal S = PetscAbsReal(s) / h * (SCENE_NCOLUMN / 2.0);
  PetscInt  k = (PetscInt)S;
  if (k >= SCENE_NCOLUMN) return 0;
  return ((1 - (S - k)) * ck->w[k] + (S - k) * ck->w[k + 1]) / (ck->dim == 3 ? h * h : h);
}

PetscErrorCode SceneWaterDepth(Sim sim, const SceneColumnKernel *ck, PetscInt n, const PetscReal *xg, PetscReal *depth)
{
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), *h = PField(P, FIELD_H);
  const PetscInt   D = P->dim, H = D - 1; /* the horizontal directions */
  PetscFunctionBeginUser;
  PetscCheck(ck->dim == D, sim->comm, PETSC_ERR_PLIB, "Column kernel of dimension %" PetscInt_FMT " in a %" PetscInt_FMT "D run: initialise it after the scene's create", ck->dim, D);
  for (PetscInt g = 0; g < n; g++) depth[g] = 0;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    for (PetscInt g = 0; g < n; g++) {
      PetscReal s = D == 3 ? PetscSqrtReal(PetscSqr(xg[H * g] - x[D * a]) + PetscSqr(xg[H * g + 1] - x[D * a + 1])) : xg[g] - x[D * a];
      depth[g] += SceneFluidVolume(sim, m[a], rho[a]) * ColumnKernel(ck, s, h[a]);
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, depth, n, MPIU_REAL, MPI_SUM, sim->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
