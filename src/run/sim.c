#include "run/sim.h"
#include "base/options_used.h"
#include "run/scene_registry.h"
#include "fluid/open_boundary.h"
#include "fluid/wcsph.h"
#include "fluid/isph.h"
#include "solid/solid.h"
#include "fluid/boundary.h"
#include "io/io.h"
#include "base/kernel.h"
#include "io/checkpoint.h"
#include "run/guard.h"
#include "io/outdir.h"
#include "run/size_guard.h"

const char *const FluidSchemes[] = {"wcsph", "isph", "FluidScheme", "FLUID_", NULL};
const char *const KernelTypes[]  = {"cubic", "wendland_c2", "wendland_c4", "KernelType", "KERNEL_", NULL};

#define SIM_LANDING_STEPS 20 /* the steps over which a run lands on t_end */

PetscErrorCode SimCreate(MPI_Comm comm, Sim *sim)
{
  Sim s;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(sim));
  s       = *sim;
  s->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &s->rank));
  PetscCallMPI(MPI_Comm_size(comm, &s->size));
  s->refdata.rank   = s->rank;
  s->counter.add      = SizeGuardAdd; /* the scenes count what they add through these (scene layer) */
  s->counter.counting = SizeGuardCounting;
  s->t_end          = -1;
  s->max_steps      = PETSC_MAX_INT;
  s->progress_every = 5;
  s->ckpt_step      = -1;
  { /* the physics' defaults, before the scene's (physics.h) */
    Physics *ph       = &s->phys;
    ph->dim           = 2;
    ph->fluid         = FLUID_WCSPH;
    ph->cfl           = 0.25;
    ph->dx            = -1;
    ph->fl.rho0       = 1000.0;
    ph->fl.mu         = 1.0e-3;
    ph->fl.eta        = 0.1; /* the paper's */
    ph->fl.lap_kappa  = 1;
    ph->fl.alpha      = 0.02;
    ph->fl.wall_av    = 1.0;
    ph->fl.xsph       = 0.0;
    ph->fl.wall_clip  = PETSC_TRUE; /* WCSPH walls push, never pull (boundary.c) */
    ph->g[1]          = -9.81;
    ph->has_fluid     = PETSC_TRUE;
    ph->sl.rho0       = 1000.0;
    ph->sl.alpha      = 1.0;
    ph->sl.eps        = 0.3;
    ph->sl.n          = 4.0;
    KernelInit(&ph->kernel, KERNEL_CUBIC, 2, SPH_H_FACTOR);
  }
  {
    const char *names[STAGE_COUNT] = {"Neighbours", "Halo+migrate", "Physics", "PPE assembly", "PPE solve", "Solid", "Output", "Guard"};
    for (PetscInt k = 0; k < STAGE_COUNT; k++) { /* a second Sim in one program shares the stages */
      PetscCall(PetscLogStageGetId(names[k], &s->stage[k]));
      if (s->stage[k] < 0) PetscCall(PetscLogStageRegister(names[k], &s->stage[k]));
    }
  }
  PetscCall(GuardCreate(&s->guard));
  PetscCall(ParticlesCreate(comm, &s->P));
  PetscCall(DecompCreate(comm, &s->decomp));
  PetscCall(HaloCreate(comm, &s->halo));
  s->phys.comm   = comm; /* the physics' handles of the machinery (physics.h) */
  s->phys.P      = s->P;
  s->phys.decomp = s->decomp;
  s->phys.halo   = s->halo;
  s->phys.nb     = &s->nbhd;
  PetscCall(SimWireOutput(s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimDestroy(Sim *sim)
{
  Sim s = *sim;
  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(PETSC_SUCCESS);
  if (s->scene && s->scene->destroy) PetscCall(s->scene->destroy(s));
  PetscCall(OutDirClose(&s->out));
  PetscCall(IOFinalize(&s->out));
  PetscCall(ISPHDestroy(&s->phys.isph));
  PetscCall(SolidDestroy(&s->phys.solid));
  PetscCall(OpenDestroy(&s->phys.open));
  PetscCall(CellsDestroy(&s->cells));
  PetscCall(HaloDestroy(&s->halo));
  PetscCall(DecompDestroy(&s->decomp));
  PetscCall(ParticlesDestroy(&s->P));
  PetscCall(RefDataDestroy(&s->refdata));
  PetscCall(GuardDestroy(&s->guard));
  PetscCall(SizeGuardDestroy(&s->size_guard));
  PetscCall(PetscFree(*sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Generic options: scene, scheme, resolution, time, output. */
PetscErrorCode SimSetFromOptions(Sim sim)
{
  char      name[64] = "", names[512];
  PetscBool set, dx_set, t_set;
  PetscInt  fluid = sim->phys.fluid, ktype;
  PetscReal hfac;

  PetscFunctionBeginUser;
  PetscCall(CheckpointInheritOptions(sim->comm)); /* -restart FILE alone: the scene and options of FILE */
  PetscCall(PetscOptionsHasHelp(NULL, &sim->help));
  PetscCall(SceneListNames(names, sizeof(names)));
  PetscOptionsBegin(sim->comm, NULL, "sphfsi: SPH for fluid-structure interaction", "Sim");
  PetscCall(PetscOptionsString("-case", "Scene to run", "", name, name, sizeof(name), &set));
  PetscCall(OptEList("-fluid", "Fluid pressure scheme", "", FluidSchemes, 2, FluidSchemes[sim->phys.fluid], &fluid, NULL));
  /* Defaults by measurement (docs/convergence.md): WCSPH's square start lattice is unstable under
   * its own pressure with the cubic spline at 1.3 dx and stable with Wendland C2 at 1.4 dx
   * (tools/lattice_stability.py), at the same cost; ISPH keeps the paper's kernel, whose still tank
   * is at rest (its pressure is noisy with Wendland C2). */
  ktype = fluid == FLUID_WCSPH ? KERNEL_WENDLAND_C2 : KERNEL_CUBIC;
  PetscCall(OptEList("-kernel", "Smoothing kernel of every scheme and the solid: cubic (Eq. 12), wendland_c2, wendland_c4 (Dehnen & Aly 2012); support 2h; default: wendland_c2 with -fluid wcsph, cubic with isph", "", KernelTypes, 3, KernelTypes[ktype], &ktype, NULL));
  hfac = KernelDefaultHFactor((KernelType)ktype);
  PetscCall(OptReal("-h_factor", "Smoothing length over particle spacing, h / dx; default 1.4 for wendland_c2 (its lattice-stable value), else the paper's 1.3; wall rows default to cover 2h", "", hfac, &hfac, NULL));
  PetscCall(OptReal("-dx", "Particle spacing of the finest particles (m); default: the scene's", "", sim->phys.dx, &sim->phys.dx, &dx_set));
  PetscCall(OptReal("-t_end", "Physical end time (s); default: the scene's", "", sim->t_end, &sim->t_end, &t_set));
  PetscCall(OptReal("-dt", "Fixed time step (s); 0 = adaptive", "", sim->dt_fixed, &sim->dt_fixed, NULL));
  PetscCall(OptReal("-cfl", "Courant number of the adaptive time step", "", sim->phys.cfl, &sim->phys.cfl, NULL));
  PetscCall(OptInt("-max_steps", "Stop after this many steps", "", sim->max_steps, &sim->max_steps, NULL));
  PetscCall(PetscOptionsString("-output_dir", "Output directory (default out/CASE; with -restart, the checkpoint's directory)", "", sim->out.dir, sim->out.dir, sizeof(sim->out.dir), NULL));
  PetscCall(OptBool("-overwrite", "A new run into a directory that holds an earlier run's output removes that output (snapshots, probes, summary, checkpoints); without it the run refuses to start", "", sim->out.overwrite, &sim->out.overwrite, NULL));
  PetscCall(OptReal("-output_interval", "Snapshot interval in physical time (s); 0 = none", "", sim->out.snap_interval, &sim->out.snap_interval, NULL));
  PetscCall(OptReal("-probe_interval", "probes.csv row interval in physical time (s); 0 = every step", "", sim->out.probe_interval, &sim->out.probe_interval, NULL));
  PetscCall(OptInt("-progress_every", "Seconds of wall time between progress lines; 0 = none", "", sim->progress_every, &sim->progress_every, NULL));
  PetscCall(OptReal("-checkpoint_interval", "Checkpoint interval in physical time (s), OUTDIR/checkpoint.h5, also at the end; 0 = none (a stop by signal or -max_wall_time writes one anyway)", "", sim->out.ckpt_interval, &sim->out.ckpt_interval, NULL));
  PetscCall(PetscOptionsString("-restart", "Continue the run of this checkpoint (OUTDIR/checkpoint.h5 or last_good.h5): the scene and every option come from the checkpoint, options given now override them, output goes on in the checkpoint's directory", "", sim->out.restart, sim->out.restart, sizeof(sim->out.restart), NULL));
  PetscCall(PetscOptionsString("-refdata_dir", "Reference data for the errors in summary.json (default $SPHFSI_REFDATA, else per file the first of PREFIX/share/sphfsi/refdata, EXEDIR/refdata, the build's SRCDIR/../shared/refdata, ../shared/refdata from the current directory)", "", sim->refdata.dir, sim->refdata.dir, sizeof(sim->refdata.dir), NULL));
  PetscOptionsEnd();
  sim->phys.fluid = (FluidScheme)fluid;
  /* forces on bodies free of the gauge with WCSPH, whose sum moves with the level; ISPH's does not
   * (its PPE's pressure answers the particles' disorder, and the mean over the pairs would take that
   * out with the gauge: body_force.c) */
  sim->phys.fl.force_gauge = (PetscBool)(sim->phys.fluid == FLUID_WCSPH);
  PetscCheck(hfac >= 1 && hfac <= 3, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-h_factor %g must be in [1, 3] (h / dx; 1.3 for the cubic spline, 1.5-2.5 for the Wendland kernels)", (double)hfac);
  KernelInit(&sim->phys.kernel, (KernelType)ktype, 2, hfac);
  PetscCheck(set && name[0], sim->comm, PETSC_ERR_USER_INPUT, "No scene given: use -case NAME with NAME one of: %s (or -options_file cases/NAME.opts)", names);
  PetscCall(SceneFind(name, &sim->scene));
  PetscCheck(sim->scene, sim->comm, PETSC_ERR_USER_INPUT, "Unknown -case %s: choose one of %s", name, names);
  PetscCheck(!dx_set || sim->phys.dx > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dx %g must be > 0", (double)sim->phys.dx);
  PetscCheck(!t_set || sim->t_end > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-t_end %g must be > 0", (double)sim->t_end);
  PetscCheck(sim->dt_fixed >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dt %g must be > 0 (or 0 for an adaptive step)", (double)sim->dt_fixed);
  PetscCheck(sim->phys.cfl > 0 && sim->phys.cfl <= 1, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cfl %g must be in (0, 1]", (double)sim->phys.cfl);
  PetscCheck(sim->out.snap_interval >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-output_interval %g must be >= 0", (double)sim->out.snap_interval);
  PetscCheck(sim->out.probe_interval >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-probe_interval %g must be >= 0", (double)sim->out.probe_interval);
  PetscCheck(sim->max_steps >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-max_steps must be >= 0");
  PetscCheck(sim->progress_every >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-progress_every %" PetscInt_FMT " must be >= 0 (seconds of wall time between progress lines; 0 = none)", sim->progress_every);
  PetscCheck(sim->out.ckpt_interval >= 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-checkpoint_interval %g must be >= 0 (s of physical time; 0 = none)", (double)sim->out.ckpt_interval);
  PetscCall(GuardSetFromOptions(sim));
  if (!sim->out.dir[0] && sim->out.restart[0]) { /* the directory the checkpoint belongs to */
    char *slash;
    PetscCall(PetscStrncpy(sim->out.dir, sim->out.restart, sizeof(sim->out.dir)));
    if ((slash = strrchr(sim->out.dir, '/'))) *slash = 0;
    else PetscCall(PetscStrncpy(sim->out.dir, ".", sizeof(sim->out.dir)));
  }
  if (!sim->out.dir[0]) PetscCall(PetscSNPrintf(sim->out.dir, sizeof(sim->out.dir), "out/%s", sim->scene->name));
  PetscCall(DecompSetFromOptions(sim->decomp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every particle the scene made lies in the domain box (periodic directions wrapped): a scene whose
 * walls or water stick out of its -domain (e.g. a case file's box with another -dx) is bad input,
 * not a run that fails at its first migration. */
static PetscErrorCode CheckInDomain(Sim sim)
{
  const PetscInt   D = sim->phys.dim;
  const PetscReal *x = PField(sim->P, FIELD_X);
  PetscReal        out[4] = {-1, 0, 0, 0}; /* id and position of one particle outside */
  PetscInt         n = 0;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < sim->P->n; a++) {
    PetscReal y[3] = {0, 0, 0};
    for (PetscInt d = 0; d < D; d++) y[d] = x[D * a + d];
    GridWrap(&sim->grid, y);
    if (GridCellOf(&sim->grid, y) >= 0) continue;
    if (!n++) { out[0] = sim->P->id[a]; for (PetscInt d = 0; d < D; d++) out[1 + d] = y[d]; }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, sim->comm));
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, out, 4, MPIU_REAL, MPIU_MAX, sim->comm)); /* the one of the highest id */
  SETERRQ(sim->comm, PETSC_ERR_USER_INPUT, "%" PetscInt_FMT " particle(s) of the scene lie outside its domain [%g, %g] x [%g, %g]%s, e.g. one at (%g, %g%s): its walls or water do not fit the box; choose a larger -domain (or a -dx with which the scene fits it)", n, (double)sim->dom_lo[0], (double)sim->dom_hi[0], (double)sim->dom_lo[1], (double)sim->dom_hi[1], D == 3 ? " x [..]" : "", (double)out[1], (double)out[2], D == 3 ? ", .." : "");
}

/* The scene's prescribed motion, for the solid's steps (physics.h: the physics does not know the scene). */
static PetscErrorCode ScenePrescribe(void *ctx)
{
  Sim sim = (Sim)ctx;
  PetscFunctionBeginUser;
  PetscCall(sim->scene->prescribe(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimTotalMass(Sim sim, PetscReal *M)
{
  PetscReal s = 0, *m = PField(sim->P, FIELD_M);
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < sim->P->n; a++)
    if (KindIsFluid(sim->P->kind[a]) || sim->P->kind[a] == KIND_SOLID) s += m[a];
  PetscCall(MPIU_Allreduce(&s, M, 1, MPIU_REAL, MPI_SUM, sim->comm));
  *M += sim->nbhd.mass_out;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -help: the options of the modules this run does not build as well (the other fluid scheme and
 * its pressure solver, -ppe_*), and of the neighbour list, with their values.  The run stops after
 * listing them (main.c), so what these set up is never used. */
/* W is read in few places (wall state, ISPH's density and wall normals, XSPH), F in all: the list
 * keeps F, and W is recomputed where read (the same bits; docs/performance.md item 15) */
static PetscErrorCode NeighbourListOptions(Sim sim, PetscBool *store)
{
  PetscFunctionBeginUser;
  *store = PETSC_FALSE;
  PetscOptionsBegin(sim->comm, NULL, "Neighbour list", "Sim");
  PetscCall(OptBool("-neighbour_store_w", "Keep each pair's kernel value W in the neighbour list (8 B a pair more) instead of recomputing it where it is read; the same results bit for bit", "", *store, store, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode HelpOtherModules(Sim sim)
{
  PetscBool store;
  PetscFunctionBeginUser;
  if (sim->phys.has_fluid && sim->phys.fluid == FLUID_ISPH) {
    PetscCall(WCSPHSetFromOptions(&sim->phys));
    PetscCall(WCSPHSetUp(&sim->phys));
  } else if (sim->phys.has_fluid) {
    PetscCall(ISPHSetFromOptions(&sim->phys));
    PetscCall(ISPHSetUp(&sim->phys));
    PetscCall(ISPHDestroy(&sim->phys.isph));
  }
  PetscCall(NeighbourListOptions(sim, &store));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A phase of a step, logged in its stage (-log_view).  The stages are the driver's: the physics
 * pushes none; the neighbourhood's work and the ghost refreshes inside a phase log in their own
 * stages (NeighbourhoodWire).  A fault inside leaves the stage pushed: GuardStep pops it. */
static PetscErrorCode Staged(Sim sim, SimStage stage, PetscErrorCode (*phase)(Physics *))
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim->stage[stage]));
  PetscCall(phase(&sim->phys));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -gravity_pulse: the gravity of the time t (a step sees that of its start). */
static void GravityPulse(Sim sim)
{
  PetscBool in;
  if (!sim->pulse.on) return;
  in = (PetscBool)(sim->phys.t >= sim->pulse.t0 && sim->phys.t < sim->pulse.t1);
  for (PetscInt d = 0; d < sim->phys.dim; d++) sim->phys.g[d] = sim->pulse.g_base[d] + (in ? sim->pulse.g[d] : 0);
}

/* The solid's state after the particles moved (its list, loads and rates). */
static PetscErrorCode SolidAfterRebuild(Physics *ph)
{
  PetscFunctionBeginUser;
  PetscCall(SolidPrepare(ph));
  PetscCall(SolidRates(ph));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimSetUp(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(sim->scene->create(sim));
  PetscCheck(sim->phys.dx > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dx %g must be > 0", (double)sim->phys.dx);
  PetscCheck(sim->phys.dim == 2 || sim->phys.dim == 3, sim->comm, PETSC_ERR_PLIB, "Scene %s set dimension %" PetscInt_FMT, sim->scene->name, sim->phys.dim);
  { /* a -dx so fine that the lattice counts overflow would leave an empty scene: say so first */
    PetscReal lattice = 1;
    char      box[128] = "";
    for (PetscInt d = 0; d < sim->phys.dim; d++) {
      lattice *= (sim->dom_hi[d] - sim->dom_lo[d]) / sim->phys.dx;
      PetscCall(PetscSNPrintf(box + strlen(box), sizeof(box) - strlen(box), "%s%g", d ? " x " : "", (double)(sim->dom_hi[d] - sim->dom_lo[d])));
    }
    PetscCheck(lattice < 1e12, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dx %g would make more than 1e12 particles in the %s m domain: choose a larger -dx", (double)sim->phys.dx, box);
  }
  PetscCheck(sim->t_end > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-t_end %g must be > 0", (double)sim->t_end);
  PetscCheck(sim->phys.has_fluid || sim->phys.has_solid, sim->comm, PETSC_ERR_PLIB, "Scene %s has neither fluid nor solid", sim->scene->name);
  PetscCall(SimWireOutputToScene(sim));
  PetscOptionsBegin(sim->comm, NULL, "Body force", "Sim");
  {
    PetscReal g[3] = {sim->phys.g[0], sim->phys.g[1], sim->phys.g[2]};
    PetscInt  ng   = 3;
    PetscBool set;
    PetscCall(PetscOptionsRealArray("-gravity", "Gravity vector gx,gy (2D) or gx,gy,gz (3D) (m/s^2)", "", g, &ng, &set));
    PetscCheck(!set || ng == sim->phys.dim, sim->comm, PETSC_ERR_ARG_WRONG, "-gravity takes %" PetscInt_FMT " components in this %" PetscInt_FMT "D scene (%s), %" PetscInt_FMT " given", sim->phys.dim, sim->phys.dim, sim->phys.dim == 3 ? "gx,gy,gz" : "gx,gy", ng);
    if (set) PetscCall(PetscArraycpy(sim->phys.g, g, sim->phys.dim));
  }
  {
    PetscReal v[5] = {0, 0, 0, 0, 0};
    PetscInt  nv = 5, D = sim->phys.dim;
    PetscBool set;
    PetscCall(PetscOptionsRealArray("-gravity_pulse", "gx,gy[,gz],t0,t1: gravity grows by (gx,gy[,gz]) (m/s^2) over the steps that start in t0 <= t < t1 (s): a push that starts an instability which would otherwise grow from round-off, such as the Turek-Hron flag's flutter", "", v, &nv, &set));
    PetscCheck(!set || nv == D + 2, sim->comm, PETSC_ERR_ARG_WRONG, "-gravity_pulse takes %" PetscInt_FMT " values in this %" PetscInt_FMT "D scene (%s,t0,t1), %" PetscInt_FMT " given", D + 2, D, D == 3 ? "gx,gy,gz" : "gx,gy", nv);
    for (PetscInt i = 0; set && i < nv; i++) PetscCheck(!PetscIsInfOrNanReal(v[i]), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gravity_pulse: value %" PetscInt_FMT " is not finite", i + 1);
    PetscCheck(!set || (v[D] >= 0 && v[D + 1] > v[D]), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gravity_pulse: its window t0 = %g, t1 = %g needs 0 <= t0 < t1 (s)", (double)v[D], (double)v[D + 1]);
    sim->pulse.on = set;
    for (PetscInt d = 0; set && d < D; d++) sim->pulse.g[d] = v[d];
    sim->pulse.t0 = v[D];
    sim->pulse.t1 = v[D + 1];
  }
  PetscOptionsEnd();
  for (PetscInt d = 0; d < sim->phys.dim; d++) PetscCheck(!PetscIsInfOrNanReal(sim->phys.g[d]), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-gravity: component %" PetscInt_FMT " is not finite", d + 1);
  PetscCall(PetscArraycpy(sim->pulse.g_base, sim->phys.g, 3));
  KernelInit(&sim->phys.kernel, sim->phys.kernel.type, sim->phys.dim, sim->phys.kernel.h_factor); /* the normalisation of the scene's dimension */
  PetscCall(ParticlesSetDimension(sim->P, sim->phys.dim));
  if (sim->phys.has_fluid) PetscCall(FluidMaterialSetFromOptions(sim->comm, &sim->phys.kernel, sim->phys.dim, sim->phys.v_ref, &sim->phys.fl, &sim->start_jitter)); /* after the scene's defaults */
  if (sim->phys.has_solid) {
    PetscCall(SolidSetFromOptions(&sim->phys));
    PetscCall(SolidSetUp(&sim->phys)); /* before ISPH: the coupling decides the PPE's symmetry */
    PetscCall(ParticlesEnableField(sim->P, FIELD_XREB, PETSC_FALSE)); /* solids move after a rebuild */
  }
  if (sim->phys.has_fluid && sim->phys.fluid == FLUID_ISPH) {
    PetscCall(ISPHSetFromOptions(&sim->phys));
    PetscCall(ISPHSetUp(&sim->phys));
  } else if (sim->phys.has_fluid) {
    PetscCall(WCSPHSetFromOptions(&sim->phys));
    PetscCall(WCSPHSetUp(&sim->phys));
  }
  if (sim->help) PetscCall(HelpOtherModules(sim));
  PetscCall(ParticlesSetUp(sim->P));
  if (sim->help) PetscFunctionReturn(PETSC_SUCCESS); /* listed: no particles, no output */
  PetscCall(SizeGuardCheck(sim)); /* before the particles: a run too large for the memory stops here */
  PetscCall(OutDirOpen(&sim->out));
  PetscCall(GuardCheckSetUp(sim, "before the particles were made"));
  if (sim->guard->state) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(sim->scene->populate(sim));
  PetscCall(GuardCheckSetUp(sim, "after the particles were made"));
  if (sim->guard->state) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ParticlesGlobalCount(sim->P, &sim->nbhd.nparticles));
  if (sim->phys.solid) { /* the solids' extent as built (a restart reads its state after this) */
    PetscReal dt_transit;
    PetscCall(SolidTransitLimit(&sim->phys, &dt_transit));
  }
  { /* the largest smoothing length sets the cells (scenes may mix particle sizes) */
    const PetscReal *h = PField(sim->P, FIELD_H);
    sim->phys.h_max = sim->phys.kernel.h_factor * sim->phys.dx;
    for (PetscInt a = 0; a < sim->P->n; a++) sim->phys.h_max = PetscMax(sim->phys.h_max, h[a]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sim->phys.h_max, 1, MPIU_REAL, MPIU_MAX, sim->comm));
  }
  if (sim->phys.has_fluid) {
    PetscInt nfluid = 0;
    for (PetscInt a = 0; a < sim->P->n; a++) nfluid += KindIsFluid(sim->P->kind[a]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nfluid, 1, MPIU_INT, MPI_SUM, sim->comm));
    PetscCheck(nfluid > 0, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "The geometry leaves no fluid particle at -dx %g: the water region is thinner than one -dx; choose a smaller -dx or a larger water region", (double)sim->phys.dx);
  }
  /* a periodic length holds three cells: a skin that does not fit is made smaller (a short
   * periodic channel), down to none, rather than refuse a run that fits without it */
  /* solids keep their neighbour lists over sub-steps, and WCSPH its main list over steps: cells
   * wide enough for both skins, since the solids' list is built from bins up to half the fluid's
   * skin old (SolidPrepare after every fluid step) */
  {
    const PetscReal reach = 2.0 * sim->phys.h_max + (sim->phys.solid ? sim->phys.solid->skin * sim->phys.dx : 0); /* the cell without the fluid's skin */
    for (PetscInt d = 0; d < sim->phys.dim && sim->nbhd.skin > 0; d++)
      if (sim->periodic[d]) sim->nbhd.skin = PetscMin(sim->nbhd.skin, PetscMax(0, (1 - 1e-9) * (sim->dom_hi[d] - sim->dom_lo[d]) / 3 - reach));
    PetscCall(GridSetUp(&sim->grid, sim->phys.dim, sim->dom_lo, sim->dom_hi, reach + sim->nbhd.skin, sim->periodic));
  }
  PetscCall(CheckInDomain(sim));
  sim->decomp->split_solids = (PetscBool)(sim->decomp->split_solids && sim->phys.has_fluid && sim->phys.has_solid);
  PetscCall(DecompSetUp(sim->decomp, &sim->grid));
  PetscCall(CellsCreate(&sim->grid, &sim->phys.kernel, &sim->cells));
  sim->phys.cells = sim->cells;
  if (sim->scene->prescribe) {
    sim->phys.prescribe     = ScenePrescribe;
    sim->phys.prescribe_ctx = sim;
  }
  sim->cells->skin = sim->nbhd.skin;
  PetscCall(NeighbourhoodWire(&sim->nbhd, sim->comm, sim->P, &sim->grid, sim->decomp, sim->halo, sim->cells, sim->periodic, sim->outflow, sim->stage[STAGE_HALO], sim->stage[STAGE_NEIGHBOUR]));
  if (sim->phys.open) { /* the buffers' particles, and new ones at every rebuild */
    PetscCall(OpenSetUp(&sim->phys));
    sim->nbhd.inflow     = OpenInflow;
    sim->nbhd.inflow_ctx = &sim->phys;
  }
  {
    PetscBool store;
    PetscCall(NeighbourListOptions(sim, &store));
    sim->cells->drop_w = (PetscBool)!store;
  }
  sim->out.next_probe = sim->out.next_snap = 0;
  sim->out.next_ckpt  = sim->out.ckpt_interval;
  PetscCall(GuardCheckSetUp(sim, "before the neighbour lists were built"));
  if (sim->guard->state) PetscFunctionReturn(PETSC_SUCCESS);
  if (sim->out.restart[0]) PetscCall(CheckpointRestart(&sim->out)); /* the particles and state of the checkpoint */
  else {
    PetscCall(DecompPartition(sim->decomp, sim->P)); /* from the scene's round-robin spread, so no rank ever holds them all */
    PetscCall(DecompMigrate(sim->decomp, sim->P));   /* wraps and checks every particle is inside */
    PetscCall(NeighbourhoodRebuild(&sim->nbhd, sim->phys.step));
    PetscCall(SimTotalMass(sim, &sim->mass0));
    GravityPulse(sim); /* the first rates see it too */
    if (sim->phys.has_fluid && sim->phys.fluid == FLUID_ISPH) PetscCall(Staged(sim, STAGE_PHYSICS, ISPHInitialize));
    else if (sim->phys.has_fluid) PetscCall(Staged(sim, STAGE_PHYSICS, WCSPHRates));
    if (sim->phys.has_solid) PetscCall(Staged(sim, STAGE_SOLID, SolidAfterRebuild));
  }
  if (sim->out.restart[0]) PetscCall(OutDirTidyRestart(&sim->out)); /* the snapshots past the checkpoint */
  PetscCall(IOSetUp(&sim->out));
  sim->ready = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Progress(Sim sim)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  {
    PetscReal el = now - sim->wall_start, done = sim->phys.t - sim->t_start, left = done > 0 ? el * (sim->t_end - sim->phys.t) / done : 0;
    char its[64] = "";
    if (sim->phys.isph) PetscCall(PetscSNPrintf(its, sizeof(its), "  PPE its %" PetscInt_FMT " (free surface %" PetscInt_FMT ")", sim->phys.isph->ppe->its_last, sim->phys.isph->nfree));
    if (sim->phys.has_fluid && sim->phys.solid) PetscCall(PetscSNPrintf(its + strlen(its), sizeof(its) - strlen(its), "  solid sub-steps %" PetscInt_FMT, sim->phys.solid->nsub_last));
    PetscCall(PetscPrintf(sim->comm, "step %7" PetscInt_FMT "  t %.5e / %.4g s  dt %.3e  particles %" PetscInt_FMT "%s  wall %.1f s  left ~%.0f s\n", sim->phys.step, (double)sim->phys.t, (double)sim->t_end, (double)sim->phys.dt, sim->nbhd.nparticles, its, (double)el, (double)left));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid's step; ISPH's in its four phases (isph.h). */
static PetscErrorCode FluidStep(Sim sim)
{
  PetscFunctionBeginUser;
  if (!sim->phys.isph) {
    PetscCall(Staged(sim, STAGE_PHYSICS, WCSPHStep));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(Staged(sim, STAGE_PHYSICS, ISPHPredict));
  PetscCall(Staged(sim, STAGE_PPE_ASSEMBLY, ISPHAssemble));
  PetscCall(Staged(sim, STAGE_PPE_SOLVE, ISPHSolve));
  PetscCall(Staged(sim, STAGE_PHYSICS, ISPHCorrect));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One step of the fluid, then the solid sub-cycled with its own step inside it (multi-rate). */
static PetscErrorCode Step(Sim sim)
{
  PetscReal dts = PETSC_MAX_REAL;
  PetscInt  nsub = 1;

  PetscFunctionBeginUser;
  GravityPulse(sim);
  if (sim->phys.has_solid && (sim->phys.has_fluid || !sim->dt_fixed)) PetscCall(SolidTimeStep(&sim->phys, &dts)); /* with a fluid, -dt is the fluid's: the solid sub-steps in it */
  if (sim->dt_fixed > 0) sim->phys.dt = sim->dt_fixed;
  else if (sim->phys.isph) PetscCall(ISPHTimeStep(&sim->phys, &sim->phys.dt));
  else if (sim->phys.has_fluid) PetscCall(WCSPHTimeStep(&sim->phys, &sim->phys.dt));
  else sim->phys.dt = dts;
  if (sim->phys.has_solid && !sim->phys.solid->subcycle) sim->phys.dt = PetscMin(sim->phys.dt, dts); /* one step for all (the paper's way) */
  /* a collapsing step is a blow-up: stop before the state changes */
  if (sim->phys.has_fluid && !sim->dt_fixed) PetscCall(GuardCheckDt(sim, 0, sim->phys.dt));
  if (dts < PETSC_MAX_REAL && !sim->guard->state) PetscCall(GuardCheckDt(sim, 1, dts));
  if (sim->guard->state) PetscFunctionReturn(PETSC_SUCCESS);
  { /* land on t_end in equal steps over the last SIM_LANDING_STEPS, not a full step and a sliver, nor
     * a halved last step: ISPH's pressure grows as 1/dt^2 with its source's density part (SPHERIC
     * Test 2: a 0.6 ms last step after 4 ms ones put 22.6 kPa on P1, against 2 kPa the step before;
     * the still bowl: two halves kicked the water from 0.05 to 3 mm/s).  Here a step shrinks by at
     * most 1 / SIM_LANDING_STEPS. */
    const PetscReal left = sim->t_end - sim->phys.t;
    if (left < sim->phys.dt * (1 + 1e-6)) sim->phys.dt = left;
    else if (left < SIM_LANDING_STEPS * sim->phys.dt) sim->phys.dt = left / PetscCeilReal(left / sim->phys.dt);
  }
  if (sim->phys.has_fluid) PetscCall(FluidStep(sim));
  if (sim->phys.has_solid) {
    if (dts < sim->phys.dt) nsub = (PetscInt)PetscCeilReal(sim->phys.dt / dts * (1 - 1e-12));
    PetscCall(PetscLogStagePush(sim->stage[STAGE_SOLID]));
    if (sim->phys.has_fluid) PetscCall(SolidAfterRebuild(&sim->phys)); /* the fluid moved and everything was rebuilt: new loads on the solid */
    PetscCall(SolidBeginSubsteps(&sim->phys));
    for (PetscInt k = 0; k < nsub; k++) PetscCall(SolidStep(&sim->phys, sim->phys.dt / nsub));
    PetscCall(PetscLogStagePop());
    if (sim->phys.has_fluid) { /* the last half kick left the solids' ghosts a half kick behind their owners,
                            and the next fluid step reads them (ISPH's predictor before any refresh) */
      const FieldId vel[] = {FIELD_V};
      PetscCall(HaloRefresh(sim->halo, sim->P, 1, vel));
    }
    sim->phys.solid->nsub_last = nsub;
    sim->phys.solid->nsub_max  = PetscMax(sim->phys.solid->nsub_max, nsub);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A checkpoint unless the last one holds this step already. */
static PetscErrorCode Checkpoint(Sim sim)
{
  PetscFunctionBeginUser;
  if (sim->ckpt_step == sim->phys.step) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CheckpointSave(&sim->out));
  PetscCall(GuardCheckIO(sim));
  if (sim->guard->state == GUARD_IO) PetscFunctionReturn(PETSC_SUCCESS);
  sim->ckpt_step = sim->phys.step;
  sim->out.ckpt_t = sim->phys.t;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimRun(Sim sim)
{
  PetscLogDouble  last, t1;
  const PetscReal eps = 1e-12 * sim->t_end, ps0 = sim->particle_steps;
  const PetscInt  step0 = sim->phys.step;
  Guard           g = sim->guard;
  PetscBool       shown;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(PETSC_VIEWER_STDOUT_(sim->comm), "sphfsi: case %s, fluid %s, kernel %s at h = %g dx, %d rank(s), dx %g, t_end %g, c0 %g\n", sim->scene->name, sim->phys.has_fluid ? FluidSchemes[sim->phys.fluid] : "none", KernelTypes[sim->phys.kernel.type], (double)sim->phys.kernel.h_factor, sim->size, (double)sim->phys.dx, (double)sim->t_end, (double)(sim->phys.has_fluid ? sim->phys.fl.c0 : sim->phys.sl.c0)));
  PetscCall(ParticlesView(sim->P, PETSC_VIEWER_STDOUT_(sim->comm)));
  PetscCall(DecompView(sim->decomp, PETSC_VIEWER_STDOUT_(sim->comm)));
  if (sim->phys.isph) PetscCall(ISPHView(&sim->phys, PETSC_VIEWER_STDOUT_(sim->comm)));
  else if (sim->phys.has_fluid) PetscCall(WCSPHView(&sim->phys, PETSC_VIEWER_STDOUT_(sim->comm)));
  if (sim->phys.solid) PetscCall(SolidView(&sim->phys, PETSC_VIEWER_STDOUT_(sim->comm)));
  PetscCall(PetscTime(&sim->wall_start));
  sim->t_start = sim->phys.t;
  last         = sim->wall_start;
  if (!sim->out.restart[0]) { /* a restart has the first probe row and snapshot already */
    PetscCall(IOProbes(&sim->out));
    if (sim->out.snap_interval > 0) PetscCall(IOSnapshot(&sim->out));
  }
  PetscCall(GuardCheckInitial(sim));
  PetscCall(GuardCheckIO(sim));
  while (!g->state && sim->phys.t < sim->t_end - eps && sim->phys.step < sim->max_steps) {
    PetscCall(GuardStepBegin(sim));
    PetscCall(GuardStep(sim, Step));
    if (g->state) break; /* a fault inside the step: time does not advance */
    sim->phys.t += sim->phys.dt;
    sim->phys.step++;
    sim->particle_steps += (PetscReal)sim->nbhd.nparticles;
    PetscCall(PetscTime(&t1));
    shown = (PetscBool)(sim->progress_every && t1 - last >= sim->progress_every);
    PetscCall(GuardStepEnd(sim, &shown)); /* NaN/Inf, signals, wall time, progress: agreed */
    if (g->state == GUARD_FAULT) break;
    if (g->state == GUARD_STOP) PetscCall(GuardAnnounceStop(sim));
    if (sim->phys.t >= sim->out.next_probe - eps) PetscCall(IOProbes(&sim->out));
    if (g->state == GUARD_STOP) { /* what a launcher's kill may not leave time for: probes and summary first */
      PetscCall(PetscTime(&t1));
      sim->wall_loop = t1 - sim->wall_start;
      PetscCall(IOWriteProbes(&sim->out));
      PetscCall(SimTotalMass(sim, &sim->mass));
      PetscCall(SimWriteSummary(sim));
    }
    PetscCall(OutDirBeat(&sim->out));
    if (sim->out.snap_interval > 0 && sim->phys.t >= sim->out.next_snap - eps) {
      PetscCall(IOSnapshot(&sim->out));
      PetscCall(IOWriteProbes(&sim->out));
    }
    if (sim->out.ckpt_interval > 0 && sim->phys.t >= sim->out.next_ckpt - eps) {
      PetscCall(Checkpoint(sim));
      PetscCall(IOWriteProbes(&sim->out));
    }
    PetscCall(GuardCheckIO(sim)); /* output that could not be written ends the run */
    if (g->state == GUARD_STOP || g->state == GUARD_IO) break;
    if (shown) {
      last = t1;
      PetscCall(Progress(sim));
      PetscCall(IOWriteProbes(&sim->out)); /* probes.csv is at most a progress interval old */
      PetscCall(GuardCheckIO(sim));
    }
  }
  PetscCall(PetscTime(&t1));
  sim->wall_loop = t1 - sim->wall_start;
  if (sim->progress_every) PetscCall(Progress(sim));
  if (g->state == GUARD_STOP && getenv("SPHFSI_TEST_STOP_DELAY")) PetscCall(PetscSleep(atof(getenv("SPHFSI_TEST_STOP_DELAY")))); /* tests: a stop as slow as a large checkpoint's (tests/check_stop.sh) */
  if (g->state == GUARD_STOP || (!g->state && sim->out.ckpt_interval > 0)) PetscCall(Checkpoint(sim));
  PetscCall(GuardFinish(sim));
  if (sim->exit_status == SIM_EXIT_FAULT && sim->phys.isph) PetscCall(PPEFaultHint(sim->phys.isph->ppe));
  PetscCall(IOWriteProbes(&sim->out));
  PetscCall(SimTotalMass(sim, &sim->mass));
  PetscCall(SimWriteSummary(sim));
  if (sim->decomp->log_stats) PetscCall(DecompWriteStats(sim->decomp, sim->out.dir));
  PetscCall(PetscPrintf(sim->comm, "sphfsi: %" PetscInt_FMT " steps in %.2f s (%.3g particle-steps/s); output in %s\n", sim->phys.step - step0, (double)sim->wall_loop, (double)((sim->particle_steps - ps0) / PetscMax(sim->wall_loop, 1e-9)), sim->out.dir));
  PetscFunctionReturn(PETSC_SUCCESS);
}
