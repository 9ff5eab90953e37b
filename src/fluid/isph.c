#include "fluid/isph.h"
#include "fluid/open_boundary.h"
#include "base/options_used.h"
#include "solid/solid.h"
#include "fluid/boundary.h"
#include "base/kernel.h"
#include "fluid/fluid_terms.h"
#include "fluid/shifting.h"
#include "base/dim.h"
#include "particles/pair_loop.h"

const char *const ISPHFreeSurfaces[] = {"density", "divr", "ISPHFreeSurface", "ISPH_FS_", NULL};
const char *const ISPHSources[]      = {"divergence", "density", "blend", "ISPHSource", "ISPH_SOURCE_", NULL};
const char *const ISPHGradients[]    = {"eq14", "corrected", "hybrid", "ISPHGradient", "ISPH_GRAD_", NULL};

PetscErrorCode ISPHSetFromOptions(Physics *ph)
{
  ISPH      s;
  PetscInt  fs, src, grad;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  ph->isph   = s;
  s->beta     = 0.9;
  s->divr_min = 1.5;
  /* Defaults measured on the still tank (docs/convergence.md): the corrected gradient is exact for
   * the hydrostatic field in the bulk, where Eq. 14 is 1 % off on the lattice; a small density
   * weight in the source restores the positions that the divergence source lets drift */
  s->blend    = 0.01;
  s->alpha    = 0.1;
  s->source   = ISPH_SOURCE_BLEND;
  s->gradient = ISPH_GRAD_CORRECTED;
  s->solid_eq14 = PETSC_TRUE;
  /* a thin jet's correction matrix is nearly singular; corrected there, splashing particles were
   * flung at 16 m/s and over walls (docs/convergence.md, -isph_gradient_cond) */
  s->grad_cond  = 0.25;
  fs = s->fs; src = s->source; grad = s->gradient;
  PetscOptionsBegin(ph->comm, "isph_", "ISPH fluid (section 2.8)", "ISPH");
  PetscCall(OptEList("-free_surface", "Free-surface criterion: density (rho* < beta rho0, section 2.5) or divr (divergence of position)", "", ISPHFreeSurfaces, 2, ISPHFreeSurfaces[fs], &fs, NULL));
  PetscCall(OptReal("-beta", "Free surface where rho* < beta rho0 (paper: 0.8 < beta < 0.99)", "", s->beta, &s->beta, NULL));
  PetscCall(OptReal("-divr", "Free surface where div r < this (2 in the bulk in 2D)", "", s->divr_min, &s->divr_min, NULL));
  PetscCall(OptEList("-source", "PPE source: divergence (Eq. 13, 48), density ((rho0 - rho*)/(rho0 dt^2)) or blend", "", ISPHSources, 3, ISPHSources[src], &src, NULL));
  PetscCall(OptReal("-blend", "Weight of the density source in -isph_source blend", "", s->blend, &s->blend, NULL));
  PetscCall(OptEList("-gradient", "Pressure gradient of the corrector: eq14 (symmetric, Eq. 14), corrected (Bonet-Lok), hybrid (corrected on and next to the free surface)", "", ISPHGradients, 3, ISPHGradients[grad], &grad, NULL));
  PetscCall(OptReal("-gradient_cond", "The corrected gradient only where its correction matrix is well conditioned: smallest over largest eigenvalue above this (1 on a full or half support; small across a thin jet; 0: wherever it is invertible); elsewhere the uncorrected difference form", "", s->grad_cond, &s->grad_cond, NULL));
  PetscCall(OptBool("-solid_eq14", "Fluid particles next to a solid body (and not at the free surface) take Eq. 14, whose pair forces are those the body receives: the momentum exchange is exact", "", s->solid_eq14, &s->solid_eq14, NULL));
  PetscCall(OptReal("-alpha", "Artificial viscosity (Eq. 24, velocity scale c0) in the predictor; damps the free-surface noise of the projection", "", s->alpha, &s->alpha, NULL));
  PetscCall(OptReal("-wall_av", "Artificial viscosity against walls and solids, as a factor of -isph_alpha: with the walls at rest it acts as a friction that slows a thin front running along a floor (the dam break's front reaches the far wall late); 0 = none, the walls hold the fluid by pressure and Eq. 16 alone", "", ph->fl.wall_av, &ph->fl.wall_av, NULL));
  PetscCall(OptBool("-wall_contact", "A free-surface particle (P = 0, so no pressure stops it) that approaches a wall within dx of its first row loses its velocity towards the wall", "", s->wall_contact, &s->wall_contact, NULL));
  PetscCall(OptReal("-shift", "Particle shifting coefficient A (D = A h |v| dt, Skillen et al. 2013); 0 = off", "", s->shift, &s->shift, NULL));
  PetscOptionsEnd();
  s->fs = (ISPHFreeSurface)fs; s->source = (ISPHSource)src; s->gradient = (ISPHGradient)grad;
  PetscCheck(s->beta > 0 && s->beta < 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_beta %g must be in (0, 1); the paper uses 0.8 .. 0.99", (double)s->beta);
  PetscCheck(s->divr_min > 0 && s->divr_min < 2, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_divr %g must be in (0, 2)", (double)s->divr_min);
  PetscCheck(s->blend >= 0 && s->blend <= 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_blend %g must be in [0, 1]", (double)s->blend);
  PetscCheck(s->alpha >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_alpha %g must be >= 0", (double)s->alpha);
  PetscCheck(ph->fl.wall_av >= 0 && ph->fl.wall_av <= 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_wall_av %g must be in [0, 1] (a factor of -isph_alpha)", (double)ph->fl.wall_av);
  PetscCheck(s->shift >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_shift %g must be >= 0", (double)s->shift);
  PetscCheck(s->grad_cond >= 0 && s->grad_cond < 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-isph_gradient_cond %g must be in [0, 1): the smallest over the largest eigenvalue of the correction matrix (0.25 the default)", (double)s->grad_cond);
  if (s->source == ISPH_SOURCE_DIVERGENCE) s->blend = 0;
  if (s->source == ISPH_SOURCE_DENSITY) s->blend = 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHSetUp(Physics *ph)
{
  ISPH s = ph->isph;
  PetscFunctionBeginUser;
  s->lat_w    = KernelLatticeSum(&ph->kernel, LATTICE_W, 0);
  s->lat_divr = KernelLatticeSum(&ph->kernel, LATTICE_DIVR, 0);
  PetscCall(PPECreate(ph->comm, &s->ppe));
  PetscCall(PPESetFromOptions(s->ppe, (PetscBool)!(ph->solid && ph->solid->implicit)));
  s->ppe->row_stiffness = ph->solid ? ph->solid->row_stiffness : 1;
  PetscCall(ParticlesEnableField(ph->P, FIELD_ACC, PETSC_FALSE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_VWALL, PETSC_FALSE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_VSTAR, PETSC_TRUE)); /* read by neighbours after the predictor's rebuild */
  PetscCall(ParticlesEnableField(ph->P, FIELD_FS, PETSC_FALSE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_ROW, PETSC_FALSE));
  if (s->ppe->wall_approach) PetscCall(ParticlesEnableField(ph->P, FIELD_WNORMAL, PETSC_FALSE)); /* the walls' rows (ppe.c, WallNormalsD) */
  if (ph->fl.xsph > 0 || s->shift > 0) PetscCall(ParticlesEnableField(ph->P, FIELD_XSPH, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHDestroy(ISPH *isph)
{
  PetscFunctionBeginUser;
  if (!*isph) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PPEDestroy(&(*isph)->ppe));
  PetscCall(PetscFree((*isph)->src));
  PetscCall(PetscFree(*isph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHView(Physics *ph, PetscViewer v)
{
  ISPH s = ph->isph;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "ISPH: free surface by %s (%s %g), PPE source %s (density weight %g), gradient %s (corrected where its matrix's eigenvalue ratio > %g)%s, AV alpha %g, shifting A = %g, XSPH %g\n", ISPHFreeSurfaces[s->fs], s->fs == ISPH_FS_DENSITY ? "beta" : "div r <", (double)(s->fs == ISPH_FS_DENSITY ? s->beta : s->divr_min), ISPHSources[s->source], (double)s->blend, ISPHGradients[s->gradient], (double)s->grad_cond, s->solid_eq14 && s->gradient != ISPH_GRAD_EQ14 ? " (Eq. 14 next to solids)" : "", (double)s->alpha, (double)s->shift, (double)ph->fl.xsph));
  PetscCall(PPEView(s->ppe, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHInitialize(Physics *ph)
{
  Particles  P   = ph->P;
  PetscReal *rho = PField(P, FIELD_RHO);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n + P->ng; a++)
    if (KindIsWall(P->kind[a])) rho[a] = ph->fl.rho0; /* solids' fluid view: BoundaryWallVelocity */
  PetscCall(BoundaryWallVelocity(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHTimeStep(Physics *ph, PetscReal *dt)
{
  Particles        P = ph->P;
  const PetscReal *v = PField(P, FIELD_V), *h = PField(P, FIELD_H);
  const PetscReal  g = PetscSqrtReal(VDot(ph->g, ph->g, P->dim));
  PetscReal        lim = PETSC_MAX_REAL, hmin = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  /* The force limit uses the body force only: the projection's velocity change does not scale
   * with dt, so a limit on (v - v_t)/dt would shrink dt without end. */
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal vn;
    if (!KindIsFluid(P->kind[a])) continue;
    vn   = PetscSqrtReal(VDot(v + P->dim * a, v + P->dim * a, P->dim));
    hmin = PetscMin(hmin, h[a]);
    if (vn > 0) lim = PetscMin(lim, ph->cfl * h[a] / vn);                                     /* CFL on the flow speed */
    if (g > 0) lim = PetscMin(lim, 0.25 * PetscSqrtReal(h[a] / g));                            /* body force */
    if (ph->fl.mu > 0) lim = PetscMin(lim, 0.125 * h[a] * h[a] * ph->fl.rho0 / ph->fl.mu); /* viscous */
    if (ph->isph->alpha > 0) lim = PetscMin(lim, 0.5 * h[a] / (ph->isph->alpha * ph->fl.c0));    /* explicit AV, nu ~ alpha c0 h / 8 */
  }
  { /* the fallback is decided on the global minimum: a rank without fluid has no limit of its own,
     * and its fallback would cut every rank's step (8 ranks of the dam break: 81 steps, not 41) */
    PetscReal m[3] = {lim, hmin, PETSC_MAX_REAL};
    if (ph->solid) PetscCall(SolidTransitLimit(ph, &m[2])); /* the pressure is frozen over the solid sub-steps: at most about one elastic transit */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 3, MPIU_REAL, MPIU_MIN, ph->comm));
    lim = m[0] == PETSC_MAX_REAL ? ph->cfl * m[1] / ph->v_ref : m[0]; /* nothing moves and no force yet */
    *dt = PetscMin(lim, m[2]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the predictor gathers over the pairs of fluid particle a (PredictorD). */
typedef struct {
  const FluidMaterial *fl;
  Particles            P;
  const PetscReal     *x, *v, *rho, *m, *h, *vw, *fv;
  PetscReal            alpha, alpha_wall; /* Eq. 24's between fluid particles, against walls and solids */
  PetscReal            ac[3];
} PredictorSum;

/* Eq. 16's pair against b's no-slip velocity, and Eq. 24's */
SPH_INLINE void PredictorPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  PredictorSum        *s = (PredictorSum *)ctx;
  const FluidMaterial *fl = s->fl;
  const PetscReal     *v = s->v, *rho = s->rho;
  PetscInt             b = p.b;
  PetscReal            d[3], dvab[3], r2, hab = PairH(s->h[a], s->h[b]);
  const PetscReal     *vb = KindIsBoundary(s->P->kind[b]) ? s->vw + D * b : v + D * b;
  PetscReal            mb, rb, pb, c, av;
  VSub(s->x + D * a, s->x + D * b, d, D);
  r2 = VDot(d, d, D);
  FluidView(s->fv, s->P->kind[b], b, s->m, rho, NULL, &mb, &rb, &pb);
  c = LaminarViscosity(mb, fl->mu, rho[a], rb, p.F * r2, r2, hab, fl->eta, fl->lap_kappa);
  VSub(v + D * a, v + D * b, dvab, D);
  av = s->alpha > 0 ? mb * ArtificialViscosity(KindIsFluid(s->P->kind[b]) ? s->alpha : s->alpha_wall, fl->c0, hab, 0.5 * (rho[a] + rb), VDot(dvab, d, D), r2) * p.F : 0;
  for (PetscInt i = 0; i < D; i++) s->ac[i] += c * (v[D * a + i] - vb[i]) - av * d[i];
}

/* Eqs. 45-47: v* = v + dt (g + viscous Eq. 16) at r_t; r* = r + dt v.  Walls get
 * v* = v + dt g, the velocity whose projection with their Neumann pressure (ppe.h) leaves them
 * at rest, so that the velocity divergence sees no spurious source at a wall in hydrostatics. */
SPH_INLINE PetscErrorCode PredictorD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *vw = PField(P, FIELD_VWALL), *fv = PField(P, FIELD_FVIEW);
  PetscReal       *x = PField(P, FIELD_X), *vs = PField(P, FIELD_VSTAR);
  const PetscReal  dt = ph->dt, mu = ph->fl.mu, alpha = ph->isph->alpha;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PredictorSum s = {.fl = &ph->fl, .P = P, .x = x, .v = v, .rho = rho, .m = m, .h = h, .vw = vw, .fv = fv, .alpha = alpha, .alpha_wall = alpha * ph->fl.wall_av, .ac = {ph->g[0], ph->g[1], ph->g[2]}};
    if (KindIsFluid(P->kind[a]) && (mu > 0 || alpha > 0)) SPHPairs(ph->cells, a, PredictorPair, &s, D);
    for (PetscInt i = 0; i < D; i++) vs[D * a + i] = v[D * a + i] + dt * s.ac[i];
  }
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a]))
      for (PetscInt i = 0; i < D; i++) x[D * a + i] += dt * v[D * a + i];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Predictor(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, PredictorD, ph); }

/* What the summation density gathers over the pairs of fluid particle a. */
typedef struct {
  Particles        P;
  const PetscReal *x, *m, *vs, *fv, *rho;
  PetscReal        rho0;
  PetscReal        sw, divr, div; /* sum m W, div r (unscaled), div v* */
} DensitySum;

/* Eq. 17's pair, div r's and Eq. 13's div v* */
SPH_INLINE void DensityPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  DensitySum *s = (DensitySum *)ctx;
  PetscInt    b = p.b;
  PetscReal   d[3], dvs[3], F = p.F, mb, rb, pb;
  VSub(s->x + D * a, s->x + D * b, d, D);
  VSub(s->vs + D * b, s->vs + D * a, dvs, D);
  FluidView(s->fv, s->P->kind[b], b, s->m, s->rho, NULL, &mb, &rb, &pb);
  s->sw += mb * p.W;
  s->divr -= mb / s->rho0 * F * VDot(d, d, D);
  s->div += mb * F * VDot(dvs, d, D);
}

/* rho* by summation (Eq. 17) normalised by the full-lattice sum, walls at rho0; free surface by
 * rho* < beta rho0 (section 2.5) or div r < divr_min; and the PPE source of fluid rows,
 * (1 - w) div v* / dt (Eq. 13 with 1/rho_a, Eq. 48) + w (rho0 - rho*) / (rho0 dt^2) (density
 * invariance, Shao & Lo 2003): one pass, since v* of the neighbours came with the rebuild. */
SPH_INLINE PetscErrorCode DensityFreeSurfaceSourceD(Physics *ph, const PetscInt D)
{
  ISPH             s = ph->isph;
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *vs = PField(P, FIELD_VSTAR), *fv = PField(P, FIELD_FVIEW);
  PetscReal       *rho = PField(P, FIELD_RHO), *fs = PField(P, FIELD_FS);
  const PetscReal  rho0 = ph->fl.rho0, dt = ph->dt, w = s->blend;
  const PetscBool  confined = ph->confined;
  const FieldId    refresh[] = {FIELD_RHO, FIELD_FS};
  PetscInt         nfree = 0;

  PetscFunctionBeginUser;
  if (P->n > s->cap_src) {
    PetscCall(PetscFree(s->src));
    s->cap_src = (PetscInt)(1.2 * P->n) + 16;
    PetscCall(PetscMalloc1(s->cap_src, &s->src));
  }
  for (PetscInt a = 0; a < P->n; a++) {
    fs[a] = 0; s->src[a] = 0;
    if (!KindIsFluid(P->kind[a])) {
      if (!KindIsSolid(P->kind[a])) rho[a] = rho0; /* a solid keeps its own */
      continue;
    }
    DensitySum sum = {.P = P, .x = x, .m = m, .vs = vs, .fv = fv, .rho = rho, .rho0 = rho0, .sw = m[a] * KernelW(&ph->kernel, 0, h[a])};
    SPHPairsW(ph->cells, P, a, PETSC_TRUE, DensityPair, &sum, D);
    rho[a] = sum.sw / s->lat_w;
    sum.divr *= 2.0 / s->lat_divr;
    /* a confined flow (Taylor-Green, Poiseuille) has no free surface: a particle whose rho* dips
     * below beta rho0 there is disorder, and a P = 0 row inside the fluid would be wrong */
    fs[a] = !confined && (s->fs == ISPH_FS_DENSITY ? rho[a] < s->beta * rho0 : sum.divr < s->divr_min) ? 1.0 : 0.0;
    s->src[a] = (1 - w) * sum.div / (rho[a] * dt) + w * (rho0 - rho[a]) / (rho0 * dt * dt);
    if (ph->open) OpenPressureRows(ph, a, &fs[a], &s->src[a]); /* open boundaries' buffers */
    nfree += fs[a] > 0;
  }
  PetscCall(MPIU_Allreduce(&nfree, &s->nfree, 1, MPIU_INT, MPI_SUM, ph->comm));
  PetscCall(HaloRefresh(ph->halo, P, 2, refresh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DensityFreeSurfaceSource(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, DensityFreeSurfaceSourceD, ph); }

/* What the pressure gradient gathers over the pairs of fluid particle a. */
typedef struct {
  Particles        P;
  const PetscReal *x, *m, *rho, *p, *fs, *fv;
  PetscReal        rho0, pa;                  /* p_a / rho_a^2 */
  PetscReal        gs[3], gd[3], M[6];        /* Eq. 14; the difference form and its correction matrix */
  PetscBool        near, body;                /* a fluid neighbour on the free surface; a solid neighbour */
} GradientSum;

/* Eq. 14's pair, the difference form's and its correction matrix's */
SPH_INLINE void PressureGradientPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  GradientSum     *s = (GradientSum *)ctx;
  const PetscReal *p = s->p, *fs = s->fs;
  PetscInt         b = pr.b, kb = s->P->kind[b];
  PetscReal        d[3], F = pr.F, mb, rb, pb, cs, vb;
  VSub(s->x + D * a, s->x + D * b, d, D);
  FluidView(s->fv, kb, b, s->m, s->rho, p, &mb, &rb, &pb);
  cs = mb * (pb / (rb * rb) + s->pa) * F; vb = mb / s->rho0 * F;
  for (PetscInt i = 0; i < D; i++) s->gs[i] += cs * d[i];
  if (!(KindIsWall(kb) && fs[b] > 0)) { /* a dry wall (its pressure clipped, ppe.c) would tilt the plane fit */
    for (PetscInt i = 0; i < D; i++) s->gd[i] += vb * (pb - p[a]) / s->rho0 * d[i];
    SymOuterSubtract(s->M, vb, d, D); /* (x_b - x_a) (x) V_b grad_a W */
  }
  if (fs[b] > 0 && KindIsFluid(kb)) s->near = PETSC_TRUE;
  if (KindIsSolid(kb)) s->body = PETSC_TRUE;
}

/* grad P / rho at particle a.  Eq. 14 (symmetric, conserves momentum; its rho_a cancels), or the
 * difference form with the kernel-gradient correction of Bonet & Lok 1999, exact for a linear P
 * on a truncated support: the free surface, where Eq. 14 sees half the gradient and lets surface
 * particles fall at g/2.  The corrected form divides by rho0: rho* is truncated there too.  One
 * pass gathers both forms and whether a free-surface particle is in reach (hybrid). */
SPH_INLINE void PressureGradient(Particles P, Cells C, PetscInt a, ISPHGradient mode, PetscBool solid_eq14, PetscReal cond, PetscReal rho0, PetscReal g[], const PetscInt D)
{
  const PetscReal *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *fs = PField(P, FIELD_FS);
  GradientSum      s = {.P = P, .x = PField(P, FIELD_X), .m = PField(P, FIELD_M), .rho = rho, .p = p, .fs = fs, .fv = PField(P, FIELD_FVIEW), .rho0 = rho0, .pa = p[a] / (rho[a] * rho[a]), .near = (PetscBool)(fs[a] > 0)};
  PetscBool        corrected;
  SPHPairs(C, a, PressureGradientPair, &s, D);
  corrected = (PetscBool)(mode == ISPH_GRAD_CORRECTED || (mode == ISPH_GRAD_HYBRID && s.near));
  if (solid_eq14 && s.body && !s.near) corrected = PETSC_FALSE; /* the pair forces the body receives (FluidPairLoad) */
  if (!corrected) {
    for (PetscInt i = 0; i < D; i++) g[i] = s.gs[i];
    return;
  }
  /* the correction only where M is well conditioned: its eigenvalues' ratio above cond (a thin jet's
   * M is nearly singular, and M^-1 amplifies the pressure's noise across it) */
  if (!SymSolveConditioned(s.M, s.gd, cond, g, D))
    for (PetscInt i = 0; i < D; i++) g[i] = s.gd[i];
}

/* What the wall contact gathers over the pairs of particle a: the wall's volume gradient, then the
 * distance along its normal n. */
typedef struct {
  Particles        P;
  const PetscReal *x, *m;
  PetscReal        rho0;
  PetscReal        g[3], n[3], dmin;
} WallContactSum;

/* V_w grad_a W_aw of a wall neighbour */
SPH_INLINE void WallVolumePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  WallContactSum *s = (WallContactSum *)ctx;
  PetscInt        b = p.b;
  if (!KindIsWall(s->P->kind[b])) return;
  for (PetscInt i = 0; i < D; i++) s->g[i] += s->m[b] / s->rho0 * p.F * (s->x[D * a + i] - s->x[D * b + i]);
}

/* (x_a - x_w) . n of a first-row wall neighbour */
SPH_INLINE void WallDistancePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  WallContactSum *s = (WallContactSum *)ctx;
  PetscReal       d[3];
  if (s->P->kind[p.b] != KIND_WALL) return;
  VSub(s->x + D * a, s->x + D * p.b, d, D);
  s->dmin = PetscMin(s->dmin, VDot(d, s->n, D));
}

/* A free-surface particle has P = 0 in the pressure equation, so no pressure acts on it and a wall
 * it flies at cannot push it back until it has passed the wall's first row (a splashing front at an
 * impact).  Such a particle within dx of the first wall row, moving towards the wall, loses that
 * velocity component (an inelastic contact).  The wall's normal is that of the wall particles'
 * volume seen from the particle, n = -sum_w V_w grad_a W_aw / |.|; the distance is the smallest
 * (x_a - x_w) . n over the first-row (KIND_WALL) neighbours.  Walls are at rest. */
SPH_INLINE void WallContact(Particles P, Cells C, PetscInt a, PetscReal rho0, PetscReal dxa, PetscReal v[], const PetscInt D)
{
  WallContactSum s = {.P = P, .x = PField(P, FIELD_X), .m = PField(P, FIELD_M), .rho0 = rho0, .dmin = PETSC_MAX_REAL};
  PetscReal      gn, vn;
  SPHPairs(C, a, WallVolumePair, &s, D);
  gn = PetscSqrtReal(VDot(s.g, s.g, D));
  if (gn == 0) return;
  for (PetscInt i = 0; i < D; i++) s.n[i] = -s.g[i] / gn;
  SPHPairs(C, a, WallDistancePair, &s, D);
  vn = VDot(v, s.n, D);
  if (s.dmin < dxa && vn < 0)
    for (PetscInt i = 0; i < D; i++) v[i] -= vn * s.n[i];
}

/* Eqs. 49, 51: v = v* - dt grad P / rho; acc = (v - v_t) / dt. */
SPH_INLINE PetscErrorCode CorrectorD(Physics *ph, const PetscInt D)
{
  ISPH             s = ph->isph;
  Particles        P = ph->P;
  Cells            C = ph->cells;
  const PetscReal *vs = PField(P, FIELD_VSTAR);
  PetscReal       *v = PField(P, FIELD_V), *acc = PField(P, FIELD_ACC);
  const PetscReal  dt = ph->dt;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal g[3], vn[3];
    if (!KindIsFluid(P->kind[a])) continue;
    PressureGradient(P, C, a, s->gradient, s->solid_eq14, s->grad_cond, ph->fl.rho0, g, D);
    for (PetscInt i = 0; i < D; i++) vn[i] = vs[D * a + i] - dt * g[i];
    if (s->wall_contact && PField(P, FIELD_FS)[a] > 0) WallContact(P, C, a, ph->fl.rho0, PField(P, FIELD_H)[a] / ph->kernel.h_factor, vn, D);
    for (PetscInt i = 0; i < D; i++) {
      acc[D * a + i] = (vn[i] - v[D * a + i]) / dt;
      v[D * a + i]   = vn[i];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Corrector(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, CorrectorD, ph); }

/* What the drift gathers over the pairs of fluid particle a. */
typedef struct {
  Particles        P;
  const PetscReal *x, *v, *m, *rho, *fs;
  PetscReal        rho0;
  PetscBool        xsph, grad;        /* XSPH; the shift's velocity correction */
  PetscReal        sx[3], c[3];       /* XSPH; grad C */
  PetscBool        near;              /* a fluid neighbour on the free surface */
  ShiftGrad        sg;
} DriftSum;

/* XSPH's pair (Eq. 44) and shifting's (shifting.h) */
SPH_INLINE void DriftPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  DriftSum        *s = (DriftSum *)ctx;
  const PetscReal *m = s->m, *rho = s->rho;
  PetscInt         b = p.b;
  PetscReal        d[3], dvab[3];
  VSub(s->x + D * a, s->x + D * b, d, D);
  VSub(s->v + D * a, s->v + D * b, dvab, D);
  if (KindIsFluid(s->P->kind[b])) {
    if (s->xsph) {
      PetscReal w = XSPHWeight(p.W, m[b], rho[a], rho[b]);
      for (PetscInt i = 0; i < D; i++) s->sx[i] -= w * dvab[i];
    }
    if (s->fs[b] > 0) s->near = PETSC_TRUE;
    if (s->grad) ShiftGradAdd(&s->sg, m[b] / s->rho0, p.F, d, dvab, D);
  }
  if (!KindIsSolid(s->P->kind[b])) /* a solid's volume: its own mass over its own density */
    for (PetscInt i = 0; i < D; i++) s->c[i] += m[b] / s->rho0 * p.F * d[i];
  else
    for (PetscInt i = 0; i < D; i++) s->c[i] += m[b] / rho[b] * p.F * d[i];
}

/* Position corrections as velocities: XSPH (Eq. 44) and Fickian shifting (shifting.h); a particle
 * is next to the free surface when a fluid neighbour is on it. */
SPH_INLINE PetscErrorCode DriftD(Physics *ph, const PetscInt D)
{
  ISPH             s = ph->isph;
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), *v = PField(P, FIELD_V), *h = PField(P, FIELD_H), *fs = PField(P, FIELD_FS);
  PetscReal       *xs = PField(P, FIELD_XSPH);
  const PetscReal  dt = ph->dt, rho0 = ph->fl.rho0, eps = ph->fl.xsph;
  const FieldId    vel[] = {FIELD_V};
  PetscReal       *dv = NULL; /* velocity corrections of shifted particles, applied after the loop (2D) */

  PetscFunctionBeginUser;
  if (s->shift > 0 && ph->fl.shift_correct) PetscCall(PetscCalloc1(D * P->n, &dv));
  if (eps != 0 || dv) PetscCall(HaloRefresh(ph->halo, P, 1, vel)); /* only XSPH and the shift's velocity correction read the neighbours' v */
  for (PetscInt a = 0; a < P->n; a++) {
    for (PetscInt i = 0; i < D; i++) xs[D * a + i] = 0;
    if (!KindIsFluid(P->kind[a])) continue;
    DriftSum sum = {.P = P, .x = x, .v = v, .m = m, .rho = rho, .fs = fs, .rho0 = rho0, .xsph = (PetscBool)(eps != 0), .grad = (PetscBool)!!dv};
    SPHPairsW(ph->cells, P, a, sum.xsph, DriftPair, &sum, D); /* W only for XSPH */
    for (PetscInt i = 0; i < D; i++) xs[D * a + i] = eps * sum.sx[i];
    ShiftVelocity(s->shift, ph->fl.shift_dmax, ph->fl.shift_vmin, fs[a] > 0 ? SHIFT_SURFACE : sum.near ? SHIFT_NEAR_SURFACE : SHIFT_BULK, h[a], v + D * a, dt, sum.c, xs + D * a, D);
    if (dv) {
      PetscReal dr[3];
      for (PetscInt i = 0; i < D; i++) dr[i] = dt * (xs[D * a + i] - eps * sum.sx[i]);
      ShiftCorrectVelocity(&sum.sg, dr, dv + D * a, D);
    }
  }
  if (dv) {
    PetscReal *vv = PField(P, FIELD_V);
    for (PetscInt k = 0; k < D * P->n; k++) vv[k] += dv[k];
    PetscCall(PetscFree(dv));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Drift(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, DriftD, ph); }

/* Eq. 50: r = r_t + dt (v_t + v) / 2 = r* + dt^2 acc / 2, plus the drift corrections. */
SPH_INLINE PetscErrorCode MoveToEndD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *acc = PField(P, FIELD_ACC), *xs = PField(P, FIELD_XSPH);
  PetscReal       *x = PField(P, FIELD_X);
  const PetscReal  dt = ph->dt;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    for (PetscInt i = 0; i < D; i++) x[D * a + i] += 0.5 * dt * dt * acc[D * a + i] + (xs ? dt * xs[D * a + i] : 0);
  }
  return PETSC_SUCCESS;
}

static PetscErrorCode MoveToEnd(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, MoveToEndD, ph); }

PetscErrorCode ISPHAssemble(Physics *ph)
{
  ISPH s = ph->isph;
  PetscFunctionBeginUser;
  PetscCall(PPENumber(s->ppe, ph));
  PetscCall(PPEAssemble(s->ppe, ph, s->src));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHPressureEquation(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(DensityFreeSurfaceSource(ph));
  PetscCall(ISPHAssemble(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHPredict(Physics *ph)
{
  PetscFunctionBeginUser;
  if (ph->has_solid) PetscCall(BoundaryWallVelocity(ph)); /* the solids moved (and may have rebuilt) since the last step */
  PetscCall(Predictor(ph));
  if (ph->open) { /* crossings of the open boundaries' planes; the inlets' v* before the ghosts take it */
    PetscCall(OpenAfterDrift(ph));
    PetscCall(OpenImpose(ph, ph->t + ph->dt));
  }
  PetscCall(NeighbourhoodRebuild(ph->nb, ph->step)); /* neighbours at r* (and the inflow's new particles) */
  PetscCall(DensityFreeSurfaceSource(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHSolve(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(PPESolve(ph->isph->ppe, ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ISPHCorrect(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(Corrector(ph));
  if (ph->open) { /* the buffers: no acceleration, an outlet's velocity the fluid's upstream, an inlet's the profile's */
    const FieldId vel[] = {FIELD_V};
    PetscCall(HaloRefresh(ph->halo, ph->P, 1, vel)); /* the corrected velocities, which an outlet reads */
    PetscCall(OpenRates(ph));
    PetscCall(OpenImpose(ph, ph->t + ph->dt));
  }
  if (PField(ph->P, FIELD_XSPH)) PetscCall(Drift(ph));
  if (ph->open) PetscCall(OpenNoShift(ph));
  PetscCall(MoveToEnd(ph));
  PetscCall(NeighbourhoodRebuild(ph->nb, ph->step));
  PetscCall(BoundaryWallVelocity(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}
