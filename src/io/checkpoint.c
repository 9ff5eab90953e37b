#include "io/checkpoint.h"
#include "base/options_used.h"
#include "io/io.h"
#include "io/io_space.h"
#include "io/h5.h"
#include "fluid/isph.h"
#include "solid/solid.h"
#include <petscviewerhdf5.h>
#include <errno.h>

#define CHECKPOINT_FORMAT  "sphfsi checkpoint"
#define CHECKPOINT_VERSION 1

/* Scalars of the state: names in the file, and where they live in the run. */
static const char *const RealNames[STATE_NREAL] = {"time", "dt", "next_output", "next_probe", "next_checkpoint", "mass0", "mass_out", "particle_steps", "wall_used", "dt_first_fluid", "dt_first_solid", "ppe_its_sum"};
static const char *const IntNames[STATE_NINT]   = {"step", "particles", "next_id", "repartitions", "solid_substeps_last", "solid_substeps_max", "solid_rebuilds", "ppe_solves", "ppe_its_max", "ppe_its_last", "isph_free_surface", "snapshots"};

/* Pointers to the scalars; modules the scene lacks point to a dummy. */
static void Slots(Output *out, PetscReal *r[STATE_NREAL], PetscInt *i[STATE_NINT], PetscReal *rd, PetscInt *id)
{
  Physics *ph  = out->phys;
  PPE      ppe = ph->isph ? ph->isph->ppe : NULL;
  Solid    s   = ph->solid;
  r[0] = &ph->t; r[1] = &ph->dt; r[2] = &out->next_snap; r[3] = &out->next_probe; r[4] = &out->next_ckpt;
  r[5] = out->run.mass0; r[6] = &ph->nb->mass_out; r[7] = out->run.particle_steps; r[8] = out->run.wall_used;
  r[9] = &out->run.dt_first[0]; r[10] = &out->run.dt_first[1]; r[11] = ppe ? &ppe->its_sum : rd;
  i[0] = &ph->step; i[1] = &ph->nb->nparticles; i[2] = out->run.next_id; i[3] = &ph->decomp->nrepartition;
  i[4] = s ? &s->nsub_last : id; i[5] = s ? &s->nsub_max : id; i[6] = s ? &s->nrebuild : id;
  i[7] = ppe ? &ppe->nsolve : id; i[8] = ppe ? &ppe->its_max : id; i[9] = ppe ? &ppe->its_last : id;
  i[10] = ph->isph ? &ph->isph->nfree : id; i[11] = &out->nsnap;
}

