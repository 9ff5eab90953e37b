/* Collapse of a water column of width a and height 2a (Martin & Moyce 1952) in a tank. */
#include "scenes/scene.h"
#include "base/options_used.h"
#include "base/refdata.h"

typedef struct {
  PetscReal a, H, L, top;
  PetscInt  rows;
  Series    front, height;
} DamBreak;

static PetscErrorCode Create(Sim sim)
{
  DamBreak *c;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  sim->scene_ctx = c;
  PetscCall(SceneKeepSeries(sim, &c->front));
  PetscCall(SceneKeepSeries(sim, &c->height));
  c->a = 0.05715; c->H = -1; c->L = -1; c->top = -1; c->rows = KernelSupportRows(&sim->phys.kernel);
  PetscOptionsBegin(sim->comm, NULL, "Scene dam_break: collapse of a water column", "");
  PetscCall(OptReal("-column_width", "Column width a (m)", "", c->a, &c->a, NULL));
  PetscCall(OptReal("-column_height", "Column height (m); default 2a", "", c->H, &c->H, NULL));
  PetscCall(OptReal("-tank_length", "Tank length from the wall behind the column (m); default 5.25a", "", c->L, &c->L, NULL));
  PetscCall(OptReal("-tank_height", "Tank wall height (m); default 3x the column height", "", c->top, &c->top, NULL));
  PetscCall(OptInt("-wall_rows", "Rows of wall + dummy particles", "", c->rows, &c->rows, NULL));
  PetscOptionsEnd();
  PetscCheck(c->a > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-column_width %g must be > 0", (double)c->a);
  if (c->H < 0) c->H = 2 * c->a;
  if (c->L < 0) c->L = 5.25 * c->a;
  if (c->top < 0) c->top = 3 * c->H;
  PetscCheck(c->H > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-column_height %g must be > 0", (double)c->H);
  PetscCheck(c->L > c->a, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-tank_length %g must exceed the column width %g", (double)c->L, (double)c->a);
  PetscCheck(c->top >= c->H, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-tank_height %g must be at least the column height %g", (double)c->top, (double)c->H);
  PetscCheck(c->rows >= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-wall_rows %" PetscInt_FMT " must be >= 1", c->rows);
  if (sim->phys.dx < 0) sim->phys.dx = c->a / 20;
  if (sim->t_end < 0) sim->t_end = 3.0 / PetscSqrtReal(2 * 9.81 / c->a); /* T = 3 */
  PetscCheck(sim->phys.dx <= 0.5 * c->a, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dx %g is larger than half the column width %g: choose a smaller -dx", (double)sim->phys.dx, (double)c->a);
  sim->phys.v_ref     = PetscSqrtReal(2 * 9.81 * c->H);
  /* open air above the walls, as high again: the run-up jet on the far wall rises past 3x the
   * column height by t = 0.29 s at a/80 (ISPH, 4 m/s at the tip) and falls back into the tank */
  SceneTankDomain(sim, c->L, 2 * c->top, c->rows);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  DamBreak *c = (DamBreak *)sim->scene_ctx;
  PetscFunctionBeginUser;
  PetscCall(SceneAddDamBreak(sim, c->a, c->H, c->L, c->top, c->rows));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* front_x: leading fluid particle + dx/2 (= a at t = 0).  height_left: the mean water depth within
 * w = a/10 of the wall behind the column (SceneStripShare), the bulk surface that Martin & Moyce
 * read off photographs.  The width is fixed whatever dx, so that an O(dx) defect at the wall (a gap,
 * a corner) is an O(dx) error; the highest particle near the wall scattered by ~1 mm at every
 * resolution (docs/convergence.md). */
static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  DamBreak        *c = (DamBreak *)sim->scene_ctx;
  Particles        P = sim->P;
  const PetscReal *x = PField(P, FIELD_X), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO), w = 0.1 * c->a;
  PetscReal        r[2] = {0, 0}; /* the front (max), the volume within w of the wall (sum) */
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++) {
    if (!KindIsFluid(P->kind[a])) continue;
    r[0] = PetscMax(r[0], x[2 * a]);
    r[1] += SceneFluidVolume(sim, m[a], rho[a]) * SceneStripShare(x[2 * a], w, sim->phys.dx);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &r[0], 1, MPIU_REAL, MPIU_MAX, sim->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &r[1], 1, MPIU_REAL, MPIU_SUM, sim->comm));
  vals[0] = r[0] + 0.5 * sim->phys.dx;
  vals[1] = r[1] / w;
  PetscCall(SeriesAppend(&c->front, sim->phys.t, vals[0]));
  PetscCall(SeriesAppend(&c->height, sim->phys.t, vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Surge front against Martin & Moyce (1952), n^2 = 2, a = 2.25 in: Z = x/a at T = t sqrt(2g/a),
 * at the points where their front was still inside this tank (Z < L/a: their tank was longer, and
 * a front held by the far wall is no error of the scheme); residual height at the wall against
 * their Table 6: h/H0 at tau = t sqrt(g/a). */
static PetscErrorCode Errors(Sim sim, FILE *f)
{
  DamBreak *c = (DamBreak *)sim->scene_ctx;
  Series    ref = {0};
  PetscBool found;
  PetscReal rms, max, g = -sim->phys.g[1], Tend = sim->phys.t * PetscSqrtReal(2 * g / c->a);
  PetscInt  n;
  PetscFunctionBeginUser;
  PetscCall(RefDataLoad(&sim->refdata, "martin_moyce1952_surge_n2eq2_a2.25in__pysph.csv", "T", "Z", &ref, &found));
  if (found && f) {
    SeriesKeepBelow(&ref, c->L / c->a);
    PetscCall(SeriesCompare(&c->front, &ref, 1.0 / PetscSqrtReal(2 * g / c->a), c->a, 0, Tend, PETSC_TRUE, &rms, &max, &n));
    fprintf(f, "\"front_rel_err_rms\": %.6g, \"front_rel_err_max\": %.6g, \"front_points\": %d, \"front_T_max\": %.4g, ", (double)rms, (double)max, (int)n, (double)Tend);
  }
  PetscCall(SeriesDestroy(&ref));
  PetscCall(RefDataLoad(&sim->refdata, "martin_moyce1952_height_n2eq2_a2.25in_table6__ocellaris.csv", "tau", "H_over_H0", &ref, &found));
  if (found && f) {
    PetscCall(SeriesCompare(&c->height, &ref, 1.0 / PetscSqrtReal(g / c->a), c->H, 0, sim->phys.t * PetscSqrtReal(g / c->a), PETSC_TRUE, &rms, &max, &n));
    fprintf(f, "\"height_rel_err_rms\": %.6g, \"height_rel_err_max\": %.6g, \"height_points\": %d, ", (double)rms, (double)max, (int)n);
  }
  PetscCall(SeriesDestroy(&ref));
  if (f) fprintf(f, "\"reference\": \"Martin & Moyce 1952\"");
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  DamBreak *c = (DamBreak *)sim->scene_ctx;
  PetscFunctionBeginUser;
  PetscCall(SeriesDestroy(&c->front));
  PetscCall(SeriesDestroy(&c->height));
  PetscCall(PetscFree(sim->scene_ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneDamBreak = {
  .name = "dam_break", .help = "collapse of a water column (Martin & Moyce 1952)",
  .create = Create, .populate = Populate,
  .nprobes = 2, .probe_names = {"front_x", "height_left"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
