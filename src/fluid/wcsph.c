#include "fluid/wcsph.h"
#include "fluid/open_boundary.h"
#include "base/options_used.h"
#include "fluid/boundary.h"
#include "base/kernel.h"
#include "fluid/fluid_terms.h"
#include "solid/solid.h"
#include "fluid/shifting.h"
#include "base/dim.h"
#include "particles/pair_loop.h"

PetscErrorCode WCSPHSetFromOptions(Physics *ph)
{
  FluidMaterial *fl   = &ph->fl;
  PetscReal      skin = WCSPH_SKIN_DEFAULT;
  PetscFunctionBeginUser;
  PetscOptionsBegin(ph->comm, "wcsph_", "WCSPH fluid", "WCSPH");
  PetscCall(OptDeprecated("-alpha", "-wcsph_alpha"));
  PetscCall(OptDeprecated("-delta", "-wcsph_delta"));
  PetscCall(OptReal("-alpha", "Artificial viscosity coefficient, Eq. 24", "", fl->alpha, &fl->alpha, NULL));
  PetscCall(OptReal("-wall_av", "Artificial viscosity against walls and solids, as a factor of -wcsph_alpha: with the walls at rest it acts as a friction that slows a thin front running along a floor (the dam break's front reaches the far wall late); 0 = none, the walls hold the fluid by pressure and Eq. 16 alone", "", fl->wall_av, &fl->wall_av, NULL));
  PetscCall(OptReal("-delta", "Density diffusion coefficient (delta-SPH); 0 = off", "", fl->delta, &fl->delta, NULL));
  PetscCall(OptReal("-riemann", "Dissipation of the acoustic Riemann solver between approaching pairs, with Zhang, Hu & Adams 2017's limiter beta = min(eta du / c0, 1): the coefficient eta (they take 3); against walls and solids along the fluid particle's wall normal, at twice its approach speed (the wall mirrors it).  Used instead of -wcsph_alpha it dissipates only where pairs approach fast; 0 = off", "", fl->riemann, &fl->riemann, NULL));
  PetscCall(OptReal("-damper", "Acoustic damper: the pressure of Eq. 20 plus damper rho0 c0 h (drho/dt) / rho, a bulk viscosity rho0 c0 h times the coefficient, as the pressure of the density a time damper h / c0 ahead; it damps the sound waves a few h long that ring after an impact and leaves shear and incompressible motion alone (docs/impact.md); 0 = off", "", fl->damper, &fl->damper, NULL));
  PetscCall(OptReal("-shift", "Particle shifting coefficient A (D = A h |v| dt, Skillen et al. 2013; none on the free surface, div r < 1.5, and next to it); 0 = off", "", fl->shift, &fl->shift, NULL));
  PetscCall(OptBool("-shift_volume", "With shifting: the continuity equation follows the shifted particle, its density changing with the divergence of the shifting velocity as with the flow's, so that the density stays that of the particles' spacing (without it Fickian shifting spreads a disordered flow's particles while their densities stay: behind the Turek-Hron cylinder 4.5 % fewer particles than the density says, docs/turek_hron.md)", "", fl->shift_volume, &fl->shift_volume, NULL));
  PetscCall(OptBool("-tic", "Tensile instability control (Sun et al. 2017's delta+-SPH): a fluid particle whose pressure is negative takes the pressure difference p_b - p_a from its fluid neighbours instead of Eq. 19's sum, which pulls particles in tension together; the level of the pressure then no longer acts on it.  Confined flows only (no free surface)", "", fl->tic, &fl->tic, NULL));
  PetscCall(OptBool("-wall_clip", "Clip the wall pressure (Adami extrapolation) at 0: fluid in tension next to a wall is not held on it", "", fl->wall_clip, &fl->wall_clip, NULL));
  PetscCall(OptReal("-skin", "Verlet skin of the neighbour list, in particle spacings: the pairs within 2h + skin are kept and the list is rebuilt only once some particle has moved half the skin; 0 rebuilds at every step", "", skin, &skin, NULL));
  PetscOptionsEnd();
  PetscCheck(fl->alpha >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_alpha %g must be >= 0", (double)fl->alpha);
  PetscCheck(fl->wall_av >= 0 && fl->wall_av <= 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_wall_av %g must be in [0, 1] (a factor of -wcsph_alpha)", (double)fl->wall_av);
  PetscCheck(fl->riemann >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_riemann %g must be >= 0 (Zhang et al.'s limiter is 3; 0 = off)", (double)fl->riemann);
  PetscCheck(fl->damper >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_damper %g must be >= 0 (0 = off)", (double)fl->damper);
  PetscCheck(fl->delta >= 0 && fl->delta <= 1, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_delta %g must be in [0, 1]", (double)fl->delta);
  PetscCheck(fl->shift >= 0, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_shift %g must be >= 0", (double)fl->shift);
  PetscCheck(skin >= 0 && skin <= 2, ph->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wcsph_skin %g must be in [0, 2] particle spacings", (double)skin);
  ph->nb->skin = skin * ph->dx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WCSPHSetUp(Physics *ph)
{
  FluidMaterial *fl = &ph->fl;
  PetscFunctionBeginUser;
  if (ph->nb->skin > 0) PetscCall(ParticlesEnableField(ph->P, FIELD_XREB, PETSC_FALSE)); /* the positions at the last rebuild */
  /* the solids' sub-steps move them after the list's pairs are computed, and their own list is made
   * then (SolidPrepare): a restart needs those positions too */
  if (ph->nb->skin > 0 && ph->has_solid) PetscCall(ParticlesEnableField(ph->P, FIELD_XLIST, PETSC_FALSE));
  fl->lat_divr = KernelLatticeSum(&ph->kernel, LATTICE_DIVR, 0);
  PetscCall(ParticlesEnableField(ph->P, FIELD_ACC, PETSC_FALSE));
  PetscCall(ParticlesEnableField(ph->P, FIELD_DRHO, (PetscBool)(fl->damper > 0))); /* ghosts: WCSPHPressure's damper */
  PetscCall(ParticlesEnableField(ph->P, FIELD_VWALL, PETSC_FALSE)); /* ghosts: refreshed by BoundaryWallState */
  if (fl->xsph > 0 || fl->shift > 0) PetscCall(ParticlesEnableField(ph->P, FIELD_XSPH, PETSC_FALSE)); /* ghosts: refreshed by ShiftVolume, where it reads them */
  /* the control has no free-surface region: a surface particle in tension would take p_b - p_a and the surface tear */
  PetscCheck(!fl->tic || ph->confined, ph->comm, PETSC_ERR_ARG_INCOMP, "-wcsph_tic is for confined flows (no free surface): this scene has one, where it tears the surface apart; leave it off");
  if (fl->shift > 0 && !ph->confined) PetscCall(ParticlesEnableField(ph->P, FIELD_FS, PETSC_TRUE)); /* ghosts: at the rebuild */
  if (fl->riemann > 0) PetscCall(ParticlesEnableField(ph->P, FIELD_QWALL, PETSC_FALSE)); /* ghosts: by WallRiemann, where solids read them */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WCSPHView(Physics *ph, PetscViewer v)
{
  const FluidMaterial *fl = &ph->fl;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "WCSPH: c0 %g m/s, AV alpha %g (x %g against walls), Riemann dissipation eta %g, acoustic damper %g, delta-SPH %g, XSPH %g, shifting A = %g%s, wall pressure %s, neighbour skin %g dx\n", (double)fl->c0, (double)fl->alpha, (double)fl->wall_av, (double)fl->riemann, (double)fl->damper, (double)fl->delta, (double)fl->xsph, (double)fl->shift, fl->shift > 0 && fl->shift_volume ? " (its volume in the continuity equation)" : "", fl->wall_clip ? "clipped at 0" : "as extrapolated (may be < 0)", (double)(ph->nb->skin / ph->dx)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Eq. 20, with -wcsph_damper the acoustic damper's bulk viscous part from the last step's density
 * rate (the ghosts' from their owners). */
PetscErrorCode WCSPHPressure(Physics *ph)
{
  Particles        P = ph->P;
  PetscReal       *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P);
  const PetscReal *drho = PField(P, FIELD_DRHO), *h = PField(P, FIELD_H), zeta = ph->fl.damper * ph->fl.rho0 * ph->fl.c0;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n + P->ng; a++)
    if (KindIsFluid(P->kind[a])) p[a] = EOSPressure(&ph->fl, rho[a]) + (zeta > 0 ? zeta * h[a] * drho[a] / rho[a] : 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the continuity loop gathers over the pairs of fluid particle a (ContinuityD). */
typedef struct {
  Particles        P;
  const PetscReal *x, *v, *rho, *m, *h, *g, *fs;
  PetscReal        dcoef, dhyd;                  /* delta-SPH: delta c0, rho0 / c0^2 */
  PetscBool        shift, surf, grad, xsph;      /* shifting; its free-surface flags; its velocity correction; XSPH */
  PetscReal        ra;                           /* rho_a */
  PetscReal        dr, dd, divr, sxs[3], c[3];   /* div v, the diffusion, div r, XSPH, grad C */
  PetscBool        near;                         /* a fluid neighbour on the free surface */
  ShiftGrad        sg;
} ContinuitySum;

/* Eq. 18's pair, delta-SPH's, XSPH's (Eq. 44) and shifting's (shifting.h) */
SPH_INLINE void ContinuityPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  ContinuitySum *s = (ContinuitySum *)ctx;
  PetscInt       b = p.b;
  PetscReal      d[3], dvab[3], F = p.F, vb = s->m[b] / s->rho[b];
  VSub(s->x + D * a, s->x + D * b, d, D);
  VSub(s->v + D * a, s->v + D * b, dvab, D);
  s->dr += vb * F * VDot(dvab, d, D);
  if (s->shift) {
    for (PetscInt i = 0; i < D; i++) s->c[i] += vb * F * d[i];
    s->divr -= vb * F * VDot(d, d, D);
  }
  if (!KindIsFluid(s->P->kind[b])) return;
  if (s->grad) ShiftGradAdd(&s->sg, vb, F, d, dvab, D);
  if (s->surf && s->fs[b] > 0) s->near = PETSC_TRUE;
  if (s->dcoef > 0) {
    PetscReal gd = -s->g[0] * d[0] - s->g[1] * d[1], dh;
    if (D == 3) gd -= s->g[2] * d[2];
    dh = s->dhyd * gd; /* rho_b^H - rho_a^H */
    s->dd += PairH(s->h[a], s->h[b]) * vb * (-2.0 * F) * (s->rho[b] - s->ra - dh);
  }
  if (s->xsph) {
    PetscReal w = XSPHWeight(p.W, s->m[b], s->ra, s->rho[b]);
    for (PetscInt i = 0; i < D; i++) s->sxs[i] -= w * dvab[i];
  }
}

/* drho/dt of owned fluid: continuity Eq. 18, optional delta-SPH diffusion (Molteni & Colagrossi
 * 2009, hydrostatic part removed); and the XSPH velocity correction Eq. 44 plus the shifting
 * velocity (shifting.h) over the coming step ph->dt.  With shifting, the free-surface flags (div r)
 * of the neighbours are those of the last call, which the rebuild gave the ghosts; the new flags
 * are written after the loop, so the result does not depend on the order of the particles.  A
 * confined flow has no free surface: a void that opens in it (div r < 1.5 of 2) is shifted shut. */
SPH_INLINE PetscErrorCode ContinuityD(Physics *ph, const PetscInt D)
{
  Particles            P = ph->P;
  Cells                C = ph->cells;
  const PetscReal     *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *rho = PField(P, FIELD_RHO);
  const PetscReal     *m = PField(P, FIELD_M), *h = PField(P, FIELD_H), *g = ph->g;
  PetscReal           *drho = PField(P, FIELD_DRHO), *xs = PField(P, FIELD_XSPH), *fs = PField(P, FIELD_FS);
  PetscBool           *surface = NULL;
  PetscReal           *dv = NULL; /* velocity corrections of shifted particles, applied after the loop (2D) */
  const FluidMaterial *fl   = &ph->fl;
  const PetscReal      dcoef = fl->delta * fl->c0, dhyd = fl->rho0 / (fl->c0 * fl->c0);
  const PetscBool      shift = (PetscBool)(fl->shift > 0), surf = (PetscBool)(shift && fs);

  PetscFunctionBeginUser;
  if (surf) PetscCall(PetscCalloc1(P->n, &surface));
  if (shift && fl->shift_correct) PetscCall(PetscCalloc1(D * P->n, &dv));
  for (PetscInt a = 0; a < P->n; a++) {
    ContinuitySum s = {.P = P, .x = x, .v = v, .rho = rho, .m = m, .h = h, .g = g, .fs = fs, .dcoef = dcoef, .dhyd = dhyd, .shift = shift, .surf = surf, .grad = (PetscBool)!!dv, .xsph = (PetscBool)!!xs, .ra = rho[a]};
    if (!KindIsFluid(P->kind[a])) continue;
    SPHPairsW(C, P, a, s.xsph, ContinuityPair, &s, D);
    drho[a] = s.ra * s.dr + dcoef * s.dd;
    if (xs)
      for (PetscInt i = 0; i < D; i++) xs[D * a + i] = fl->xsph * s.sxs[i];
    if (surf) surface[a] = (PetscBool)(2.0 * s.divr / fl->lat_divr < SHIFT_DIVR_SURFACE);
    if (shift) {
      PetscReal s0[3], dr[3];
      for (PetscInt i = 0; i < D; i++) s0[i] = xs[D * a + i];
      ShiftVelocity(fl->shift, fl->shift_dmax, fl->shift_vmin, surf && surface[a] ? SHIFT_SURFACE : s.near ? SHIFT_NEAR_SURFACE : SHIFT_BULK, h[a], v + D * a, ph->dt, s.c, xs + D * a, D);
      for (PetscInt i = 0; i < D; i++) dr[i] = ph->dt * (xs[D * a + i] - s0[i]);
      if (dv) ShiftCorrectVelocity(&s.sg, dr, dv + D * a, D);
    }
  }
  if (dv) {
    PetscReal *vw = PField(P, FIELD_V);
    for (PetscInt k = 0; k < D * P->n; k++) vw[k] += dv[k];
    PetscCall(PetscFree(dv));
  }
  if (surf) {
    for (PetscInt a = 0; a < P->n; a++) fs[a] = surface[a] ? 1.0 : 0.0;
    PetscCall(PetscFree(surface));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Continuity(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, ContinuityD, ph); }

/* What the wall pass gathers over the walls and solids next to fluid particle a (WallRiemannD). */
typedef struct {
  Particles        P;
  const PetscReal *x, *v, *m, *rho;
  PetscReal        g[3], w, vw[3]; /* sum V_b grad_a W_ab; the weights -V_b F_ab and the velocities they weigh */
} WallApproachSum;

SPH_INLINE void WallApproachPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  WallApproachSum *s = (WallApproachSum *)ctx;
  PetscInt         b = pr.b;
  PetscReal        vb;
  if (!KindIsBoundary(s->P->kind[b])) return;
  vb = s->m[b] / s->rho[b];
  for (PetscInt i = 0; i < D; i++) s->g[i] += vb * pr.F * (s->x[D * a + i] - s->x[D * b + i]);
  s->w -= vb * pr.F;
  for (PetscInt i = 0; i < D; i++) s->vw[i] -= vb * pr.F * s->v[D * b + i];
}

/* The Riemann dissipation of fluid particle a against the walls and solids it touches, per unit
 * density (fluid_terms.h), into FIELD_QWALL.  The wall is the mirror of the fluid (Adami et al.
 * 2012): the jump is twice a's approach speed along the wall's normal, here the direction of
 * sum_b V_b grad_a W_ab over a's boundary neighbours, relative to their mean velocity.  A particle
 * sliding along a wall has no jump; along the pairs' own lines, each wall particle ahead of it
 * would be approached and the dissipation would act as a friction (as Eq. 24 does against walls). */
SPH_INLINE PetscErrorCode WallRiemannD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscReal       *q       = PField(P, FIELD_QWALL);
  const FieldId    field[] = {FIELD_QWALL};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    WallApproachSum s = {.P = P, .x = x, .v = v, .m = m, .rho = rho};
    PetscReal       gn, du = 0;
    q[a] = 0;
    if (!KindIsFluid(P->kind[a])) continue;
    SPHPairs(ph->cells, a, WallApproachPair, &s, D);
    gn = PetscSqrtReal(VDot(s.g, s.g, D));
    if (!(gn > 0 && s.w > 0)) continue;
    for (PetscInt i = 0; i < D; i++) du += 2.0 * (v[D * a + i] - s.vw[i] / s.w) * s.g[i] / gn; /* g points at the wall */
    q[a] = RiemannDissipation(ph->fl.riemann, ph->fl.c0, 1.0, du);
  }
  /* the momentum loop and the bodies' forces read owned particles' values; a solid's load also its
   * fluid ghosts' (boundary_load.h) */
  if (ph->has_solid) PetscCall(HaloRefresh(ph->halo, P, 1, field));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode WallRiemann(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, WallRiemannD, ph); }

/* What the momentum pair reads of fluid particle a and its neighbours (MomentumD). */
typedef struct {
  const PetscInt      *kind;
  const PetscReal     *x, *v, *h, *nrm;
  const PetscReal     *mv, *rv, *pv, *vv; /* m, rho, p / rho^2 and the velocity of Eq. 16 of each particle as the fluid sees it (FluidView; walls' and solids' VWALL) */
  const FluidMaterial *fl;
  PetscReal            ra, pa, ha, qa;  /* rho_a, p_a / rho_a^2, h_a, a's Riemann dissipation against walls (WallRiemannD) */
  PetscReal            repulsion_scale, dt;
  PetscBool            repulse, riemann, tic; /* Eq. 41 (nrm), the Riemann dissipation, the tensile instability control: constants of MomentumLoop's plain variant */
} MomentumPairs;

/* Eq. 19 with Eq. 24 and the Riemann dissipation (fluid_terms.h; against walls WallRiemannD's), Eq. 16 and Eq. 41's pair */
SPH_INLINE void MomentumPair(const void *ctx, PetscInt a, SPHPair pr, PetscReal *out, const PetscInt D)
{
  const MomentumPairs *s  = (const MomentumPairs *)ctx;
  const FluidMaterial *fl = s->fl;
  const PetscReal     *va = s->v + D * a, *vb = s->v + D * pr.b;
  PetscInt             b = pr.b, kind = s->kind[b];
  PetscBool            wall = KindIsBoundary(kind);
  PetscReal            d[3], dvab[3], r2, F = pr.F;
  PetscReal            hab = PairH(s->ha, s->h[b]), mb = s->mv[b], rb = s->rv[b], pterm, visc, rep = 0;
  VSub(s->x + D * a, s->x + D * b, d, D);
  VSub(va, vb, dvab, D);
  r2    = VDot(d, d, D);
  pterm = (s->tic && s->pa < 0 && KindIsFluid(kind) ? s->pv[b] * rb / s->ra - s->pa * s->ra / rb : s->pa + s->pv[b]) + ArtificialViscosity(KindIsFluid(kind) ? fl->alpha : fl->alpha * fl->wall_av, fl->c0, hab, 0.5 * (s->ra + rb), VDot(dvab, d, D), r2);
  visc  = LaminarViscosity(mb, fl->mu, s->ra, rb, F * r2, r2, hab, fl->eta, fl->lap_kappa);
  if (s->repulse && KindIsSolid(kind)) rep = s->repulsion_scale * FSIRepulsion(VDot(dvab, s->nrm + D * b, D), PetscSqrtReal(r2) / (2 * hab), s->dt); /* scale: to the paper's 2D sum at 1.3 dx (solid.c) */
  VSub(va, s->vv + D * b, dvab, D); /* against walls and solids their no-slip (mirrored) velocity */
  if (s->riemann) {
    if (wall) pterm += s->qa * (s->ra + rb) / (s->ra * rb); /* 2 P* / (rho_a rho_b), WallRiemannD */
    else if (r2 > 0) pterm += 2.0 * RiemannDissipation(fl->riemann, fl->c0, 0.5 * (s->ra + rb), -VDot(dvab, d, D) / PetscSqrtReal(r2)) / (s->ra * rb);
  }
  for (PetscInt i = 0; i < D; i++) out[i] = visc * dvab[i] - mb * pterm * F * d[i];
  if (rep != 0)
    for (PetscInt i = 0; i < D; i++) out[i] += rep * s->nrm[D * b + i];
}

/* The loop over the owned fluid (MomentumD), with repulse and riemann constants where the caller
 * gives them, so that the pair has no branch for what is off and its loop vectorises. */
SPH_INLINE void MomentumLoop(Physics *ph, const PetscReal *mv, const PetscReal *rv, const PetscReal *pv, const PetscReal *vv, PetscReal *scratch, PetscBool repulse, PetscBool riemann, PetscBool tic, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *rho = PField(P, FIELD_RHO), *h = PField(P, FIELD_H);
  const PetscReal *qw  = riemann ? PField(P, FIELD_QWALL) : NULL;
  PetscReal       *acc = PField(P, FIELD_ACC);
  for (PetscInt a = 0; a < P->n; a++) {
    MomentumPairs s = {.kind = P->kind, .x = PField(P, FIELD_X), .v = PField(P, FIELD_V), .h = h, .nrm = repulse ? PField(P, FIELD_NORMAL) : NULL, .mv = mv, .rv = rv, .pv = pv, .vv = vv, .fl = &ph->fl, .ra = rho[a], .pa = pv[a], .ha = h[a], .qa = qw ? qw[a] : 0, .repulsion_scale = repulse ? ph->solid->repulsion_scale : 0, .dt = ph->dt, .repulse = repulse, .riemann = riemann, .tic = tic};
    PetscReal     ac[3] = {0, 0, 0};
    if (!KindIsFluid(P->kind[a])) continue;
    SPHPairsSum(ph->cells, a, MomentumPair, &s, D, scratch, ac, D);
    for (PetscInt i = 0; i < D; i++) acc[D * a + i] = ac[i] + ph->g[i];
  }
}

/* Acceleration of owned fluid: pressure Eq. 19 with artificial viscosity Eq. 24, laminar viscosity
 * Eq. 16 (walls and solids with their no-slip velocity), gravity; solids as the fluid sees them
 * (boundary.h) and, when on, the repulsive force Eq. 41 along their normals. */
SPH_INLINE PetscErrorCode MomentumD(Physics *ph, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), *p = PField(P, FIELD_P), *fv = PField(P, FIELD_FVIEW);
  const PetscBool  repulse = (PetscBool)(ph->solid && ph->solid->repulsion), riemann = (PetscBool)(ph->fl.riemann > 0), tic = ph->fl.tic;
  const PetscReal *v = PField(P, FIELD_V), *vw = PField(P, FIELD_VWALL);
  PetscReal       *mv, *rv, *pv, *vv, *scratch;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc5(P->n + P->ng, &mv, P->n + P->ng, &rv, P->n + P->ng, &pv, D * (P->n + P->ng), &vv, D * PetscMax(ph->cells->max_nbr, 1), &scratch));
  for (PetscInt b = 0; b < P->n + P->ng; b++) {
    FluidView(fv, P->kind[b], b, m, rho, p, &mv[b], &rv[b], &pv[b]);
    pv[b] /= rv[b] * rv[b];
    for (PetscInt i = 0; i < D; i++) vv[D * b + i] = KindIsBoundary(P->kind[b]) ? vw[D * b + i] : v[D * b + i];
  }
  if (!repulse && !riemann && !tic) MomentumLoop(ph, mv, rv, pv, vv, scratch, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, D);
  else MomentumLoop(ph, mv, rv, pv, vv, scratch, repulse, riemann, tic, D);
  PetscCall(PetscFree5(mv, rv, pv, vv, scratch));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Momentum(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, MomentumD, ph); }

/* Pressure of fluid (EOS) and walls, then accelerations: the state after a rebuild. */
PetscErrorCode WCSPHRates(Physics *ph)
{
  PetscFunctionBeginUser;
  if (ph->open) PetscCall(OpenState(ph)); /* the buffers' densities */
  PetscCall(WCSPHPressure(ph));
  PetscCall(BoundaryWallState(ph));
  if (ph->fl.riemann > 0) PetscCall(WallRiemann(ph));
  PetscCall(Momentum(ph));
  if (ph->open) PetscCall(OpenRates(ph)); /* buffer particles move as their boundary says */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WCSPHTimeStep(Physics *ph, PetscReal *dt)
{
  Particles        P = ph->P;
  const PetscReal *v = PField(P, FIELD_V), *acc = PField(P, FIELD_ACC), *h = PField(P, FIELD_H), *rho = PField(P, FIELD_RHO);
  PetscReal        lim = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    lim = PetscMin(lim, AcousticStepLimit(ph->cfl, h[a], ph->fl.c0, v + P->dim * a, acc + P->dim * a, P->dim)); /* CFL, force */
    if (ph->fl.mu > 0) lim = PetscMin(lim, 0.125 * h[a] * h[a] * rho[a] / ph->fl.mu); /* viscous */
  }
  PetscCall(MPIU_Allreduce(&lim, dt, 1, MPIU_REAL, MPIU_MIN, ph->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void KickVelocity(Physics *ph, PetscReal dt)
{
  Particles  P = ph->P;
  PetscReal *v = PField(P, FIELD_V), *acc = PField(P, FIELD_ACC);
  PetscInt   D = P->dim;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    for (PetscInt i = 0; i < D; i++) v[D * a + i] += dt * acc[D * a + i];
  }
}

/* What the shifting's volume pass gathers over the pairs of fluid particle a (ShiftVolumeD). */
typedef struct {
  Particles        P;
  const PetscReal *x, *xs, *m, *rho;
  PetscReal        div; /* -div(dr / dt), the shift's share of Eq. 18 over rho_a */
} ShiftVolumeSum;

/* Eq. 18's pair with the shifting velocities dr / dt in place of v (walls and solids do not shift) */
SPH_INLINE void ShiftVolumePair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  ShiftVolumeSum *s = (ShiftVolumeSum *)ctx;
  PetscInt        b = p.b;
  PetscReal       d[3], dsab[3];
  VSub(s->x + D * a, s->x + D * b, d, D);
  for (PetscInt i = 0; i < D; i++) dsab[i] = s->xs[D * a + i] - (KindIsFluid(s->P->kind[b]) ? s->xs[D * b + i] : 0);
  s->div += s->m[b] / s->rho[b] * p.F * VDot(dsab, d, D);
}

/* -wcsph_shift_volume: a shifted particle moves with v + dr/dt, so its density changes by
 * -rho div(dr/dt) as well (the continuity equation along its path, as the ALE form of delta+-SPH
 * takes it); after the buffers' shifts are cleared (OpenNoShift), with the ghosts' shifts. */
SPH_INLINE PetscErrorCode ShiftVolumeD(Physics *ph, const PetscInt D)
{
  Particles        P    = ph->P;
  const FieldId    xf[] = {FIELD_XSPH};
  const PetscReal *x = PField(P, FIELD_X), *xs = PField(P, FIELD_XSPH), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscReal       *drho = PField(P, FIELD_DRHO);
  PetscFunctionBeginUser;
  PetscCall(HaloRefresh(ph->halo, P, 1, xf));
  for (PetscInt a = 0; a < P->n; a++) {
    ShiftVolumeSum s = {.P = P, .x = x, .xs = xs, .m = m, .rho = rho};
    if (!KindIsFluid(P->kind[a])) continue;
    SPHPairs(ph->cells, a, ShiftVolumePair, &s, D);
    drho[a] += rho[a] * s.div;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ShiftVolume(Physics *ph) { return SPH_DIM_DISPATCH(ph->dim, ShiftVolumeD, ph); }

/* Velocity Verlet with density as a position-like variable (symplectic for the acoustic pair):
 * v+ = v + dt/2 a;  rho' = rho + dt drho(x, v+);  x' = x + dt (v+ + xsph);  a' = a(x', rho');
 * v' = v+ + dt/2 a'. */
PetscErrorCode WCSPHStep(Physics *ph)
{
  Particles     P  = ph->P;
  const PetscReal dt = ph->dt;
  const FieldId vel[] = {FIELD_V};

  PetscFunctionBeginUser;
  KickVelocity(ph, 0.5 * dt);
  if (ph->open) PetscCall(OpenImpose(ph, ph->t + 0.5 * dt)); /* the inlets' velocities over the drift */
  PetscCall(HaloRefresh(ph->halo, P, 1, vel));
  PetscCall(Continuity(ph));
  if (ph->open) PetscCall(OpenNoShift(ph));
  if (ph->fl.shift > 0 && ph->fl.shift_volume) PetscCall(ShiftVolume(ph));
  {
    PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *xs = PField(P, FIELD_XSPH), *rho = PField(P, FIELD_RHO), *drho = PField(P, FIELD_DRHO);
    PetscInt   D = P->dim;
    for (PetscInt a = 0; a < P->n; a++) {
      if (!KindIsFluid(P->kind[a])) continue;
      rho[a] += dt * drho[a];
      for (PetscInt i = 0; i < D; i++) x[D * a + i] += dt * (v[D * a + i] + (xs ? xs[D * a + i] : 0));
    }
  }
  if (ph->open) PetscCall(OpenAfterDrift(ph)); /* crossings of the open boundaries' planes */
  PetscCall(NeighbourhoodUpdate(ph->nb, ph->step));
  PetscCall(WCSPHRates(ph));
  KickVelocity(ph, 0.5 * dt);
  if (ph->open) PetscCall(OpenImpose(ph, ph->t + dt));
  PetscFunctionReturn(PETSC_SUCCESS);
}
