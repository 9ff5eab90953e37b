/* The run as a scene sees it: the accessors of <sphfsi/scene.h> and <sphfsi/particles.h> over the
 * Sim struct, which no scene sees. */
#include "run/sim.h"
#include "particles/pair_loop.h"
#include "solid/solid.h"
#include "fluid/open_boundary.h"
#include "fluid/body_force.h"

MPI_Comm SimComm(Sim sim) { return sim->comm; }

/* The scene's state that checkpoints carry (output.h: the kept series and values) */
PetscErrorCode SceneKeepSeries(Sim sim, Series *s)
{
  PetscFunctionBeginUser;
  PetscCheck(sim->nkeep_series < SIM_MAX_KEEP, sim->comm, PETSC_ERR_PLIB, "More than %d kept series: raise SIM_MAX_KEEP", SIM_MAX_KEEP);
  sim->keep_series[sim->nkeep_series++] = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneKeepReal(Sim sim, PetscReal *r)
{
  PetscFunctionBeginUser;
  PetscCheck(sim->nkeep_reals < SIM_MAX_KEEP, sim->comm, PETSC_ERR_PLIB, "More than %d kept values: raise SIM_MAX_KEEP", SIM_MAX_KEEP);
  sim->keep_reals[sim->nkeep_reals++] = r;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void    *SimSceneContext(Sim sim) { return sim->scene_ctx; }
PetscErrorCode SimSetSceneContext(Sim sim, void *ctx)
{
  sim->scene_ctx = ctx;
  return PETSC_SUCCESS;
}
PetscInt  SimDim(Sim sim) { return sim->phys.dim; }
PetscErrorCode SimSetDim(Sim sim, PetscInt dim) /* the run checks it after the scene's create */
{
  sim->phys.dim = dim;
  return PETSC_SUCCESS;
}
PetscReal SimSpacing(Sim sim) { return sim->phys.dx; }
PetscErrorCode SimSetSpacing(Sim sim, PetscReal dx)
{
  sim->phys.dx = dx;
  return PETSC_SUCCESS;
}
PetscReal SimTime(Sim sim) { return sim->phys.t; }
PetscInt  SimStep(Sim sim) { return sim->phys.step; }
PetscReal SimEndTime(Sim sim) { return sim->t_end; }
PetscErrorCode SimSetEndTime(Sim sim, PetscReal t_end)
{
  sim->t_end = t_end;
  return PETSC_SUCCESS;
}
const PetscReal *SimDomainLo(Sim sim) { return sim->dom_lo; }
const PetscReal *SimDomainHi(Sim sim) { return sim->dom_hi; }
PetscErrorCode SimSetDomain(Sim sim, PetscInt d, PetscReal lo, PetscReal hi)
{
  PetscFunctionBeginUser;
  PetscCheck(d >= 0 && d < 3, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "Direction %" PetscInt_FMT " of the domain: 0, 1 or 2", d);
  sim->dom_lo[d] = lo;
  sim->dom_hi[d] = hi;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscBool SimPeriodic(Sim sim, PetscInt d) { return sim->periodic[d]; }
PetscErrorCode SimSetPeriodic(Sim sim, PetscInt d, PetscBool periodic)
{
  PetscFunctionBeginUser;
  PetscCheck(d >= 0 && d < 3, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "Direction %" PetscInt_FMT " of the domain: 0, 1 or 2", d);
  sim->periodic[d] = periodic;
  PetscFunctionReturn(PETSC_SUCCESS);
}
const PetscReal *SimGravity(Sim sim) { return sim->phys.g; }
PetscReal        SimGravityNorm(Sim sim) { return PetscSqrtReal(VDot(sim->phys.g, sim->phys.g, sim->phys.dim)); }
PetscErrorCode SimSetGravity(Sim sim, PetscReal gx, PetscReal gy, PetscReal gz)
{
  sim->phys.g[0] = gx;
  sim->phys.g[1] = gy;
  sim->phys.g[2] = gz;
  return PETSC_SUCCESS;
}
PetscBool SimHasFluid(Sim sim) { return sim->phys.has_fluid; }
PetscBool SimHasSolid(Sim sim) { return sim->phys.has_solid; }
PetscErrorCode SimSetMedia(Sim sim, PetscBool fluid, PetscBool solid)
{
  sim->phys.has_fluid = fluid;
  sim->phys.has_solid = solid;
  return PETSC_SUCCESS;
}
FluidMaterial *SimFluidMaterial(Sim sim) { return &sim->phys.fl; }
SolidMaterial *SimSolidMaterial(Sim sim) { return &sim->phys.sl; }
PetscBool      SimFluidIncompressible(Sim sim) { return (PetscBool)(sim->phys.fluid == FLUID_ISPH); }
PetscErrorCode SimSetReferenceSpeed(Sim sim, PetscReal v_ref)
{
  sim->phys.v_ref = v_ref;
  return PETSC_SUCCESS;
}
PetscBool SimConfined(Sim sim) { return sim->phys.confined; }
PetscErrorCode SimSetConfined(Sim sim, PetscBool confined)
{
  sim->phys.confined = confined;
  return PETSC_SUCCESS;
}
PetscBool SimOutflow(Sim sim) { return sim->outflow; }
PetscErrorCode SimSetOutflow(Sim sim, PetscBool outflow)
{
  sim->outflow = outflow;
  return PETSC_SUCCESS;
}
PetscReal SimFluidMassOut(Sim sim) { return sim->nbhd.mass_out; }
PetscInt  SimKernelRows(Sim sim) { return KernelSupportRows(&sim->phys.kernel); }
PetscReal SimKernelHFactor(Sim sim) { return sim->phys.kernel.h_factor; }
RefData  *SimRefData(Sim sim) { return &sim->refdata; }

PetscErrorCode SimSolidEnergy(Sim sim, PetscReal *ekin, PetscReal *estrain)
{
  PetscFunctionBeginUser;
  PetscCall(SolidEnergy(&sim->phys, ekin, estrain));
  PetscFunctionReturn(PETSC_SUCCESS);
}
const PetscReal *SimSolidLoad(Sim sim) { return sim->phys.solid->load_mean; }
const PetscReal *SimSolidSupport(Sim sim) { return sim->phys.solid->support_mean; }
PetscErrorCode   SimBodyForces(Sim sim, PetscInt k, PetscInt n, PetscReal force[][3])
{
  PetscFunctionBeginUser;
  PetscCheck(sim->phys.has_fluid, sim->comm, PETSC_ERR_ARG_WRONGSTATE, "A body's force is the fluid's: this run has no fluid");
  PetscCall(FluidBodyForces(&sim->phys, k, n, force));
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode SimBodyForce(Sim sim, PetscInt k, PetscReal force[3])
{
  PetscReal f[1][3];
  PetscFunctionBeginUser;
  PetscCall(SimBodyForces(sim, k, 1, f));
  for (PetscInt i = 0; i < 3; i++) force[i] = f[0][i];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Particles */
PetscErrorCode SimGetLocalSize(Sim sim, PetscInt *n)
{
  *n = sim->P->n;
  return PETSC_SUCCESS;
}

/* The field of that name: its id, or FIELD_COUNT for "id" and "kind" (*ints set), or an error. */
static PetscErrorCode FieldByName(Sim sim, const char name[], FieldId *f, PetscInt **ints)
{
  PetscFunctionBeginUser;
  *ints = NULL;
  *f    = FIELD_COUNT;
  if (!strcmp(name, "id")) *ints = sim->P->id;
  else if (!strcmp(name, "kind")) *ints = sim->P->kind;
  else {
    for (PetscInt k = 0; k < FIELD_COUNT; k++)
      if (!strcmp(name, FieldTable[k].name)) *f = (FieldId)k;
    PetscCheck(*f < FIELD_COUNT, sim->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "No particle field named %s (docs/output.md lists them)", name);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimHasField(Sim sim, const char name[], PetscBool *has)
{
  FieldId   f;
  PetscInt *ints;
  PetscFunctionBeginUser;
  PetscCall(FieldByName(sim, name, &f, &ints));
  *has = (PetscBool)(ints || sim->P->f[f].on);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimGetField(Sim sim, const char name[], PetscInt *width, void *array)
{
  FieldId   f;
  PetscInt *ints;
  PetscFunctionBeginUser;
  PetscCall(FieldByName(sim, name, &f, &ints));
  if (ints) {
    *(PetscInt **)array = ints;
    if (width) *width = 1;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(sim->P->f[f].on, sim->comm, PETSC_ERR_ARG_WRONGSTATE, "Particle field %s is not allocated in this run (a scene that reads it enables it in its create: SimEnableField)", name);
  *(PetscReal **)array = sim->P->f[f].a;
  if (width) *width = sim->P->f[f].width;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimRestoreField(Sim sim, const char name[], PetscInt *width, void *array)
{
  *(void **)array = NULL;
  return PETSC_SUCCESS;
}

PetscErrorCode SimEnableField(Sim sim, const char name[])
{
  FieldId   f;
  PetscInt *ints;
  PetscFunctionBeginUser;
  PetscCall(FieldByName(sim, name, &f, &ints));
  if (!ints) PetscCall(ParticlesEnableField(sim->P, f, (PetscBool)(f == FIELD_BODY))); /* SimBodyForce reads the ghosts' bodies */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimAddParticle(Sim sim, PetscInt id, ParticleKind kind, const PetscReal x[], PetscReal m, PetscReal h, PetscReal rho)
{
  PetscFunctionBeginUser;
  PetscCall(ParticlesAdd(sim->P, id, kind, x, m, h, rho));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt SimNextId(Sim sim) { return sim->next_id; }
PetscErrorCode SimSetNextId(Sim sim, PetscInt id)
{
  sim->next_id = id;
  return PETSC_SUCCESS;
}

typedef struct {
  void (*pair)(void *ctx, PetscInt a, PetscInt b);
  void *ctx;
} NeighbourVisit;

SPH_INLINE void VisitPair(void *ctx, PetscInt a, SPHPair p, const PetscInt D)
{
  NeighbourVisit *v = (NeighbourVisit *)ctx;
  v->pair(v->ctx, a, p.b);
}

PetscErrorCode SimForEachNeighbour(Sim sim, PetscInt a, void (*pair)(void *ctx, PetscInt a, PetscInt b), void *ctx)
{
  NeighbourVisit v = {pair, ctx};
  PetscFunctionBeginUser;
  PetscCheck(a >= 0 && a < sim->P->n, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "Particle %" PetscInt_FMT " is not owned (0 to %" PetscInt_FMT ")", a, sim->P->n - 1);
  SPHPairs(sim->cells, a, VisitPair, &v, sim->phys.dim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimAddOpenBoundary(Sim sim, const OpenBoundarySpec *spec)
{
  PetscFunctionBeginUser;
  PetscCheck(sim->phys.has_fluid, sim->comm, PETSC_ERR_ARG_INCOMP, "Open boundaries need a fluid: call SimSetMedia first");
  PetscCheck(sim->phys.fluid == FLUID_WCSPH || spec->kind != OPEN_OUTLET || spec->pressure == 0, sim->comm, PETSC_ERR_ARG_INCOMP, "Outlet: with -fluid isph the outlet's pressure is the pressure equation's Dirichlet value 0; give pressure 0 (or -fluid wcsph)");
  if (!sim->phys.open) {
    PetscCall(OpenCreate(&sim->phys.open));
    sim->phys.open->next_id = &sim->next_id;
    PetscCall(ParticlesEnableField(sim->P, FIELD_OPEN, PETSC_TRUE)); /* ghosts too: an outlet reads its neighbours' */
    PetscCall(SceneKeepReal(sim, &sim->phys.open->mass_in)); /* checkpoints carry it */
  }
  PetscCall(OpenAdd(&sim->phys, sim->phys.open, spec, sim->dom_lo, sim->dom_hi));
  if (spec->kind == OPEN_OUTLET) sim->outflow = PETSC_TRUE; /* its buffer's particles leave at the domain's end */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal SimFluidMassIn(Sim sim) { return sim->phys.open ? sim->phys.open->mass_in : 0; }