static PetscErrorCode StateScalars(Output *out, SimState *s)
{
  PetscReal     *r[STATE_NREAL], rd = 0;
  PetscInt      *i[STATE_NINT], id = 0;
  PetscLogDouble now;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  Slots(out, r, i, &rd, &id);
  for (PetscInt k = 0; k < STATE_NREAL; k++) s->r[k] = *r[k];
  if (*out->run.wall_start > 0) s->r[8] += now - *out->run.wall_start; /* wall_used: with this run's loop so far */
  for (PetscInt k = 0; k < STATE_NINT; k++) s->i[k] = *i[k];
  s->nrows = out->nprobe_rows;
  s->nsnap = out->nsnap;
  for (PetscInt k = 0; k < out->scene.nkept_series; k++) s->series_n[k] = out->scene.kept_series[k]->n;
  for (PetscInt k = 0; k < out->scene.nkept_reals; k++) s->kept[k] = *out->scene.kept_reals[k];
  s->ncell = GridNumCells(out->grid);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StateView(Output *out, SimState *s)
{
  Particles P = out->phys->P;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->n = P->n; s->id = P->id; s->kind = P->kind; s->owner = out->phys->decomp->owner;
  for (PetscInt f = 0; f < FIELD_COUNT; f++) s->f[f] = ParticlesCheckpointField(P, (FieldId)f) ? P->f[f].a : NULL;
  PetscCall(StateScalars(out, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StateDestroy(SimState *s)
{
  PetscFunctionBeginUser;
  if (s->copy) {
    PetscCall(PetscFree2(s->id, s->kind));
    for (PetscInt f = 0; f < FIELD_COUNT; f++) PetscCall(PetscFree(s->f[f]));
    PetscCall(PetscFree(s->owner));
  }
  PetscCall(PetscMemzero(s, sizeof(*s)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StateCopy(Output *out, SimState *s)
{
  Particles P = out->phys->P;
  PetscInt  nc = GridNumCells(out->grid);
  PetscFunctionBeginUser;
  if (!s->copy) PetscCall(PetscMemzero(s, sizeof(*s)));
  if (s->cap < P->n || !s->id) { /* grow with room: the particle count drifts between ranks */
    PetscInt cap = (3 * P->n) / 2 + 16;
    PetscCall(PetscFree2(s->id, s->kind));
    PetscCall(PetscMalloc2(cap, &s->id, cap, &s->kind));
    for (PetscInt f = 0; f < FIELD_COUNT; f++) {
      PetscCall(PetscFree(s->f[f]));
      if (ParticlesCheckpointField(P, (FieldId)f)) PetscCall(PetscMalloc1(cap * P->f[f].width, &s->f[f]));
    }
    s->cap = cap;
  }
  if (!s->owner) PetscCall(PetscMalloc1(nc, &s->owner));
  s->copy = PETSC_TRUE;
  s->n    = P->n;
  PetscCall(PetscArraycpy(s->id, P->id, P->n));
  PetscCall(PetscArraycpy(s->kind, P->kind, P->n));
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (ParticlesCheckpointField(P, (FieldId)f)) PetscCall(PetscArraycpy(s->f[f], P->f[f].a, P->n * P->f[f].width));
  PetscCall(PetscArraycpy(s->owner, out->phys->decomp->owner, nc));
  PetscCall(StateScalars(out, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Comma-separated names of the fields checkpoints carry: a restart needs the same set. */
static PetscErrorCode FieldList(Particles P, char *buf, size_t len)
{
  PetscFunctionBeginUser;
  buf[0] = 0;
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (ParticlesCheckpointField(P, (FieldId)f)) {
      if (buf[0]) PetscCall(PetscStrlcat(buf, ",", len));
      PetscCall(PetscStrlcat(buf, P->f[f].name, len));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWrite(Output *out, const SimState *s, const char *path)
{
  Particles   P = out->phys->P;
  MPI_Comm    comm = out->comm;
  PetscViewer v;
  char        tmp[PETSC_MAX_PATH_LEN], fields[1024], name[64];
  PetscInt    version = CHECKPOINT_VERSION, ranks = out->size, ncol = 1 + out->scene.nprobes, *owner = NULL;
  const char *fluid = out->phys->has_fluid ? FluidSchemes[out->phys->fluid] : "none";

  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(out->stage));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  PetscCall(FieldList(P, fields, sizeof(fields)));
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "format", PETSC_STRING, CHECKPOINT_FORMAT));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "version", PETSC_INT, &version));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "case", PETSC_STRING, out->scene.name));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "fluid", PETSC_STRING, fluid));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "fields", PETSC_STRING, fields));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ranks", PETSC_INT, &ranks));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "dx", PETSC_REAL, &out->phys->dx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cells", PETSC_INT, &s->ncell));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "probe_columns", PETSC_INT, &ncol));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "probe_rows", PETSC_INT, &s->nrows));
  {
    char *all;
    PetscCall(PetscOptionsGetAll(NULL, &all));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "options", PETSC_STRING, all));
    PetscCall(PetscFree(all));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "kept_series", PETSC_INT, &out->scene.nkept_series));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "kept_values", PETSC_INT, &out->scene.nkept_reals));
  for (PetscInt k = 0; k < STATE_NREAL; k++) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", RealNames[k], PETSC_REAL, &s->r[k]));
  for (PetscInt k = 0; k < STATE_NINT; k++) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", IntNames[k], PETSC_INT, &s->i[k]));
  for (PetscInt k = 0; k < out->scene.nkept_reals; k++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_value_%d", (int)k));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", name, PETSC_REAL, &s->kept[k]));
  }
  /* particles: each rank's block in its order, and the block sizes, for a same-size restart */
  PetscCall(DatasetWriteInts(v, comm, "rank_counts", 1, &s->n));
  PetscCall(DatasetWriteInts(v, comm, "id", s->n, s->id));
  PetscCall(DatasetWriteInts(v, comm, "kind", s->n, s->kind));
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (ParticlesCheckpointField(P, (FieldId)f)) PetscCall(DatasetWriteReals(v, comm, P->f[f].name, s->n, P->f[f].width, s->f[f]));
  /* rank 0's: partition, probe rows, snapshot times and sizes, kept histories (empty ones are left out) */
  if (!out->rank) {
    PetscCall(PetscMalloc1(s->ncell, &owner));
    for (PetscInt c = 0; c < s->ncell; c++) owner[c] = s->owner[c];
  }
  PetscCall(DatasetWriteInts(v, comm, "partition", out->rank ? 0 : s->ncell, owner));
  PetscCall(PetscFree(owner));
  if (s->nrows) PetscCall(DatasetWriteReals(v, comm, "probe_table", out->rank ? 0 : s->nrows * ncol, 1, out->probe_rows));
  if (s->nsnap) PetscCall(DatasetWriteReals(v, comm, "snapshot_table", out->rank ? 0 : 2 * s->nsnap, 1, out->snaps));
  for (PetscInt k = 0; k < out->scene.nkept_series; k++) {
    const Series *se = out->scene.kept_series[k];
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_n", (int)k));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", name, PETSC_INT, &s->series_n[k]));
    if (!s->series_n[k]) continue;
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_t", (int)k));
    PetscCall(DatasetWriteReals(v, comm, name, out->rank ? 0 : s->series_n[k], 1, se->t));
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_y", (int)k));
    PetscCall(DatasetWriteReals(v, comm, name, out->rank ? 0 : s->series_n[k], 1, se->y));
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(IORenameOnRoot(out, tmp, path));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointSave(Output *out)
{
  SimState s;
  char     path[PETSC_MAX_PATH_LEN];
  PetscReal bytes;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(IOSpaceCheckpoint(out, &bytes));
  PetscCall(IOSpaceReserve(out, "checkpoint.h5", bytes, &ok));
  if (!ok) PetscFunctionReturn(PETSC_SUCCESS); /* the previous checkpoint stays */
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/checkpoint.h5", out->dir));
  PetscCall(StateView(out, &s));
  PetscCall(IOSpacePushWrite(path));
  PetscCall(CheckpointWrite(out, &s, path));
  PetscCall(IOSpacePopWrite());
  if (out->fault.set) PetscFunctionReturn(PETSC_SUCCESS); /* not renamed into place */
  out->nckpt++;
  if (out->ckpt_interval > 0)
    out->next_ckpt = OutputNextTime(out->next_ckpt, out->ckpt_interval, out->phys->t + 1e-12 * out->t_end);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* n reals that rank 0 wrote (a history or a table), read on rank 0 and broadcast. */
static PetscErrorCode ReadRootReals(Output *out, PetscViewer v, const char *name, PetscInt n, PetscReal *vals)
{
  PetscFunctionBeginUser;
  PetscCall(DatasetReadReals(v, out->comm, name, out->rank ? 0 : n, 1, vals));
  PetscCallMPI(MPI_Bcast(vals, (PetscMPIInt)n, MPIU_REAL, 0, out->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ReadString(PetscViewer v, const char *name, char *buf, size_t len)
{
  char     *s = NULL;
  PetscBool has;
  PetscFunctionBeginUser;
  buf[0] = 0;
  PetscCall(PetscViewerHDF5HasAttribute(v, "/", name, &has));
  if (!has) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", name, PETSC_STRING, NULL, &s));
  PetscCall(PetscStrncpy(buf, s, len));
  PetscCall(PetscFree(s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The header: is this a checkpoint of this run's scene, scheme, fields and resolution? */
static PetscErrorCode CheckHeader(Output *out, PetscViewer v, PetscInt *ranks, PetscInt *ncell)
{
  const char *path = out->restart;
  char        buf[1024], fields[1024];
  PetscReal   dx;
  PetscInt    k, want;

  PetscFunctionBeginUser;
  PetscCall(ReadString(v, "format", buf, sizeof(buf)));
  PetscCheck(!strcmp(buf, CHECKPOINT_FORMAT), out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s is not an sphfsi checkpoint (snapshots particles_*.h5 cannot be restarted from; use checkpoint.h5 or last_good.h5 of a run)", path);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "version", PETSC_INT, NULL, &k));
  PetscCheck(k == CHECKPOINT_VERSION, out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s has checkpoint format version %d; this program reads version %d", path, (int)k, CHECKPOINT_VERSION);
  PetscCall(ReadString(v, "case", buf, sizeof(buf)));
  PetscCheck(!strcmp(buf, out->scene.name), out->comm, PETSC_ERR_USER_INPUT, "-restart %s is a checkpoint of scene %s, not of -case %s: restart with -case %s (its options file)", path, buf, out->scene.name, buf);
  PetscCall(ReadString(v, "fluid", buf, sizeof(buf)));
  PetscCheck(!strcmp(buf, out->phys->has_fluid ? FluidSchemes[out->phys->fluid] : "none"), out->comm, PETSC_ERR_USER_INPUT, "-restart %s was written with -fluid %s, this run has -fluid %s: restart with -fluid %s", path, buf, FluidSchemes[out->phys->fluid], buf);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "dx", PETSC_REAL, NULL, &dx));
  PetscCheck(PetscAbsReal(dx - out->phys->dx) <= 1e-12 * dx, out->comm, PETSC_ERR_USER_INPUT, "-restart %s was written with -dx %g, this run has -dx %g: a restart keeps the resolution (drop -dx or give %g)", path, (double)dx, (double)out->phys->dx, (double)dx);
  PetscCall(ReadString(v, "fields", buf, sizeof(buf)));
  PetscCall(FieldList(out->phys->P, fields, sizeof(fields)));
  PetscCheck(!strcmp(buf, fields), out->comm, PETSC_ERR_USER_INPUT, "-restart %s holds the particle fields {%s}, this run allocates {%s}: restart with the options the checkpoint was written with (e.g. -fluid_xsph, -isph_shift, -wcsph_shift, -solid_gradient, -fsi_*)", path, buf, fields);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "cells", PETSC_INT, NULL, ncell));
  PetscCheck(*ncell == GridNumCells(out->grid), out->comm, PETSC_ERR_USER_INPUT, "-restart %s has a grid of %d cells, this run %d: the scene's geometry options differ from the checkpointed run's", path, (int)*ncell, (int)GridNumCells(out->grid));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "probe_columns", PETSC_INT, NULL, &k));
  PetscCheck(k == 1 + out->scene.nprobes, out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s has %d probe columns, scene %s %d", path, (int)k, out->scene.name, (int)(1 + out->scene.nprobes));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "kept_series", PETSC_INT, NULL, &k));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "kept_values", PETSC_INT, NULL, &want));
  PetscCheck(k == out->scene.nkept_series && want == out->scene.nkept_reals, out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s keeps %d histories and %d values of the scene, this program %d and %d: written by another version", path, (int)k, (int)want, (int)out->scene.nkept_series, (int)out->scene.nkept_reals);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "ranks", PETSC_INT, NULL, ranks));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Options that may change at a restart (run control, output, diagnostics); a change of any other
 * is reported. */
static PetscBool RunControl(const char *name)
{
  const char *exact[]  = {"-restart", "-t_end", "-max_steps", "-max_wall_time", "-checkpoint_interval", "-output_dir", "-output_interval", "-probe_interval", "-progress_every", "-dt", "-cfl", "-dt_min", "-unused_options", "-refdata_dir", "-help", "-overwrite", "-max_memory"};
  const char *prefix[] = {"-log", "-info", "-malloc", "-options_", "-ppe_ksp_monitor", "-ppe_ksp_view", "-ppe_ksp_converged"};
  for (size_t k = 0; k < sizeof(exact) / sizeof(exact[0]); k++)
    if (!strcmp(name, exact[k])) return PETSC_TRUE;
  for (size_t k = 0; k < sizeof(prefix) / sizeof(prefix[0]); k++)
    if (!strncmp(name, prefix[k], strlen(prefix[k]))) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* The value of option `name` in a PetscOptionsGetAll string ("" for a flag, NULL if absent). */
static const char *ValueIn(char *all, const char *name, char *buf, size_t len)
{
  size_t n = strlen(name);
  for (char *p = strstr(all, name); p; p = strstr(p + 1, name)) {
    char *v;
    if ((p != all && p[-1] != ' ') || (p[n] != ' ' && p[n] != 0)) continue;
    v = p + n + (p[n] == ' ');
    if (*v == '-' && !(v[1] >= '0' && v[1] <= '9') && v[1] != '.') return ""; /* a flag */
    buf[0] = 0;
    strncat(buf, v, PetscMin(len - 1, strcspn(v, " ")));
    return buf;
  }
  return NULL;
}

/* Physics options that differ from the checkpointed run's: a warning (the run goes on, e.g. with a
 * changed -wcsph_alpha, but it is then no continuation of the same run).  A checkpoint of an earlier
 * version may hold options by their old names: compared by their new ones. */
static PetscErrorCode CompareOptions(Output *out, PetscViewer v)
{
  char     *then = NULL, *now = NULL, diff[2048] = "", a[256], b[256];
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasAttribute(v, "/", "options", &has));
  if (!has) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "options", PETSC_STRING, NULL, &then));
  {
    char *renamed;
    PetscCall(OptionsRenameAll(then, &renamed));
    PetscCall(PetscFree(then));
    then = renamed;
  }
  PetscCall(PetscOptionsGetAll(NULL, &now));
  for (int pass = 0; pass < 2; pass++) { /* options of the checkpointed run, then this run's */
    char *list = pass ? now : then;
    for (char *p = list; (p = strchr(p, '-'));) {
      char        name[256] = "";
      const char *va, *vb;
      size_t      n = strcspn(p, " ");
      if ((p != list && p[-1] != ' ') || (p[1] >= '0' && p[1] <= '9') || p[1] == '.' || n >= sizeof(name)) { p++; continue; }
      strncat(name, p, n);
      p += n;
      if (RunControl(name)) continue;
      va = ValueIn(then, name, a, sizeof(a));
      vb = ValueIn(now, name, b, sizeof(b));
      if (pass && va) continue; /* compared in the first pass */
      if (va && vb && !strcmp(va, vb)) continue;
      if (strlen(diff) + strlen(name) + (va ? strlen(va) : 7) + (vb ? strlen(vb) : 7) + 16 >= sizeof(diff)) break; /* enough said */
      PetscCall(PetscSNPrintf(diff + strlen(diff), sizeof(diff) - strlen(diff), " %s %s -> %s;", name, va ? (*va ? va : "(set)") : "(unset)", vb ? (*vb ? vb : "(set)") : "(unset)"));
    }
  }
  if (diff[0]) PetscCall(PetscPrintf(out->comm, "sphfsi: warning: options differ from the checkpointed run's:%s the run goes on with this run's values\n", diff));
  PetscCall(PetscFree(then));
  PetscCall(PetscFree(now));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Scalars, probe rows, snapshot times and the scene's kept histories and values. */
static PetscErrorCode ReadRunState(Output *out, PetscViewer v)
{
  PetscReal *r[STATE_NREAL], rd = 0;
  PetscInt  *i[STATE_NINT], id = 0, ncol = 1 + out->scene.nprobes;
  char       name[64];

  PetscFunctionBeginUser;
  Slots(out, r, i, &rd, &id);
  for (PetscInt k = 0; k < STATE_NREAL; k++) PetscCall(PetscViewerHDF5ReadAttribute(v, "/", RealNames[k], PETSC_REAL, NULL, r[k]));
  for (PetscInt k = 0; k < STATE_NINT; k++) PetscCall(PetscViewerHDF5ReadAttribute(v, "/", IntNames[k], PETSC_INT, NULL, i[k]));
  for (PetscInt k = 0; k < out->scene.nkept_reals; k++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_value_%d", (int)k));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", name, PETSC_REAL, NULL, out->scene.kept_reals[k]));
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "probe_rows", PETSC_INT, NULL, &out->nprobe_rows));
  PetscCall(PetscFree(out->probe_rows));
  out->cap_probe_rows = out->nprobe_rows + 64;
  PetscCall(PetscMalloc1(out->cap_probe_rows * ncol, &out->probe_rows));
  if (out->nprobe_rows) PetscCall(DatasetReadReals(v, out->comm, "probe_table", out->rank ? 0 : out->nprobe_rows * ncol, 1, out->probe_rows));
  PetscCall(PetscFree(out->snaps));
  out->snap_cap = out->nsnap + 16;
  PetscCall(PetscMalloc1(2 * out->snap_cap, &out->snaps));
  if (out->nsnap) PetscCall(ReadRootReals(out, v, "snapshot_table", 2 * out->nsnap, out->snaps));
  for (PetscInt k = 0; k < out->scene.nkept_series; k++) {
    Series    *se = out->scene.kept_series[k];
    PetscInt   n;
    PetscReal *buf;
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_n", (int)k));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", name, PETSC_INT, NULL, &n));
    PetscCall(SeriesDestroy(se));
    if (!n) continue;
    PetscCall(PetscMalloc1(2 * n, &buf));
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_t", (int)k));
    PetscCall(ReadRootReals(out, v, name, n, buf));
    PetscCall(PetscSNPrintf(name, sizeof(name), "kept_series_%d_y", (int)k));
    PetscCall(ReadRootReals(out, v, name, n, buf + n));
    for (PetscInt j = 0; j < n; j++) PetscCall(SeriesAppend(se, buf[j], buf[n + j]));
    PetscCall(PetscFree(buf));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Owned particles: with the checkpoint's number of ranks each rank takes its own block back (the
 * same particles in the same order); otherwise an even split, sorted out by the migration. */
static PetscErrorCode ReadParticles(Output *out, PetscViewer v, PetscInt ranks)
{
  Particles P = out->phys->P;
  PetscInt  n = PETSC_DECIDE, N = out->phys->nb->nparticles, nsum;
  PetscFunctionBeginUser;
  if (ranks == out->size) PetscCall(DatasetReadInts(v, out->comm, "rank_counts", 1, &n));
  else PetscCall(PetscSplitOwnership(out->comm, &n, &N));
  PetscCall(MPIU_Allreduce(&n, &nsum, 1, MPIU_INT, MPI_SUM, out->comm));
  PetscCheck(nsum == out->phys->nb->nparticles, out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the ranks' blocks hold %d particles, the header says %d", out->restart, (int)nsum, (int)out->phys->nb->nparticles);
  P->n = P->ng = 0;
  PetscCall(ParticlesReserve(P, n));
  P->n = n;
  PetscCall(DatasetReadInts(v, out->comm, "id", n, P->id));
  PetscCall(DatasetReadInts(v, out->comm, "kind", n, P->kind));
  for (PetscInt f = 0; f < FIELD_COUNT; f++) {
    if (ParticlesCheckpointField(P, (FieldId)f)) PetscCall(DatasetReadReals(v, out->comm, P->f[f].name, n, P->f[f].width, P->f[f].a));
    else if (P->f[f].on) PetscCall(PetscArrayzero(P->f[f].a, n * P->f[f].width)); /* not carried: the step computes it (particles.h) */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Positions x and those of field f (FIELD_XREB, FIELD_XLIST) trade places, ghosts included. */
static void SwapPositions(Particles P, FieldId f)
{
  PetscReal *t = P->f[FIELD_X].a;
  if (!P->f[f].on) return;
  P->f[FIELD_X].a = P->f[f].a;
  P->f[f].a       = t;
}

PetscErrorCode CheckpointRestart(Output *out)
{
  Physics    *ph = out->phys;
  Particles   P  = ph->P;
  PetscViewer v;
  PetscInt    ranks, ncell, nf = 0;
  FieldId     all[FIELD_COUNT];
  int         err = 0;

  PetscFunctionBeginUser;
  if (!out->rank) { /* readable, and an HDF5 file (its signature), before HDF5 tries */
    FILE         *f = fopen(out->restart, "rb");
    unsigned char sig[8] = {0};
    if (!f) err = errno;
    else {
      if (fread(sig, 1, 8, f) != 8 || memcmp(sig, "\211HDF\r\n\032\n", 8)) err = -1;
      fclose(f);
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, out->comm));
  PetscCheck(err >= 0, out->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s is not an HDF5 file: give a checkpoint (OUTDIR/checkpoint.h5 or OUTDIR/last_good.h5)", out->restart);
  PetscCheck(!err, out->comm, PETSC_ERR_FILE_OPEN, "Cannot open the restart file -restart %s (%s)", out->restart, strerror(err));
  PetscCall(PetscViewerHDF5Open(out->comm, out->restart, FILE_MODE_READ, &v));
  PetscCall(CheckHeader(out, v, &ranks, &ncell));
  PetscCall(CompareOptions(out, v));
  PetscCall(ReadRunState(out, v));
  PetscCheck(ph->t < out->t_end * (1 - 1e-12), out->comm, PETSC_ERR_USER_INPUT, "-restart %s is at t = %g, not before -t_end %g: give a later -t_end to continue the run", out->restart, (double)ph->t, (double)out->t_end);
  PetscCall(ReadParticles(out, v, ranks));
  /* the run's last rebuild, at the positions it had then */
  SwapPositions(P, FIELD_XREB);
  if (ranks == out->size) {
    PetscInt *owner;
    PetscCall(PetscMalloc1(ncell, &owner));
    PetscCall(DatasetReadInts(v, out->comm, "partition", out->rank ? 0 : ncell, owner));
    for (PetscInt c = 0; c < ncell && !out->rank; c++) ph->decomp->owner[c] = (PetscMPIInt)owner[c];
    PetscCall(PetscFree(owner));
    PetscCallMPI(MPI_Bcast(ph->decomp->owner, (PetscMPIInt)ncell, MPI_INT, 0, out->comm));
  } else PetscCall(DecompPartition(ph->decomp, P));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(NeighbourhoodRebuildKeepPartition(ph->nb, ph->step));
  if (ph->solid && !P->f[FIELD_XLIST].on) PetscCall(SolidPrepare(ph)); /* as after every rebuild: the solids' list, xref */
  SwapPositions(P, FIELD_XREB);
  /* ghosts take every field's current value */
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    if (P->f[f].on && f != FIELD_XREB) all[nf++] = (FieldId)f;
  PetscCall(HaloRefresh(ph->halo, P, nf, all));
  if (P->f[FIELD_XLIST].on) { /* WCSPH's skin with solids: the main list's pairs and the solids' list where the run made them */
    SwapPositions(P, FIELD_XLIST);
    PetscCall(CellsRefreshPairs(ph->cells, P));
    PetscCall(SolidPrepare(ph));
    SwapPositions(P, FIELD_XLIST);
  } else if (ph->nb->skin > 0) PetscCall(CellsRefreshPairs(ph->cells, P)); /* the main list's pairs now (-wcsph_skin) */
  if (ph->solid) PetscCall(CellsUpdatePairs(ph->solid->nl, P)); /* solid pairs: their current kernel values */
  out->ckpt_t = ph->t; /* the state the last checkpoint holds (summary.json) */
  PetscCall(PetscPrintf(out->comm, "sphfsi: restarted from %s (written on %d rank(s)) at step %" PetscInt_FMT ", t = %g\n", out->restart, (int)ranks, ph->step, (double)ph->t));
  PetscFunctionReturn(PETSC_SUCCESS);
}
