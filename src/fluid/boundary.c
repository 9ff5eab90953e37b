#include "fluid/boundary.h"
#include "base/dim.h"
#include "particles/pair_loop.h"

/* What a wall gathers over its fluid neighbours: sum W, sum p W, sum rho r W, sum v W. */
typedef struct {
  Particles        P;
  const PetscReal *x, *v, *p, *rho;
  PetscReal        sw, sp, sg[3], sv[3];
} WallSum;

/* Adami et al. 2012's sums, one fluid neighbour's share */
SPH_INLINE void WallPair(void *ctx, PetscInt a, SPHPair pr, const PetscInt D)
{
  WallSum  *s = (WallSum *)ctx;
  PetscInt  b = pr.b;
  PetscReal d[3], w = pr.W;
  if (!KindIsFluid(s->P->kind[b])) return;
  VSub(s->x + D * a, s->x + D * b, d, D);
  s->sw += w;
  s->sp += s->p[b] * w;
  for (PetscInt i = 0; i < D; i++) s->sg[i] += s->rho[b] * d[i] * w;
  for (PetscInt i = 0; i < D; i++) s->sv[i] += s->v[D * b + i] * w;
}

/* Wall state from the fluid neighbours of each owned wall/dummy or solid particle: the no-slip
 * mirror velocity always, the Adami pressure and EOS density when `pressure` is set (WCSPH; with
 * ISPH the pressure equation gives it).  A solid's pressure goes to its fluid view.  Adami's
 * moving-wall term rho_f a_w . r is left out for solids: a particle's own acceleration carries the
 * solid's elastic waves (hundreds of g at the wetted surface when loaded), not the motion of the
 * interface. */
SPH_INLINE PetscErrorCode WallStateD(Physics *ph, PetscBool pressure, const PetscInt D)
{
  Particles        P = ph->P;
  const PetscReal *x = PField(P, FIELD_X), *v = PField(P, FIELD_V), *g = ph->g;
  PetscReal       *p = PField(P, FIELD_P), *rho = PField(P, FIELD_RHO), *vw = PField(P, FIELD_VWALL), *fv = PField(P, FIELD_FVIEW);
  const PetscReal *m = PField(P, FIELD_M);
  const FieldId    refresh[] = {FIELD_VWALL, FIELD_P, FIELD_RHO, FIELD_FVIEW};

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    PetscReal pg, sw;
    PetscBool solid = KindIsSolid(P->kind[a]);
    WallSum   s = {.P = P, .x = x, .v = v, .p = p, .rho = rho};
    if (!(KindIsWall(P->kind[a]) || (solid && fv))) continue;
    SPHPairsW(ph->cells, P, a, PETSC_TRUE, WallPair, &s, D);
    sw = s.sw;
    for (PetscInt i = 0; i < D; i++) vw[D * a + i] = sw > 0 ? 2.0 * v[D * a + i] - s.sv[i] / sw : v[D * a + i];
    pg = s.sp + g[0] * s.sg[0] + g[1] * s.sg[1]; /* sum p_f W + g . sum rho_f r_wf W */
    if (D == 3) pg += g[2] * s.sg[2];
    if (solid) {
      if (pressure) fv[3 * a] = sw > 0 ? PetscMax(pg / sw, 0.0) : 0;
      fv[3 * a + 1] = pressure ? EOSDensity(&ph->fl, fv[3 * a]) : ph->fl.rho0;
      fv[3 * a + 2] = fv[3 * a + 1] * m[a] / rho[a];
    } else if (pressure) {
      /* Adami et al. 2012, Eq. 27 (static wall): p_w = (sum p_f W + g . sum rho_f r_wf W) / sum W */
      p[a]   = sw > 0 ? pg / sw : 0;
      if (ph->fl.wall_clip) p[a] = PetscMax(p[a], 0.0); /* a wall pushes, never pulls: fluid in tension would stick to it */
      rho[a] = EOSDensity(&ph->fl, p[a]);
    }
  }
  if (fv) PetscCall(HaloRefresh(ph->halo, P, 1, refresh + 3));
  PetscCall(HaloRefresh(ph->halo, P, pressure ? 3 : 1, refresh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode WallState(Physics *ph, PetscBool pressure) { return SPH_DIM_DISPATCH(ph->dim, WallStateD, ph, pressure); }

PetscErrorCode BoundaryWallState(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(WallState(ph, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BoundaryWallVelocity(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(WallState(ph, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}
