#include "solid/solid.h"
#include "base/options_used.h"
#include "solid/solid_terms.h"
#include "fluid/fluid_terms.h"
#include "base/kernel.h"
#include "fluid/operators.h"
#include "fluid/boundary.h"
#include "fluid/isph.h"
#include "solid/solid_impl.h"
#include "solid/solid_total.h"
#include "solid/solid_updated.h"
#include "base/dim.h"
#include "particles/pair_loop.h"

const char *const SolidGradients[]    = {"standard", "corrected", "SolidGradient", "SOLID_GRAD_", NULL};
const char *const SolidFormulations[] = {"updated", "total", "SolidFormulation", "SOLID_", NULL};
const char *const SolidLaws[]         = {"neo_hookean", "st_venant_kirchhoff", "SolidLaw", "SOLID_LAW_", NULL};

/* The moduli, as the scene's K and G (which -solid_K, -solid_G override) or as -solid_E, -solid_nu,
 * one pair or the other.  E and nu are read first and with a `set` flag, so that they enter
 * options_used only when given; then K and G are not read at all (recorded as defaults beside a
 * given E they would make options_used give both pairs, which is refused).  The 3D relations:
 * K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)), i.e. lambda = E nu / ((1 + nu) (1 - 2 nu)), mu = G;
 * a 2D run is plane strain with the same lambda and mu. */
