/* A free square block of the hypo-elastic solid, no gravity, for checks of the solid model:
 *   translate  uniform velocity U: no strain rate, so no stress at all;
 *   rotate     rigid rotation at omega, prescribed (the scene sets the velocity every step), of a
 *              block pre-stressed with S_xx = -S_yy = s0: the Jaumann rate (Eq. 40) must carry the
 *              stress round with the body, S(t) = Q S0 Q^T, Q the rotation by omega t;
 *   stretch    initial velocity u = rate (x - xc) (free, so it breathes in tension and
 *              compression): the tensile instability clumps particles unless the artificial stress
 *              (Eqs. 25-34) is on; d_min shows it.
 * Probes: s_err (rotate: max |S - Q S0 Q^T| / s0; otherwise max |S| / s0), d_min (smallest
 * distance between two solid particles / dx), e_kin, e_strain. */
#include <sphfsi.h>

typedef enum { BLOCK_TRANSLATE = 0, BLOCK_ROTATE, BLOCK_STRETCH } BlockMotion;
static const char *const BlockMotions[] = {"translate", "rotate", "stretch", "BlockMotion", "BLOCK_", NULL};

typedef struct {
  BlockMotion motion;
  PetscInt    n;
  PetscReal   size, rate, s0, jitter, c[2];
  PetscReal   s_err_max, d_min_min;
} Block;

static PetscErrorCode Create(Sim sim)
{
  Block   *c;
  PetscInt motion = BLOCK_ROTATE;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  PetscCall(SceneKeepReal(sim, &c->s_err_max));
  PetscCall(SceneKeepReal(sim, &c->d_min_min));
  c->n = 20; c->size = 0.02; c->rate = -1; c->s0 = 1e4; c->jitter = 0;
  SimSolidMaterial(sim)->rho0 = 1000; SimSolidMaterial(sim)->K = 3.25e6; SimSolidMaterial(sim)->G = 7.15e5;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene solid_block: free elastic block (objectivity and tensile-instability checks)", "");
  PetscCall(OptEList("-block_motion", "Motion of the block", "", BlockMotions, 3, BlockMotions[motion], &motion, NULL));
  PetscCall(OptReal("-block_size", "Side of the square block (m)", "", c->size, &c->size, NULL));
  PetscCall(OptInt("-block_n", "Particles along a side (dx = size / n unless -dx is given)", "", c->n, &c->n, NULL));
  PetscCall(OptReal("-block_rate", "U (m/s) for translate, omega (rad/s) for rotate, strain rate (1/s) for stretch; default 1, 10, 10", "", c->rate, &c->rate, NULL));
  PetscCall(OptReal("-block_s0", "Initial deviatoric stress S_xx = -S_yy (Pa) of the rotating block", "", c->s0, &c->s0, NULL));
  PetscCall(OptReal("-block_jitter", "Random displacement of the initial lattice, as a fraction of dx (fixed seed per particle id)", "", c->jitter, &c->jitter, NULL));
  PetscOptionsEnd();
  c->motion = (BlockMotion)motion;
  if (c->rate < 0) c->rate = c->motion == BLOCK_TRANSLATE ? 1.0 : 10.0;
  PetscCheck(c->size > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-block_size %g must be > 0", (double)c->size);
  PetscCheck(c->jitter >= 0 && c->jitter < 0.3, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-block_jitter %g must be in [0, 0.3)", (double)c->jitter);
  PetscCheck(c->s0 > 0, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "-block_s0 %g must be > 0", (double)c->s0);
  if (SimSpacing(sim) > 0) c->n = RoundToInt(c->size / SimSpacing(sim));
  PetscCheck(c->n >= 4, SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The block needs >= 4 particles along a side (-block_n or -dx)");
  PetscCall(SimSetSpacing(sim, c->size / c->n));
  PetscCall(SimSetMedia(sim, PETSC_FALSE, PETSC_TRUE));
  PetscCall(SimSetGravity(sim, 0, 0, SimGravity(sim)[2]));
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, c->motion == BLOCK_ROTATE ? 0.5 * PETSC_PI / c->rate : 0.05));
  c->c[0] = c->c[1] = 0.5 * c->size;
  {
    PetscReal reach = 2 * c->size + (c->motion == BLOCK_TRANSLATE ? c->rate * SimEndTime(sim) : 0);
    PetscCall(SimSetDomain(sim, 0, -reach, c->size + reach));
    PetscCall(SimSetDomain(sim, 1, -reach, c->size + reach));
  }
  c->d_min_min = PETSC_MAX_REAL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a reproducible number in [-1, 1) from an id and a salt (same on any number of ranks) */
static PetscReal Hash(PetscInt id, PetscInt salt)
{
  unsigned long long z = (unsigned long long)id * 0x9E3779B97F4A7C15ULL + (unsigned long long)salt * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return 2.0 * (PetscReal)(z >> 11) / 9007199254740992.0 - 1.0;
}

static void RigidVelocity(const Block *c, const PetscReal *x, PetscReal *v)
{
  v[0] = -c->rate * (x[1] - c->c[1]);
  v[1] = c->rate * (x[0] - c->c[0]);
}

static PetscErrorCode Populate(Sim sim)
{
  Block     *c = (Block *)SimSceneContext(sim);
  PetscReal      *x, *v, *S;
  const PetscInt *id;
  PetscInt        n;
  PetscFunctionBeginUser;
  PetscCall(SceneAddLattice(sim, KIND_SOLID, 0.5 * SimSpacing(sim), 0.5 * SimSpacing(sim), c->n, c->n, SimSpacing(sim), SimSolidMaterial(sim)->rho0));
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "id", NULL, &id));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  PetscCall(SimGetField(sim, "stress", NULL, &S));
  for (PetscInt a = 0; a < n; a++) {
    x[2 * a] += c->jitter * SimSpacing(sim) * Hash(id[a], 1);
    x[2 * a + 1] += c->jitter * SimSpacing(sim) * Hash(id[a], 2);
    switch (c->motion) {
    case BLOCK_TRANSLATE: v[2 * a] = c->rate; v[2 * a + 1] = 0.5 * c->rate; break;
    case BLOCK_ROTATE:
      RigidVelocity(c, x + 2 * a, v + 2 * a);
      S[3 * a] = c->s0; S[3 * a + 2] = -c->s0;
      break;
    case BLOCK_STRETCH: v[2 * a] = c->rate * (x[2 * a] - c->c[0]); break;
    }
  }
  PetscCall(SimRestoreField(sim, "id", NULL, &id));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscCall(SimRestoreField(sim, "stress", NULL, &S));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* rotate: the velocity of the rigid rotation about the block's (fixed) centre */
static PetscErrorCode Prescribe(Sim sim)
{
  Block     *c = (Block *)SimSceneContext(sim);
  const PetscReal *x;
  PetscReal       *v;
  const PetscInt  *kind;
  PetscInt         n;
  PetscFunctionBeginUser;
  if (c->motion != BLOCK_ROTATE) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "v", NULL, &v));
  for (PetscInt a = 0; a < n; a++)
    if (kind[a] == KIND_SOLID) RigidVelocity(c, x + 2 * a, v + 2 * a);
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "v", NULL, &v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The smallest squared distance from owned solid a to a solid neighbour (the scene is 2D) */
typedef struct {
  const PetscInt  *kind;
  const PetscReal *x;
  PetscReal        d2;
} NearestSum;

