#include <sphfsi/solid.h>
#include <sphfsi/options_used.h>
#include <sphfsi/solid_terms.h>
#include <sphfsi/fluid_terms.h>
#include <sphfsi/kernel.h>
#include <sphfsi/operators.h>
#include <sphfsi/scene.h>
#include <sphfsi/boundary.h>
#include <sphfsi/isph.h>
#include <sphfsi/solid_impl.h>

const char *const SolidGradients[]    = {"standard", "corrected", "SolidGradient", "SOLID_GRAD_", NULL};
const char *const SolidFormulations[] = {"updated", "total", "SolidFormulation", "SOLID_", NULL};

PetscErrorCode SolidSetUp(Sim sim)
{
  SolidMaterial *m = &sim->sl;
  Solid          s;
  PetscInt       grad = SOLID_GRAD_CORRECTED, form = SOLID_TOTAL;
  PetscBool      fluid = sim->has_fluid;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  sim->solid   = s;
  s->skin      = 0.4;
  s->subcycle  = PETSC_TRUE;
  s->repulsion = (PetscBool)(fluid && sim->fluid == FLUID_WCSPH);
  s->hourglass = 0;
  s->order     = 2;
  s->quadrature = PETSC_TRUE;
  s->clamp_face = PETSC_TRUE;
  PetscOptionsBegin(sim->comm, NULL, "Elastic solid: hypo-elastic updated-Lagrangian (Eqs. 20, 23-40) or total-Lagrangian", "Solid");
  PetscCall(OptEList("-solid_formulation", "total (default): total-Lagrangian neo-Hookean with a second-order reference gradient (converges in bending); updated: the paper's hypo-elastic scheme (Jaumann rate, artificial stress)", "", SolidFormulations, 2, SolidFormulations[form], &form, NULL));
  s->formulation = (SolidFormulation)form;
  PetscCall(OptReal("-solid_damping", "Mass-proportional damping rate zeta (1/s): acc -= zeta v, to reach a static solution by dynamic relaxation (about twice the lowest angular frequency damps it critically); 0 = off", "", s->damping, &s->damping, NULL));
  if (s->formulation == SOLID_TOTAL) PetscCall(OptInt("-solid_order", "Total-Lagrangian: the reference gradient is exact for displacements of this polynomial order (1: kernel-gradient correction; 2: also exact for the bending field at a free surface or clamp)", "", s->order, &s->order, NULL));
  if (s->formulation == SOLID_TOTAL && s->order == 2) PetscCall(OptBool("-solid_cell_quadrature", "Total-Lagrangian, order 2: integrate each particle's cell to second order with the strain gradient of the fit (one point per particle leaves a plate n across (1 - 1/n^2) of its bending stiffness)", "", s->quadrature, &s->quadrature, NULL));
  if (s->order != 2) s->quadrature = PETSC_FALSE;
  if (s->order != 2) s->clamp_face = PETSC_FALSE; /* with the first-order fit the face points, dx/2 from the first column, made the root unstable (the cantilever at 5 across lost pairs at t = 0.08 s) */
  if (s->formulation == SOLID_TOTAL && s->order == 2) PetscCall(OptBool("-solid_clamp_face", "Total-Lagrangian, order 2: a clamp is a boundary, its particles next to the body stand for the face midway to it in the fits, and it stores no energy (off: the clamp is material held still)", "", s->clamp_face, &s->clamp_face, NULL));
  if (s->formulation == SOLID_TOTAL) PetscCall(OptReal("-solid_hourglass", "Total-Lagrangian: hourglass-control coefficient zeta, the energy zeta G / 2 of the bonds' deviation from the affine fit (solid_terms.h); 0 = off", "", s->hourglass, &s->hourglass, NULL));
  PetscCall(OptReal("-solid_rho", "Solid reference density (kg/m^3)", "", m->rho0, &m->rho0, NULL));
  PetscCall(OptReal("-solid_K", "Solid bulk modulus K (Pa); c0^2 = K / rho0, Eq. 20", "", m->K, &m->K, NULL));
  PetscCall(OptReal("-solid_G", "Solid shear modulus mu_s (Pa), Eq. 40", "", m->G, &m->G, NULL));
  PetscCall(OptReal("-solid_alpha", "Solid artificial viscosity coefficient, Eq. 24", "", m->alpha, &m->alpha, NULL));
  PetscCall(OptReal("-solid_art_stress", "Artificial stress coefficient e, Eqs. 25-31; 0 = off", "", m->eps, &m->eps, NULL));
  PetscCall(OptReal("-solid_art_stress_n", "Exponent n of f = W_ab / W(dx, h) in the artificial stress, Eq. 23", "", m->n, &m->n, NULL));
  PetscCall(OptEList("-solid_gradient", "Velocity gradient of the strain rate: standard (Eqs. 35-38) or corrected (Bonet-Lok, exact for linear fields)", "", SolidGradients, 2, SolidGradients[grad], &grad, NULL));
  if (fluid) PetscCall(OptBool("-solid_subcycle", "Multi-rate: sub-cycle the solid with its own step inside each fluid step (off: one step, the smaller, for both)", "", s->subcycle, &s->subcycle, NULL));
  s->cfl = sim->cfl;
  PetscCall(OptReal("-solid_cfl", "Courant number of the solid's step, cfl h / (c0 + |v|) (default: -cfl)", "", s->cfl, &s->cfl, NULL));
  PetscCall(OptReal("-solid_skin", "Neighbour-list skin of the solid sub-steps, in particle spacings", "", s->skin, &s->skin, NULL));
  s->implicit = (PetscBool)(fluid && sim->fluid == FLUID_ISPH);
  if (fluid && sim->fluid == FLUID_ISPH) PetscCall(OptBool("-fsi_implicit", "ISPH + solid: the solid rows of the pressure equation answer the solid's acceleration under that pressure (implicit interface; off = the solid seen as a wall at rest during the solve, unstable for light solids)", "", s->implicit, &s->implicit, NULL));
  s->transit = fluid && sim->fluid == FLUID_ISPH ? 0.85 : 0.0; /* K, G x 5 gate: 1.0 swings the load -138..360 N/m, 0.85 runs clean */
  if (fluid && sim->fluid == FLUID_ISPH) PetscCall(OptReal("-fsi_dt_transit", "ISPH + solid: the fluid step is at most this many times the time an elastic wave (c0 of the solid) takes to cross the solid's largest extent, since the pressure is frozen over the solid sub-steps (0 = no limit); a gate 5x stiffer than the rubber needs it", "", s->transit, &s->transit, NULL));
  if (fluid) PetscCall(OptBool("-fsi_repulsion", "Repulsive force Eq. 41 between fluid and solid particles (default: on with -fluid wcsph, off with isph)", "", s->repulsion, &s->repulsion, NULL));
  PetscOptionsEnd();
  s->gradient = (SolidGradient)grad;
  PetscCheck(s->damping >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_damping %g must be >= 0", (double)s->damping);
  PetscCheck(s->order == 1 || s->order == 2, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_order %" PetscInt_FMT " must be 1 or 2", s->order);
  PetscCheck(s->hourglass >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_hourglass %g must be >= 0", (double)s->hourglass);
  PetscCheck(s->skin >= 0 && s->skin <= 2, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_skin %g must be in [0, 2] particle spacings", (double)s->skin);
  PetscCheck(s->transit >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fsi_dt_transit %g must be >= 0", (double)s->transit);
  PetscCheck(s->cfl > 0 && s->cfl <= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_cfl %g must be in (0, 1]", (double)s->cfl);
  /* the one-sided fits at a surface are stiffer than the bulk: measured on the oscillating plate
   * (6 across) the total-Lagrangian solid is stable at 0.35 and not at 0.4 */
  PetscCheck(s->formulation != SOLID_TOTAL || s->cfl <= 0.3, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_cfl %g is above 0.3, the stable limit of -solid_formulation total with a margin (its surface particles are stiffer than the bulk): use -solid_cfl 0.3 or less", (double)s->cfl);
  PetscCheck(m->rho0 > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_rho %g must be > 0", (double)m->rho0);
  PetscCheck(m->K > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_K %g must be > 0", (double)m->K);
  PetscCheck(m->G >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_G %g must be >= 0", (double)m->G);
  PetscCheck(m->alpha >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_alpha %g must be >= 0", (double)m->alpha);
  PetscCheck(m->eps >= 0 && m->eps < 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_art_stress %g must be in [0, 1)", (double)m->eps);
  PetscCheck(m->n > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_art_stress_n %g must be > 0", (double)m->n);
  m->c0 = PetscSqrtReal(m->K / m->rho0);
  PetscCall(ParticlesEnableField(sim->P, FIELD_S, PETSC_TRUE));
  PetscCall(ParticlesEnableField(sim->P, FIELD_ACC, PETSC_FALSE));
  PetscCall(ParticlesEnableField(sim->P, FIELD_DRHO, PETSC_FALSE));
  if (s->gradient == SOLID_GRAD_CORRECTED && s->formulation == SOLID_UPDATED) PetscCall(ParticlesEnableField(sim->P, FIELD_KCORR, PETSC_FALSE)); /* ghosts: refreshed when computed */
  if (s->formulation == SOLID_TOTAL) {
    PetscCall(ParticlesEnableField(sim->P, FIELD_X0, PETSC_TRUE)); /* the reference configuration */
    PetscCall(ParticlesEnableField(sim->P, FIELD_DEFGRAD, PETSC_TRUE));
    PetscCall(ParticlesEnableField(sim->P, FIELD_GRAD0, PETSC_FALSE));
    PetscCall(ParticlesEnableField(sim->P, FIELD_PK1B, PETSC_TRUE));
  }
  if (fluid) {
    PetscCall(ParticlesEnableField(sim->P, FIELD_FVIEW, PETSC_TRUE));
    PetscCall(ParticlesEnableField(sim->P, FIELD_VWALL, PETSC_FALSE));
  }
  if (s->repulsion) PetscCall(ParticlesEnableField(sim->P, FIELD_NORMAL, PETSC_TRUE));
  if (s->implicit) PetscCall(ParticlesEnableField(sim->P, FIELD_AMEAN, PETSC_FALSE));
  /* ISPH: the solid's loads (after the step's last rebuild) and its PPE rows (after the predictor's)
   * read the fluid ghosts' pressure, which nothing else recomputes there */
  if (fluid && sim->fluid == FLUID_ISPH) PetscCall(ParticlesEnableField(sim->P, FIELD_P, PETSC_TRUE));
  PetscCall(CellsCreateList(&sim->kernel, &s->nl));
  { /* |sum V grad W| of a particle on a flat surface of a lattice of spacing 1 */
    PetscReal g = 0, hh = sim->kernel.h_factor;
    PetscInt  nr = KernelSupportRows(&sim->kernel);
    for (PetscInt j = 0; j <= nr; j++)
      for (PetscInt i = -nr; i <= nr; i++) {
        PetscReal r = PetscSqrtReal((PetscReal)(i * i + j * j));
        g += KernelF(&sim->kernel, r, hh) * j;
      }
    s->nrm_min = 0.5 * PetscAbsReal(g);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidDestroy(Solid *s)
{
  PetscFunctionBeginUser;
  if (!*s) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree((*s)->R));
  PetscCall(PetscFree((*s)->f0));
  PetscCall(PetscFree((*s)->xref));
  PetscCall(CellsDestroy(&(*s)->nl));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Pressure (Eq. 20) and artificial stress (Eqs. 25-34) of owned and ghost solids: both are
 * functions of the particle's own density and stress, so ghosts compute theirs. */
static PetscErrorCode PressureAndArtificialStress(Sim sim)
{
  Particles            P = sim->P;
  Solid                s = sim->solid;
  const SolidMaterial *m = &sim->sl;
  const PetscReal     *rho = PField(P, FIELD_RHO), *S = PField(P, FIELD_S);
  PetscReal           *p = PField(P, FIELD_P);
  PetscInt             N = P->n + P->ng;

  PetscFunctionBeginUser;
  if (m->eps > 0 && s->cap_R < N) {
    PetscCall(PetscFree(s->R));
    s->cap_R = P->cap;
    PetscCall(PetscMalloc1(3 * s->cap_R, &s->R));
  }
  for (PetscInt a = 0; a < N; a++) {
    if (!KindIsSolid(P->kind[a])) continue;
    p[a] = SolidEOSPressure(m, rho[a]);
    if (m->eps > 0) ArtificialStress(m->eps, S[3 * a] - p[a], S[3 * a + 1], S[3 * a + 2] - p[a], rho[a], s->R + 3 * a);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (L v)_i for the 2x2 row-major L, or v itself without correction */
static inline void Apply(const PetscReal *L, PetscReal gx, PetscReal gy, PetscReal out[2])
{
  if (L) { out[0] = L[0] * gx + L[1] * gy; out[1] = L[2] * gx + L[3] * gy; }
  else { out[0] = gx; out[1] = gy; }
}

/* Eq. 23 for owned solids over their solid neighbours: stress, artificial viscosity (Eq. 24) and
 * artificial stress; the fluid's loads (FluidLoad); gravity.  Walls do not act; clamps do not
 * accelerate: what would, the support takes (Solid.support).  With the corrected gradient each
 * particle's stress acts through its own corrected kernel gradient, sigma_a L_a grad W +
 * sigma_b L_b grad W (pair terms with the mean), which keeps the pair forces opposite. */
static PetscErrorCode Momentum(Sim sim)
{
  Particles            P = sim->P;
  Cells                C = sim->solid->nl;
  const SolidMaterial *m = &sim->sl;
  const PetscReal     *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P);
  const PetscReal     *mass = PField(P, FIELD_M), *h = PField(P, FIELD_H), *S = PField(P, FIELD_S), *R = sim->solid->R, *L = PField(P, FIELD_KCORR);
  PetscReal           *acc = PField(P, FIELD_ACC), support[2] = {0, 0}, load[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal ax = 0, ay = 0, ra = rho[a], ia = 1.0 / (ra * ra), wdx, fl[2] = {0, 0};
    PetscReal sxx = (S[3 * a] - p[a]) * ia, sxy = S[3 * a + 1] * ia, syy = (S[3 * a + 2] - p[a]) * ia;
    if (!KindIsSolid(P->kind[a])) continue;
    wdx = R ? KernelW(&sim->kernel, h[a] / sim->kernel.h_factor, h[a]) : 1;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt  b = C->nbr[k];
      PetscReal dx = x[2 * a] - x[2 * b], dy = x[2 * a + 1] - x[2 * b + 1], r2 = dx * dx + dy * dy;
      PetscReal gx = C->f[k] * dx, gy = C->f[k] * dy, rb = rho[b], ib = 1.0 / (rb * rb), ga[2], gb[2], gm[2], txx, txy, tyy;
      if (C->f[k] == 0) continue; /* in the skin */
      if (KindIsFluid(P->kind[b])) { FluidLoad(sim, a, b, C->f[k], fl); continue; }
      if (!KindIsSolid(P->kind[b])) continue;
      {
        PetscReal hab = PairH(h[a], h[b]);
        PetscReal pi  = ArtificialViscosity(m->alpha, m->c0, hab, 0.5 * (ra + rb), (v[2 * a] - v[2 * b]) * dx + (v[2 * a + 1] - v[2 * b + 1]) * dy, r2);
        Apply(L ? L + 4 * a : NULL, gx, gy, ga);
        Apply(L ? L + 4 * b : NULL, gx, gy, gb);
        gm[0] = 0.5 * (ga[0] + gb[0]); gm[1] = 0.5 * (ga[1] + gb[1]);
        /* sigma_a / rho_a^2 through ga, sigma_b / rho_b^2 through gb, Pi (and R) through the mean */
        ax += mass[b] * (sxx * ga[0] + sxy * ga[1] + ((S[3 * b] - p[b]) * gb[0] + S[3 * b + 1] * gb[1]) * ib - pi * gm[0]);
        ay += mass[b] * (sxy * ga[0] + syy * ga[1] + (S[3 * b + 1] * gb[0] + (S[3 * b + 2] - p[b]) * gb[1]) * ib - pi * gm[1]);
        if (R) {
          PetscReal fn = PetscPowReal(C->w[k] / wdx, m->n);
          txx = fn * (R[3 * a] + R[3 * b]);
          txy = fn * (R[3 * a + 1] + R[3 * b + 1]);
          tyy = fn * (R[3 * a + 2] + R[3 * b + 2]);
          ax += mass[b] * (txx * gm[0] + txy * gm[1]);
          ay += mass[b] * (txy * gm[0] + tyy * gm[1]);
        }
      }
    }
    SolidAccelerate(sim, a, ax, ay, fl, acc, support, load);
  }
  sim->solid->support[0] = support[0];
  sim->solid->support[1] = support[1];
  sim->solid->load[0]    = load[0];
  sim->solid->load[1]    = load[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Outward normal of solid surface particles, -sum_b V_b grad_a W / |.| over solid neighbours (the
 * kernel form of Eqs. 42-43's tangent turned by 90 degrees: it needs no ordering of the surface
 * particles); zero inside the body. */
static PetscErrorCode Normals(Sim sim)
{
  Particles        P = sim->P;
  Cells            C = sim->solid->nl;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), *h = PField(P, FIELD_H);
  PetscReal       *nrm = PField(P, FIELD_NORMAL);
  const FieldId    refresh[] = {FIELD_NORMAL};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal gx = 0, gy = 0, gn, dxa = h[a] / sim->kernel.h_factor;
    nrm[2 * a] = nrm[2 * a + 1] = 0;
    if (!KindIsSolid(P->kind[a])) continue;
    for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
      PetscInt b = C->nbr[k];
      if (!KindIsSolid(P->kind[b])) continue;
      gx -= m[b] / rho[b] * C->f[k] * (x[2 * a] - x[2 * b]);
      gy -= m[b] / rho[b] * C->f[k] * (x[2 * a + 1] - x[2 * b + 1]);
    }
    gn = PetscSqrtReal(gx * gx + gy * gy);
    if (gn * dxa > sim->solid->nrm_min) { nrm[2 * a] = gx / gn; nrm[2 * a + 1] = gy / gn; }
  }
  PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
  PetscCall(HaloRefresh(sim->halo, P, 1, refresh));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool KeepSolid(PetscInt kind) { return KindIsSolid(kind); }

PetscErrorCode SolidPrepare(Sim sim)
{
  Solid            s = sim->solid;
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X);
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim->stage[STAGE_NEIGHBOUR]));
  PetscCall(CellsBuildSubList(sim->cells, P, KeepSolid, s->skin * sim->dx, s->nl));
  if (2 * P->n > s->cap_xref) {
    PetscCall(PetscFree(s->xref));
    s->cap_xref = 3 * P->n + 16;
    PetscCall(PetscMalloc1(s->cap_xref, &s->xref));
  }
  PetscCall(PetscArraycpy(s->xref, x, 2 * P->n));
  if (s->formulation == SOLID_TOTAL) PetscCall(SolidTotalPrepare(sim));
  PetscCall(PetscLogStagePop());
  if (sim->has_fluid) { /* the fluid's last half kick came after its rebuild: the loads need its ghosts' velocities */
    const FieldId vel[] = {FIELD_V};
    PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
    PetscCall(HaloRefresh(sim->halo, P, 1, vel));
    PetscCall(PetscLogStagePop());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After the drift: ghosts take the owners' new state, or, once some solid has moved half the
 * skin since SolidPrepare, everything is rebuilt (collective decision). */
static PetscErrorCode SolidRefresh(Sim sim)
{
  Solid            s = sim->solid;
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X);
  const FieldId    state[] = {FIELD_X, FIELD_RHO, FIELD_S};
  PetscReal        d2 = 0, lim = 0.5 * s->skin * sim->dx;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (P->kind[a] == KIND_SOLID) {
      PetscReal dx = x[2 * a] - s->xref[2 * a], dy = x[2 * a + 1] - s->xref[2 * a + 1];
      d2 = PetscMax(d2, dx * dx + dy * dy);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &d2, 1, MPIU_REAL, MPIU_MAX, sim->comm));
  if (d2 >= lim * lim) {
    PetscCall(SimRebuild(sim));
    PetscCall(SolidPrepare(sim));
    s->nrebuild++;
  } else {
    PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
    PetscCall(HaloRefresh(sim->halo, P, 3, state));
    PetscCall(PetscLogStagePop());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidRates(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim->stage[STAGE_SOLID]));
  PetscCall(CellsUpdatePairs(sim->solid->nl, sim->P));
  if (sim->solid->formulation == SOLID_TOTAL) {
    if (sim->solid->repulsion) PetscCall(Normals(sim));
    PetscCall(SolidTotalRates(sim));
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PressureAndArtificialStress(sim));
  if (sim->solid->repulsion) PetscCall(Normals(sim));
  if (sim->solid->gradient == SOLID_GRAD_CORRECTED) {
    const FieldId kc[] = {FIELD_KCORR};
    PetscCall(SPHGradientCorrection(sim->P, sim->solid->nl, KeepSolid, PField(sim->P, FIELD_KCORR)));
    PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
    PetscCall(HaloRefresh(sim->halo, sim->P, 1, kc));
    PetscCall(PetscLogStagePop());
  }
  PetscCall(Momentum(sim));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Velocity gradient g_ij = dv_i/dx_j of owned solid a from its solid neighbours: Eqs. 35-38 use
 * g = sum V_b (v_b - v_a) (x) grad_a W; corrected, grad_a W becomes L_a grad_a W. */
static void VelocityGradient(Sim sim, PetscInt a, PetscReal g[4])
{
  Particles        P = sim->P;
  Cells            C = sim->solid->nl;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *m = PField(P, FIELD_M), *L = PField(P, FIELD_KCORR);

  g[0] = g[1] = g[2] = g[3] = 0;
  for (PetscInt k = C->nstart[a]; k < C->nstart[a + 1]; k++) {
    PetscInt  b = C->nbr[k];
    PetscReal gw[2], V, dvx, dvy;
    if (!KindIsSolid(P->kind[b]) || C->f[k] == 0) continue;
    Apply(L ? L + 4 * a : NULL, C->f[k] * (x[2 * a] - x[2 * b]), C->f[k] * (x[2 * a + 1] - x[2 * b + 1]), gw);
    V   = m[b] / rho[b];
    dvx = V * (v[2 * b] - v[2 * a]); dvy = V * (v[2 * b + 1] - v[2 * a + 1]);
    g[0] += dvx * gw[0]; g[1] += dvx * gw[1]; g[2] += dvy * gw[0]; g[3] += dvy * gw[1];
  }
}

/* Density (continuity, Eq. 18 as -rho div v) and deviatoric stress (Eqs. 35-40) of owned solids
 * and clamps over dt, from the current velocities at the positions of the last SolidRates.  The
 * density changes after the loop: neighbours' volumes m/rho must be those of the step's start,
 * owned or ghost alike, or the answer would depend on the decomposition. */
static PetscErrorCode Deform(Sim sim, PetscReal dt)
{
  Particles  P = sim->P;
  PetscReal *rho = PField(P, FIELD_RHO), *S = PField(P, FIELD_S), *drho = PField(P, FIELD_DRHO);

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal g[4];
    if (!KindIsSolid(P->kind[a])) continue;
    VelocityGradient(sim, a, g);
    drho[a] = -rho[a] * (g[0] + g[3]);
    /* D_xy = (du/dy + dv/dx) / 2, spin W_xy = (du/dy - dv/dx) / 2 (Eqs. 37-38) */
    JaumannUpdate(sim->sl.G, dt, g[0], 0.5 * (g[1] + g[2]), g[3], 0.5 * (g[1] - g[2]), S + 3 * a);
  }
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsSolid(P->kind[a])) rho[a] += dt * drho[a];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTransitLimit(Sim sim, PetscReal *dt)
{
  Solid s = sim->solid;
  PetscFunctionBeginUser;
  *dt = PETSC_MAX_REAL;
  if (!s || s->transit <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (s->extent <= 0) { /* bounding box of the moving solids at the first call (SimSetUp: as built) */
    const PetscReal *x = PField(sim->P, FIELD_X);
    PetscReal        b[4] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* -xmin, -ymin, ... as maxima */
    for (PetscInt a = 0; a < sim->P->n; a++)
      if (sim->P->kind[a] == KIND_SOLID) { b[0] = PetscMin(b[0], x[2 * a]); b[1] = PetscMin(b[1], x[2 * a + 1]); b[2] = PetscMin(b[2], -x[2 * a]); b[3] = PetscMin(b[3], -x[2 * a + 1]); }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, b, 4, MPIU_REAL, MPIU_MIN, sim->comm));
    s->extent = b[0] < PETSC_MAX_REAL ? PetscMax(-b[2] - b[0], -b[3] - b[1]) + sim->dx : 0;
    if (s->extent <= 0) s->transit = 0; /* no moving solid */
  }
  if (s->transit > 0) *dt = s->transit * s->extent / sim->sl.c0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTimeStep(Sim sim, PetscReal *dt)
{
  Particles        P = sim->P;
  const PetscReal *v = PField(P, FIELD_V), *acc = PField(P, FIELD_ACC), *h = PField(P, FIELD_H);
  PetscReal        lim = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (P->kind[a] == KIND_SOLID) lim = PetscMin(lim, SimAcousticStepLimit(sim->solid->cfl, h[a], sim->sl.c0, v + 2 * a, acc + 2 * a, 2));
  PetscCall(MPIU_Allreduce(&lim, dt, 1, MPIU_REAL, MPIU_MIN, sim->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* v += dt acc; the means over the fluid step (SolidBeginSubsteps) gain dt / dt_f of the current
 * acceleration and support force. */
static void Kick(Sim sim, PetscReal dt)
{
  Particles        P = sim->P;
  Solid            s = sim->solid;
  PetscReal       *v = PField(P, FIELD_V), *am = PField(P, FIELD_AMEAN), w = sim->dt > 0 ? dt / sim->dt : 0;
  const PetscReal *acc = PField(P, FIELD_ACC);
  for (PetscInt a = 0; a < P->n; a++) {
    if (P->kind[a] != KIND_SOLID) continue;
    v[2 * a] += dt * acc[2 * a];
    v[2 * a + 1] += dt * acc[2 * a + 1];
    if (am) { am[2 * a] += w * acc[2 * a]; am[2 * a + 1] += w * acc[2 * a + 1]; }
  }
  s->support_mean[0] += w * s->support[0];
  s->support_mean[1] += w * s->support[1];
  s->load_mean[0] += w * s->load[0];
  s->load_mean[1] += w * s->load[1];
}

PetscErrorCode SolidBeginSubsteps(Sim sim)
{
  Particles  P = sim->P;
  PetscReal *am = PField(P, FIELD_AMEAN);
  PetscFunctionBeginUser;
  sim->solid->support_mean[0] = sim->solid->support_mean[1] = 0;
  sim->solid->load_mean[0] = sim->solid->load_mean[1] = 0;
  if (am) PetscCall(PetscArrayzero(am, 2 * P->n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Kick-drift-kick like WCSPHStep, with density and stress as position-like variables:
 * v+ = v + dt/2 a;  (rho, S)' from the rates at (x, v+);  x' = x + dt v+;  v' = v+ + dt/2 a'. */
PetscErrorCode SolidStep(Sim sim, PetscReal dt)
{
  Particles     P     = sim->P;
  const FieldId vel[] = {FIELD_V};

  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim->stage[STAGE_SOLID]));
  Kick(sim, 0.5 * dt);
  if (sim->scene->prescribe) PetscCall(sim->scene->prescribe(sim));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscLogStagePush(sim->stage[STAGE_HALO]));
  PetscCall(HaloRefresh(sim->halo, P, 1, vel));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscLogStagePush(sim->stage[STAGE_SOLID]));
  if (sim->solid->formulation == SOLID_UPDATED) PetscCall(Deform(sim, dt)); /* total: F follows from the positions */
  {
    PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V);
    for (PetscInt a = 0; a < P->n; a++) {
      if (P->kind[a] != KIND_SOLID) continue;
      x[2 * a] += dt * v[2 * a];
      x[2 * a + 1] += dt * v[2 * a + 1];
    }
  }
  PetscCall(PetscLogStagePop());
  PetscCall(SolidRefresh(sim));
  PetscCall(SolidRates(sim));
  PetscCall(PetscLogStagePush(sim->stage[STAGE_SOLID]));
  Kick(sim, 0.5 * dt);
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidEnergy(Sim sim, PetscReal *ekin, PetscReal *estrain)
{
  Particles            P = sim->P;
  const SolidMaterial *m = &sim->sl;
  const PetscReal     *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *mass = PField(P, FIELD_M), *S = PField(P, FIELD_S), *p = PField(P, FIELD_P);
  PetscReal            e[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal sxx, sxy, syy, szz, pa = p[a];
    if (!KindIsSolid(P->kind[a])) continue;
    sxx = S[3 * a]; sxy = S[3 * a + 1]; syy = S[3 * a + 2]; szz = -(sxx + syy);
    e[0] += 0.5 * mass[a] * (v[2 * a] * v[2 * a] + v[2 * a + 1] * v[2 * a + 1]);
    e[1] += mass[a] / rho[a] * ((m->G > 0 ? (sxx * sxx + syy * syy + szz * szz + 2 * sxy * sxy) / (4 * m->G) : 0) + pa * pa / (2 * m->K));
  }
  if (sim->solid->formulation == SOLID_TOTAL) e[1] = SolidTotalStrainEnergy(sim);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPI_SUM, sim->comm));
  *ekin    = e[0];
  *estrain = e[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidView(Sim sim, PetscViewer v)
{
  const SolidMaterial *m = &sim->sl;
  PetscFunctionBeginUser;
  if (sim->solid->formulation == SOLID_TOTAL) {
    PetscCall(PetscViewerASCIIPrintf(v, "Solid: total-Lagrangian neo-Hookean, rho0 %g, K %g Pa, G %g Pa, c0 %g m/s; artificial viscosity alpha %g; hourglass control %g%s\n", (double)m->rho0, (double)m->K, (double)m->G, (double)m->c0, (double)m->alpha, (double)sim->solid->hourglass, m->eps > 0 ? "; -solid_art_stress not used" : ""));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscViewerASCIIPrintf(v, "Solid: rho0 %g, K %g Pa, G %g Pa, c0 %g m/s; artificial viscosity alpha %g; artificial stress e %g n %g%s; velocity gradient %s\n", (double)m->rho0, (double)m->K, (double)m->G, (double)m->c0, (double)m->alpha, (double)m->eps, (double)m->n, m->eps > 0 ? "" : " (off)", SolidGradients[sim->solid->gradient]));
  PetscFunctionReturn(PETSC_SUCCESS);
}
