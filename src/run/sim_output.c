/* The driver's side of the output's context (output.h): the handles it wires into sim->out, the
 * scene handed over as data and callbacks, and the guard's verdict for summary.json.  The output
 * knows none of the run, the scene or the guard; this file is where they meet it. */
#include "run/sim.h"
#include "run/guard.h"
#include "io/io.h"

PetscErrorCode SimWireOutput(Sim s)
{
  Output *out = &s->out;
  PetscFunctionBeginUser;
  out->comm               = s->comm;
  out->rank               = s->rank;
  out->size               = s->size;
  out->phys               = &s->phys;
  out->grid               = &s->grid;
  out->refdata            = &s->refdata;
  out->stage              = s->stage[STAGE_OUTPUT];
  out->run.mass0          = &s->mass0;
  out->run.mass           = &s->mass;
  out->run.particle_steps = &s->particle_steps;
  out->run.wall_used      = &s->wall_used;
  out->run.wall_start     = &s->wall_start;
  out->run.wall_loop      = &s->wall_loop;
  out->run.dt_first       = s->guard->dt_first;
  out->run.next_id        = &s->next_id;
  out->ckpt_t             = -1; /* no checkpoint yet */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The scene's probes and errors take the run: the output calls them through these, with the run as
 * its opaque context. */
static PetscErrorCode SceneProbe(void *ctx, PetscReal vals[])
{
  Sim sim = (Sim)ctx;
  PetscFunctionBeginUser;
  PetscCall(sim->scene->probe(sim, vals));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SceneErrors(void *ctx, FILE *json)
{
  Sim sim = (Sim)ctx;
  PetscFunctionBeginUser;
  PetscCall(sim->scene->errors(sim, json));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimWireOutputToScene(Sim sim)
{
  Output *out = &sim->out;
  PetscFunctionBeginUser;
  PetscCheck(sim->scene->nprobes <= OUTPUT_MAX_PROBES, sim->comm, PETSC_ERR_PLIB, "Scene %s has %" PetscInt_FMT " probes, the output takes %d (OUTPUT_MAX_PROBES)", sim->scene->name, sim->scene->nprobes, OUTPUT_MAX_PROBES);
  out->t_end              = sim->t_end;
  out->scene.name         = sim->scene->name;
  out->scene.nprobes      = sim->scene->nprobes;
  out->scene.probe_names  = sim->scene->probe_names;
  out->scene.probe        = SceneProbe;
  out->scene.errors       = sim->scene->errors ? SceneErrors : NULL;
  out->scene.ctx          = sim;
  out->scene.kept_series  = sim->keep_series; /* the scene registers them in its create (SceneKeep*) */
  out->scene.kept_reals   = sim->keep_reals;
  out->scene.nkept_series = sim->nkeep_series;
  out->scene.nkept_reals  = sim->nkeep_reals;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SimWriteSummary(Sim sim)
{
  const char *const status[] = {"completed", "stopped", "fault", "io_error"}; /* by GuardState */
  Guard             g        = sim->guard;
  PetscFunctionBeginUser;
  PetscCall(IOSummary(&sim->out, status[g->state], g->state ? g->msg : NULL, sim->ready));
  PetscFunctionReturn(PETSC_SUCCESS);
}