static void NearestPair(void *ctx, PetscInt a, PetscInt b)
{
  NearestSum *s  = (NearestSum *)ctx;
  PetscReal   dx = s->x[2 * a] - s->x[2 * b], dy = s->x[2 * a + 1] - s->x[2 * b + 1];
  if (KindIsSolid(s->kind[b])) s->d2 = PetscMin(s->d2, dx * dx + dy * dy);
}

static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  Block     *c = (Block *)SimSceneContext(sim);
  const PetscReal *x, *S;
  const PetscInt  *kind;
  PetscReal        e = 0, d2 = PETSC_MAX_REAL;
  PetscInt         n;
  PetscReal        th = c->rate * SimTime(sim), q = PetscCosReal(2 * th), r = PetscSinReal(2 * th);
  /* Q diag(s0, -s0) Q^T = s0 [[cos 2th, sin 2th], [sin 2th, -cos 2th]] */
  PetscReal  ref[3] = {c->s0 * q, c->s0 * r, -c->s0 * q};
  PetscFunctionBeginUser;
  if (c->motion != BLOCK_ROTATE) ref[0] = ref[1] = ref[2] = 0;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  PetscCall(SimGetField(sim, "stress", NULL, &S));
  for (PetscInt a = 0; a < n; a++) {
    if (kind[a] != KIND_SOLID) continue;
    for (PetscInt i = 0; i < 3; i++) e = PetscMax(e, PetscAbsReal(S[3 * a + i] - ref[i]));
    NearestSum ns = {.kind = kind, .x = x, .d2 = d2};
    PetscCall(SimForEachNeighbour(sim, a, NearestPair, &ns));
    d2 = ns.d2;
  }
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(SimRestoreField(sim, "stress", NULL, &S));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &e, 1, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &d2, 1, MPIU_REAL, MPIU_MIN, SimComm(sim)));
  vals[0] = e / c->s0;
  vals[1] = PetscSqrtReal(d2) / SimSpacing(sim);
  PetscCall(SimSolidEnergy(sim, &vals[2], &vals[3]));
  c->s_err_max = PetscMax(c->s_err_max, vals[0]);
  c->d_min_min = PetscMin(c->d_min_min, vals[1]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Errors(Sim sim, FILE *f)
{
  Block *c = (Block *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  if (f) fprintf(f, "\"motion\": \"%s\", \"s_err_max\": %.6g, \"d_min_min\": %.6g, \"rate\": %.6g, \"s0\": %.6g", BlockMotions[c->motion], (double)c->s_err_max, (double)c->d_min_min, (double)c->rate, (double)c->s0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  void *c = SimSceneContext(sim);
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneSolidBlock = {
  .name = "solid_block", .help = "free elastic block: objectivity of the Jaumann rate and the tensile instability",
  .create = Create, .populate = Populate, .prescribe = Prescribe,
  .nprobes = 4, .probe_names = {"s_err", "d_min", "e_kin", "e_strain"},
  .probe = Probe, .errors = Errors, .destroy = Destroy,
};