static PetscErrorCode SolidModuliFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, SolidMaterial *m)
{
  PetscReal E = m->K > 0 ? 9 * m->K * m->G / (3 * m->K + m->G) : 0, nu = m->K > 0 ? (3 * m->K - 2 * m->G) / (2 * (3 * m->K + m->G)) : 0;
  PetscBool E_set, nu_set, K_given, G_given;
  PetscFunctionBeginUser;
  PetscCall(OptReal("-E", "Solid Young's modulus E (Pa), with -solid_nu instead of -solid_K and -solid_G: K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)) (default: from the scene's K and G)", "", E, &E, &E_set));
  PetscCall(OptReal("-nu", "Solid Poisson's ratio nu, with -solid_E (plane strain in 2D: lambda = E nu / ((1 + nu) (1 - 2 nu)), mu = E / (2 (1 + nu)))", "", nu, &nu, &nu_set));
  if (!E_set && !nu_set) {
    PetscCall(OptReal("-K", "Solid bulk modulus K (Pa); c0^2 = K / rho0, Eq. 20; lambda = K - 2 G / 3 (or give -solid_E and -solid_nu)", "", m->K, &m->K, NULL));
    PetscCall(OptReal("-G", "Solid shear modulus mu_s (Pa), Eq. 40 (or give -solid_E and -solid_nu)", "", m->G, &m->G, NULL));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, "-K", &K_given));
  PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, "-G", &G_given));
  PetscCheck(!K_given && !G_given, comm, PETSC_ERR_ARG_INCOMP, "Give the solid's moduli as -solid_K and -solid_G or as -solid_E and -solid_nu, not both (given: %s%s%s%s)", K_given ? "-solid_K " : "", G_given ? "-solid_G " : "", E_set ? "-solid_E " : "", nu_set ? "-solid_nu" : "");
  PetscCheck(E_set && nu_set, comm, PETSC_ERR_ARG_INCOMP, "Give -solid_E and -solid_nu together (only %s was given)", E_set ? "-solid_E" : "-solid_nu");
  PetscCheck(E > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_E %g must be > 0", (double)E);
  PetscCheck(nu > -1 && nu < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_nu %g must be in (-1, 0.5)", (double)nu);
  m->K = E / (3 * (1 - 2 * nu));
  m->G = E / (2 * (1 + nu));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The coupling's options (-fsi_), with a fluid: in the solid, which carries them. */
static PetscErrorCode FSISetFromOptions(Physics *ph)
{
  Solid s = ph->solid;
  PetscFunctionBeginUser;
  s->implicit = (PetscBool)(ph->fluid == FLUID_ISPH);
  s->mean_acc = PETSC_TRUE;
  s->row_stiffness = 1;
  s->transit  = ph->fluid == FLUID_ISPH ? 0.85 : 0.0; /* K, G x 5 gate: 1.0 swings the load -138..360 N/m, 0.85 runs clean */
  PetscOptionsBegin(ph->comm, "fsi_", "Fluid-structure coupling", "Solid");
  if (ph->fluid == FLUID_ISPH) PetscCall(OptBool("-implicit", "ISPH + solid: the solid rows of the pressure equation answer the solid's acceleration under that pressure (implicit interface; off = the solid seen as a wall at rest during the solve, unstable for light solids)", "", s->implicit, &s->implicit, NULL));
  if (ph->fluid == FLUID_ISPH) PetscCall(OptBool("-mean_acc", "ISPH, implicit interface: a solid particle's pressure row starts from its mean acceleration over the last fluid step, changed by what the new pressure does to it (Adami's moving wall); off = only that change, so that a thin solid's fast elastic oscillation, which the mean over a short fluid step keeps, stays out of the pressure (the Turek-Hron flag: docs/turek_hron.md)", "", s->mean_acc, &s->mean_acc, NULL));
  if (ph->fluid == FLUID_ISPH && s->implicit) PetscCall(OptReal("-row_stiffness", "ISPH, implicit interface: weight w of the solid's bonds in the inertia m + w dt^2 k / 4 that a solid particle's pressure row gives it (k: its bonds' stiffness).  The staggered coupling amplifies when that inertia is above twice the solid's real one, which for a thin flag in bending is the particle's share of its column; 0 = the particle's own mass, which is never above it (the Turek-Hron FSI3 flag, as dense as the water: docs/turek_hron_fsi2.md)", "", s->row_stiffness, &s->row_stiffness, NULL));
  if (ph->fluid == FLUID_ISPH) PetscCall(OptReal("-dt_transit", "ISPH + solid: the fluid step is at most this many times the time an elastic wave (c0 of the solid) takes to cross the solid's largest extent, since the pressure is frozen over the solid sub-steps (0 = no limit); a gate 5x stiffer than the rubber needs it", "", s->transit, &s->transit, NULL));
  PetscCall(OptBool("-repulsion", "Repulsive force Eq. 41 between fluid and solid particles, a one-sided push against each fluid particle's approach speed: it damps a structure's motion across the flow (the Turek-Hron flag: docs/turek_hron_fsi2.md) (default: on with -fluid wcsph, off with isph)", "", s->repulsion, &s->repulsion, NULL));
  PetscOptionsEnd();
  PetscCheck(s->transit >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fsi_dt_transit %g must be >= 0", (double)s->transit);
  PetscCheck(s->row_stiffness >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fsi_row_stiffness %g must be >= 0", (double)s->row_stiffness);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidSetFromOptions(Physics *ph)
{
  SolidMaterial *m = &ph->sl;
  Solid          s;
  PetscInt       grad = SOLID_GRAD_CORRECTED, form = SOLID_TOTAL;
  PetscBool      fluid = ph->has_fluid;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  ph->solid   = s;
  s->skin      = 0.4;
  s->subcycle  = PETSC_TRUE;
  s->repulsion = (PetscBool)(fluid && ph->fluid == FLUID_WCSPH);
  s->hourglass = 0;
  s->order     = 2;
  s->quadrature = PETSC_TRUE;
  s->clamp_face = PETSC_TRUE;
  PetscOptionsBegin(ph->comm, "solid_", "Elastic solid: hypo-elastic updated-Lagrangian (Eqs. 20, 23-40) or total-Lagrangian", "Solid");
  PetscCall(OptEList("-formulation", "total (default): total-Lagrangian neo-Hookean with a second-order reference gradient (converges in bending); updated: the paper's hypo-elastic scheme (Jaumann rate, artificial stress)", "", SolidFormulations, 2, SolidFormulations[form], &form, NULL));
  s->formulation = (SolidFormulation)form;
  PetscCall(OptReal("-damping", "Mass-proportional damping rate zeta (1/s): acc -= zeta v, to reach a static solution by dynamic relaxation (about twice the lowest angular frequency damps it critically); 0 = off", "", s->damping, &s->damping, NULL));
  if (s->formulation == SOLID_TOTAL) PetscCall(OptInt("-order", "Total-Lagrangian: the reference gradient is exact for displacements of this polynomial order (1: kernel-gradient correction; 2: also exact for the bending field at a free surface or clamp)", "", s->order, &s->order, NULL));
  if (s->formulation == SOLID_TOTAL && s->order == 2) PetscCall(OptBool("-cell_quadrature", "Total-Lagrangian, order 2: integrate each particle's cell to second order with the strain gradient of the fit (one point per particle leaves a plate n across (1 - 1/n^2) of its bending stiffness)", "", s->quadrature, &s->quadrature, NULL));
  if (s->order != 2) s->quadrature = PETSC_FALSE;
  if (s->order != 2) s->clamp_face = PETSC_FALSE; /* with the first-order fit the face points, dx/2 from the first column, made the root unstable (the cantilever at 5 across lost pairs at t = 0.08 s) */
  if (s->formulation == SOLID_TOTAL && s->order == 2) PetscCall(OptBool("-clamp_face", "Total-Lagrangian, order 2: a clamp is a boundary, its particles next to the body stand for the face midway to it in the fits, and it stores no energy (off: the clamp is material held still)", "", s->clamp_face, &s->clamp_face, NULL));
  s->h_factor = ph->kernel.h_factor;
  if (s->formulation == SOLID_TOTAL) PetscCall(OptReal("-h_factor", "Total-Lagrangian: h / dx of the solid's own pairs, its reference fit and elastic forces (at most -h_factor; the fluid and the fluid-solid pairs keep -h_factor).  A plate a few particles thick is softer in bending at a wide kernel: the Turek-Hron flag 4 across has its second mode 1.6 % lower at 2 dx than at 1.4 dx (default: -h_factor)", "", s->h_factor, &s->h_factor, NULL));
  s->h_ratio = s->h_factor / ph->kernel.h_factor; /* exactly 1 unless given */
  if (s->formulation == SOLID_TOTAL) PetscCall(OptReal("-hourglass", "Total-Lagrangian: hourglass-control coefficient zeta, the energy zeta G / 2 of the bonds' deviation from the affine fit (solid_terms.h); 0 = off", "", s->hourglass, &s->hourglass, NULL));
  PetscCall(OptReal("-rho", "Solid reference density (kg/m^3)", "", m->rho0, &m->rho0, NULL));
  PetscCall(SolidModuliFromOptions(PetscOptionsObject, ph->comm, m));
  {
    PetscInt law = m->law; /* the scene's default */
    PetscCall(OptEList("-law", "Total-Lagrangian: the hyper-elastic law, neo_hookean (S = G (I - C^-1) + lambda ln J C^-1) or st_venant_kirchhoff (S = lambda tr(E) I + 2 G E, E = (C - I) / 2; the Turek-Hron benchmark's); both with lambda = K - 2 G / 3", "", SolidLaws, 2, SolidLaws[law], &law, NULL));
    m->law = (SolidLaw)law;
  }
  PetscCall(OptReal("-alpha", "Solid artificial viscosity coefficient, Eq. 24", "", m->alpha, &m->alpha, NULL));
  PetscCall(OptReal("-art_stress", "Artificial stress coefficient e, Eqs. 25-31; 0 = off", "", m->eps, &m->eps, NULL));
  PetscCall(OptReal("-art_stress_n", "Exponent n of f = W_ab / W(dx, h) in the artificial stress, Eq. 23", "", m->n, &m->n, NULL));
  PetscCall(OptEList("-gradient", "Velocity gradient of the strain rate: standard (Eqs. 35-38) or corrected (Bonet-Lok, exact for linear fields)", "", SolidGradients, 2, SolidGradients[grad], &grad, NULL));
  if (fluid) PetscCall(OptBool("-subcycle", "Multi-rate: sub-cycle the solid with its own step inside each fluid step (off: one step, the smaller, for both)", "", s->subcycle, &s->subcycle, NULL));
  s->cfl = ph->cfl;
  PetscCall(OptReal("-cfl", "Courant number of the solid's step, cfl min(h, 1.3 dx) / (c0 + |v|) (default: -cfl)", "", s->cfl, &s->cfl, NULL));
  PetscCall(OptReal("-skin", "Neighbour-list skin of the solid sub-steps, in particle spacings", "", s->skin, &s->skin, NULL));
  PetscOptionsEnd();
  s->gradient = (SolidGradient)grad;
  if (fluid) PetscCall(FSISetFromOptions(ph));
  PetscCheck(s->damping >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_damping %g must be >= 0", (double)s->damping);
  PetscCheck(s->order == 1 || s->order == 2, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_order %" PetscInt_FMT " must be 1 or 2", s->order);
  /* the solid's pairs come from the one neighbour search, which reaches 2 h of the run's -h_factor */
  PetscCheck(s->h_factor >= 1 && s->h_factor <= ph->kernel.h_factor, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_h_factor %g must be in [1, %g] (h / dx of the solid's pairs; at most the run's -h_factor, whose neighbour search finds them)", (double)s->h_factor, (double)ph->kernel.h_factor);
  PetscCheck(s->hourglass >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_hourglass %g must be >= 0", (double)s->hourglass);
  PetscCheck(s->skin >= 0 && s->skin <= 2, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_skin %g must be in [0, 2] particle spacings", (double)s->skin);
  PetscCheck(s->cfl > 0 && s->cfl <= 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_cfl %g must be in (0, 1]", (double)s->cfl);
  /* the one-sided fits at a surface are stiffer than the bulk: measured on the oscillating plate
   * (6 across) the total-Lagrangian solid is stable at 0.35 and not at 0.4 */
  PetscCheck(s->formulation != SOLID_TOTAL || s->cfl <= 0.3, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_cfl %g is above 0.3, the stable limit of -solid_formulation total with a margin (its surface particles are stiffer than the bulk): use -solid_cfl 0.3 or less", (double)s->cfl);
  PetscCheck(m->law == SOLID_LAW_NEO_HOOKEAN || s->formulation == SOLID_TOTAL, ph->comm, PETSC_ERR_ARG_INCOMP, "-solid_law %s needs -solid_formulation total: the updated solid is hypo-elastic (a Jaumann rate of Hooke's law), it has no hyper-elastic law", SolidLaws[m->law]);
  PetscCheck(m->rho0 > 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_rho %g must be > 0", (double)m->rho0);
  PetscCheck(m->K > 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_K %g must be > 0", (double)m->K);
  PetscCheck(m->G >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_G %g must be >= 0", (double)m->G);
  PetscCheck(m->alpha >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_alpha %g must be >= 0", (double)m->alpha);
  PetscCheck(m->eps >= 0 && m->eps < 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_art_stress %g must be in [0, 1)", (double)m->eps);
  PetscCheck(m->n > 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-solid_art_stress_n %g must be > 0", (double)m->n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidSetUp(Physics *ph)
{
  SolidMaterial *m = &ph->sl;
  Solid          s = ph->solid;
  PetscBool      fluid = ph->has_fluid;

  PetscFunctionBeginUser;
  m->c0 = PetscSqrtReal(m->K / m->rho0);
  PetscCall(ParticlesEnableField(ph->P, FIELD_S, PETSC_TRUE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_ACC, PETSC_FALSE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_DRHO, PETSC_FALSE));
  if (s->gradient == SOLID_GRAD_CORRECTED && s->formulation == SOLID_UPDATED) PetscCall(ParticlesEnableField(ph->P, FIELD_KCORR, PETSC_FALSE)); /* ghosts: refreshed when computed */
  if (s->formulation == SOLID_TOTAL) {
    PetscCall(ParticlesEnableField(ph->P, FIELD_X0, PETSC_TRUE)); /* the reference configuration */
  }
  if (fluid) {
    PetscCall(ParticlesEnableField(ph->P, FIELD_FVIEW, PETSC_TRUE));
    PetscCall(ParticlesEnableField(ph->P, FIELD_VWALL, PETSC_FALSE));
  }
  if (s->repulsion) PetscCall(ParticlesEnableField(ph->P, FIELD_NORMAL, PETSC_TRUE));
  if (s->implicit && s->mean_acc) PetscCall(ParticlesEnableField(ph->P, FIELD_AMEAN, PETSC_FALSE));
  /* ISPH: the solid's loads (after the step's last rebuild) and its PPE rows (after the predictor's)
   * read the fluid ghosts' pressure, which nothing else recomputes there */
  if (fluid && ph->fluid == FLUID_ISPH) PetscCall(ParticlesEnableField(ph->P, FIELD_P, PETSC_TRUE));
  PetscCall(CellsCreateList(&ph->kernel, &s->nl));
  { /* Sums over the lattice of spacing 1 on one side of a flat surface, at a particle of its first
     * row: |sum V grad W| (nrm_min, the normal's threshold) and Eq. 41's repulsion.  Eq. 41 is a
     * plain sum over the solid neighbours within 2 h, not a kernel sum, and its 1/3 is the paper's
     * for 2D at h = 1.3 dx: a fluid particle dx from a flat solid has ~5 times as many such
     * neighbours in 3D and ~3 times at h = 2 dx (where the gate blew up at its 27th step).  So the
     * sum is scaled to the paper's (2D, 1.3 dx; the layer k = 0), exactly 1 there, and a slab
     * repeats the 2D run. */
    const PetscReal hh = ph->kernel.h_factor, href = SPH_H_FACTOR;
    PetscReal       g = 0, s2 = 0, s3 = 0, sref = 0;
    PetscInt        nr = PetscMax(KernelSupportRows(&ph->kernel), 3), nk = ph->dim == 3 ? nr : 0;
    for (PetscInt k = -nk; k <= nk; k++) /* one layer in 2D */
      for (PetscInt j = 0; j <= nr; j++)
        for (PetscInt i = -nr; i <= nr; i++) {
          PetscReal r = PetscSqrtReal((PetscReal)(i * i + j * j + k * k)), rep = j ? FSIRepulsion(-1.0, r / (2 * hh), 1.0) : 0;
          g += KernelF(&ph->kernel, r, hh) * j;
          s3 += rep;
          if (!k) s2 += rep;
          if (!k && j) sref += FSIRepulsion(-1.0, r / (2 * href), 1.0);
        }
    s->nrm_min         = 0.5 * PetscAbsReal(g);
    s->repulsion_scale = ph->dim == 3 ? (s3 > 0 ? sref / s3 : 1) : (s2 > 0 ? sref / s2 : 1);
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
  PetscCall(PetscFree((*s)->G0));
  PetscCall(PetscFree((*s)->slot));
  PetscCall(PetscFree2((*s)->Fd, (*s)->Qd));
  PetscCall(PetscSFDestroy(&(*s)->sf_slot));
  PetscCall(CellsDestroy(&(*s)->nl));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -sum_b V_b grad_a W_ab over the solid neighbours b of a */
typedef struct {
  Particles        P;
  const PetscReal *x, *m, *rho;
  PetscReal        g[3];
} NormalSum;

SPH_INLINE void NormalPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  NormalSum *s = (NormalSum *)ctx;
  PetscInt   b = p.b;
  if (!KindIsSolid(s->P->kind[b])) return;
  for (PetscInt i = 0; i < D; i++) s->g[i] -= s->m[b] / s->rho[b] * p.F * (s->x[D * a + i] - s->x[D * b + i]);
}

/* Outward normal of solid surface particles, -sum_b V_b grad_a W / |.| over solid neighbours (the
 * kernel form of Eqs. 42-43's tangent turned by 90 degrees: it needs no ordering of the surface
 * particles); zero inside the body. */
SPH_INLINE PetscErrorCode NormalsD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), *h = PField(P, FIELD_H);
  PetscReal       *nrm = PField(P, FIELD_NORMAL);
  const FieldId    refresh[] = {FIELD_NORMAL};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    NormalSum s = {.P = P, .x = x, .m = m, .rho = rho};
    PetscReal gn, dxa = h[a] / ph->kernel.h_factor;
    for (PetscInt i = 0; i < D; i++) nrm[D * a + i] = 0;
    if (!KindIsSolid(P->kind[a])) continue;
    SPHPairs(ph->solid->nl, a, NormalPair, &s, D);
    gn = PetscSqrtReal(VDot(s.g, s.g, D));
    if (gn * dxa > ph->solid->nrm_min)
      for (PetscInt i = 0; i < D; i++) nrm[D * a + i] = s.g[i] / gn;
  }
  PetscCall(HaloRefreshKinds(ph->halo, P, SolidKeep, 1, refresh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Normals(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, NormalsD, ph); }

PetscErrorCode SolidPrepare(Physics *ph)
{
  Solid            s = ph->solid;
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X);
  PetscFunctionBeginUser;
  PetscCall(NeighbourhoodSubList(ph->nb, SolidKeep, s->skin * ph->dx, s->nl));
  if (P->dim * P->n > s->cap_xref) {
    PetscCall(PetscFree(s->xref));
    s->cap_xref = 3 * P->n + 16;
    PetscCall(PetscMalloc1(s->cap_xref, &s->xref));
  }
  PetscCall(PetscArraycpy(s->xref, x, P->dim * P->n));
  if (s->formulation == SOLID_TOTAL) PetscCall(SolidTotalPrepare(ph));
  if (ph->has_fluid) { /* the fluid's last half kick came after its rebuild: the loads need its ghosts' velocities */
    const FieldId vel[] = {FIELD_V};
    PetscCall(HaloRefresh(ph->halo, P, 1, vel));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After the drift: ghosts take the owners' new state, or, once some solid has moved half the
 * skin since SolidPrepare, everything is rebuilt (collective decision). */
static PetscErrorCode SolidRefresh(Physics *ph)
{
  Solid            s = ph->solid;
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X);
  const FieldId    state[] = {FIELD_X, FIELD_RHO, FIELD_S};
  const PetscInt   D = P->dim;
  PetscReal        d2 = 0, lim = 0.5 * s->skin * ph->dx;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (P->kind[a] == KIND_SOLID) {
      PetscReal d[3] = {0, 0, 0};
      VSub(x + D * a, s->xref + D * a, d, D);
      d2 = PetscMax(d2, VDot(d, d, D));
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &d2, 1, MPIU_REAL, MPIU_MAX, ph->comm));
  if (d2 >= lim * lim) {
    PetscCall(NeighbourhoodRebuild(ph->nb, ph->step));
    PetscCall(SolidPrepare(ph));
    s->nrebuild++;
  } else {
    PetscCall(HaloRefreshKinds(ph->halo, P, SolidKeep, 3, state));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidRates(Physics *ph)
{
  PetscFunctionBeginUser;
  if (ph->solid->formulation == SOLID_TOTAL) PetscCall(CellsUpdatePairsF(ph->solid->nl, ph->P)); /* W: only the updated solid's artificial stress reads it */
  else PetscCall(CellsUpdatePairs(ph->solid->nl, ph->P));
  if (ph->solid->formulation == SOLID_TOTAL) {
    if (ph->solid->repulsion) PetscCall(Normals(ph));
    PetscCall(SolidTotalRates(ph));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (ph->solid->repulsion) PetscCall(Normals(ph));
  PetscCall(SolidUpdatedRates(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTransitLimit(Physics *ph, PetscReal *dt)
{
  Solid s = ph->solid;
  PetscFunctionBeginUser;
  *dt = PETSC_MAX_REAL;
  if (!s || s->transit <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (s->extent <= 0) { /* bounding box of the moving solids at the first call (SimSetUp: as built) */
    const PetscReal *x = PField(ph->P, FIELD_X);
    const PetscInt   D = ph->dim;
    PetscReal        b[6]; /* xmin, ymin[, zmin], then -xmax, ...: all as minima */
    for (PetscInt i = 0; i < 2 * D; i++) b[i] = PETSC_MAX_REAL;
    for (PetscInt a = 0; a < ph->P->n; a++)
      if (ph->P->kind[a] == KIND_SOLID)
        for (PetscInt i = 0; i < D; i++) { b[i] = PetscMin(b[i], x[D * a + i]); b[D + i] = PetscMin(b[D + i], -x[D * a + i]); }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, b, (PetscMPIInt)(2 * D), MPIU_REAL, MPIU_MIN, ph->comm));
    s->extent = 0;
    for (PetscInt i = 0; i < D; i++) s->extent = PetscMax(s->extent, -b[D + i] - b[i]);
    s->extent = b[0] < PETSC_MAX_REAL ? s->extent + ph->dx : 0;
    if (s->extent <= 0) s->transit = 0; /* no moving solid */
  }
  if (s->transit > 0) *dt = s->transit * s->extent / ph->sl.c0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidTimeStep(Physics *ph, PetscReal *dt)
{
  Particles        P = ph->P;
  const PetscReal *v = PField(P, FIELD_V), *acc = PField(P, FIELD_ACC), *h = PField(P, FIELD_H);
  /* The solid's stable step is set by its particle spacing, not by h: the nearest pairs carry the
   * stiffest mode.  -solid_cfl is calibrated at h = 1.3 dx (the paper's); at larger h / dx the step
   * stays that of h = 1.3 dx (at 2 dx it would be 1.54x longer: the elastic gate blew up in its
   * first fluid step with the Wendland kernel at 2 dx). */
  const PetscReal  hlen = PetscMin(1.0, SPH_H_FACTOR / ph->solid->h_factor) * ph->solid->h_ratio; /* of the particle's h */
  PetscReal        lim  = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (P->kind[a] == KIND_SOLID) lim = PetscMin(lim, AcousticStepLimit(ph->solid->cfl, hlen * h[a], ph->sl.c0, v + P->dim * a, acc + P->dim * a, P->dim));
  PetscCall(MPIU_Allreduce(&lim, dt, 1, MPIU_REAL, MPIU_MIN, ph->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* v += dt acc; the means over the fluid step (SolidBeginSubsteps) gain dt / dt_f of the current
 * acceleration and support force. */
static void Kick(Physics *ph, PetscReal dt)
{
  Particles        P = ph->P;
  Solid            s = ph->solid;
  PetscReal       *v = PField(P, FIELD_V), *am = PField(P, FIELD_AMEAN), w = ph->dt > 0 ? dt / ph->dt : 0;
  const PetscReal *acc = PField(P, FIELD_ACC);
  const PetscInt   D   = P->dim;
  for (PetscInt a = 0; a < P->n; a++) {
    if (P->kind[a] != KIND_SOLID) continue;
    for (PetscInt i = 0; i < D; i++) v[D * a + i] += dt * acc[D * a + i];
    if (am)
      for (PetscInt i = 0; i < D; i++) am[D * a + i] += w * acc[D * a + i];
  }
  for (PetscInt i = 0; i < D; i++) {
    s->support_mean[i] += w * s->support[i];
    s->load_mean[i] += w * s->load[i];
  }
}

PetscErrorCode SolidBeginSubsteps(Physics *ph)
{
  Particles  P = ph->P;
  PetscReal *am = PField(P, FIELD_AMEAN);
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 3; i++) ph->solid->support_mean[i] = ph->solid->load_mean[i] = 0;
  if (am) PetscCall(PetscArrayzero(am, P->dim * P->n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Kick-drift-kick like WCSPHStep, with density and stress as position-like variables:
 * v+ = v + dt/2 a;  (rho, S)' from the rates at (x, v+);  x' = x + dt v+;  v' = v+ + dt/2 a'. */
PetscErrorCode SolidStep(Physics *ph, PetscReal dt)
{
  Particles     P     = ph->P;
  const FieldId vel[] = {FIELD_V};

  PetscFunctionBeginUser;
  Kick(ph, 0.5 * dt);
  if (ph->prescribe) PetscCall(ph->prescribe(ph->prescribe_ctx));
  PetscCall(HaloRefreshKinds(ph->halo, P, SolidKeep, 1, vel)); /* only the solids were kicked */
  if (ph->solid->formulation == SOLID_UPDATED) PetscCall(SolidUpdatedDeform(ph, dt)); /* total: F follows from the positions */
  {
    PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V);
    for (PetscInt a = 0; a < P->n; a++) {
      if (P->kind[a] != KIND_SOLID) continue;
      for (PetscInt i = 0; i < P->dim; i++) x[P->dim * a + i] += dt * v[P->dim * a + i];
    }
  }
  PetscCall(SolidRefresh(ph));
  PetscCall(SolidRates(ph));
  Kick(ph, 0.5 * dt);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidEnergy(Physics *ph, PetscReal *ekin, PetscReal *estrain)
{
  Particles            P = ph->P;
  const SolidMaterial *m = &ph->sl;
  const PetscReal     *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *mass = PField(P, FIELD_M), *S = PField(P, FIELD_S), *p = PField(P, FIELD_P);
  PetscReal            e[2] = {0, 0};

  PetscFunctionBeginUser;
  const PetscInt       D = P->dim;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal SS, pa = p[a];
    if (!KindIsSolid(P->kind[a])) continue;
    if (D == 2) { /* plane strain: S_zz = -(S_xx + S_yy) */
      PetscReal sxx = S[3 * a], sxy = S[3 * a + 1], syy = S[3 * a + 2], szz = -(sxx + syy);
      SS = sxx * sxx + syy * syy + szz * szz + 2 * sxy * sxy;
    } else {
      const PetscReal *Sa = S + 6 * a;
      SS = Sa[0] * Sa[0] + Sa[3] * Sa[3] + Sa[5] * Sa[5] + 2 * (Sa[1] * Sa[1] + Sa[2] * Sa[2] + Sa[4] * Sa[4]);
    }
    e[0] += 0.5 * mass[a] * VDot(v + D * a, v + D * a, D);
    e[1] += mass[a] / rho[a] * ((m->G > 0 ? SS / (4 * m->G) : 0) + pa * pa / (2 * m->K));
  }
  if (ph->solid->formulation == SOLID_TOTAL) e[1] = SolidTotalStrainEnergy(ph);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPI_SUM, ph->comm));
  *ekin    = e[0];
  *estrain = e[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolidView(Physics *ph, PetscViewer v)
{
  const SolidMaterial *m = &ph->sl;
  PetscFunctionBeginUser;
  if (ph->solid->formulation == SOLID_TOTAL) {
    char own[64] = "";
    if (ph->solid->h_ratio != 1) PetscCall(PetscSNPrintf(own, sizeof(own), "; its own pairs at h = %g dx", (double)ph->solid->h_factor));
    PetscCall(PetscViewerASCIIPrintf(v, "Solid: total-Lagrangian %s, rho0 %g, K %g Pa, G %g Pa (lambda %g, mu %g Pa), c0 %g m/s; artificial viscosity alpha %g; hourglass control %g%s%s\n", m->law == SOLID_LAW_ST_VENANT_KIRCHHOFF ? "St Venant-Kirchhoff" : "neo-Hookean", (double)m->rho0, (double)m->K, (double)m->G, (double)(m->K - 2 * m->G / 3), (double)m->G, (double)m->c0, (double)m->alpha, (double)ph->solid->hourglass, own, m->eps > 0 ? "; -solid_art_stress not used" : ""));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscViewerASCIIPrintf(v, "Solid: rho0 %g, K %g Pa, G %g Pa, c0 %g m/s; artificial viscosity alpha %g; artificial stress e %g n %g%s; velocity gradient %s\n", (double)m->rho0, (double)m->K, (double)m->G, (double)m->c0, (double)m->alpha, (double)m->eps, (double)m->n, m->eps > 0 ? "" : " (off)", SolidGradients[ph->solid->gradient]));
  PetscFunctionReturn(PETSC_SUCCESS);
}
