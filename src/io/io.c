#include "base/version.h"
#include "io/io.h"
#include "fluid/isph.h"
#include "solid/solid.h"
#include "io/io_space.h"
#include "io/h5.h"
#include <unistd.h>
#include <petscviewerhdf5.h>
#include <sys/stat.h>
#include <errno.h>
#include <sys/resource.h>

/* A failure on rank 0 alone (files it writes) becomes an I/O fault of every rank (io_space.h), not a
 * hang: the run ends with one line and SIM_EXIT_IO. */
static PetscErrorCode RootCheck(Output *out, int err, const char *what)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, out->comm));
  if (err) PetscCall(IOFault(out, "%s writing %s/%s", strerror(err), out->dir, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IORenameOnRoot(Output *out, const char *tmp, const char *path)
{
  PetscFunctionBeginUser;
  PetscCall(RootCheck(out, out->rank || !rename(tmp, path) ? 0 : errno, path));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* probes.csv from every row so far, under a temporary name renamed when complete: the file is
 * always whole, and after a restart it holds the rows up to the checkpoint and on from there. */
PetscErrorCode IOWriteProbes(Output *out)
{
  char     path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE    *f;
  int      err = 0;
  PetscInt ncol = 1 + out->scene.nprobes;
  PetscFunctionBeginUser;
  if (out->rank) PetscFunctionReturn(RootCheck(out, 0, "probes.csv"));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/probes.csv", out->dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  if (!(f = fopen(tmp, "w"))) PetscFunctionReturn(RootCheck(out, errno, "probes.csv"));
  fprintf(f, "t");
  for (PetscInt k = 0; k < out->scene.nprobes; k++) fprintf(f, ",%s", out->scene.probe_names[k]);
  fprintf(f, "\n");
  for (PetscInt r = 0; r < out->nprobe_rows; r++) {
    const PetscReal *row = out->probe_rows + r * ncol;
    for (PetscInt k = 0; k < ncol; k++) fprintf(f, k ? ",%.9g" : "%.9g", (double)row[k]);
    fprintf(f, "\n");
  }
  if (ferror(f)) err = EIO;
  if (fclose(f) && !err) err = errno;
  if (!err && rename(tmp, path)) err = errno;
  PetscCall(RootCheck(out, err, "probes.csv"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSetUp(Output *out)
{
  PetscFunctionBeginUser;
  PetscCall(IOWriteProbes(out)); /* the header, or the restarted run's rows */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOFinalize(Output *out)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(out->probe_rows));
  PetscCall(PetscFree(out->snaps));
  out->nprobe_rows = out->cap_probe_rows = out->snap_cap = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The attributes that make a snapshot the input of -case file (src/scenes/particles_file.c): the
 * spacing dx and the computational box, domain = x0,y0[,z0],x1,y1[,z1]. */
static PetscErrorCode WriteDomain(PetscViewer v, Output *out)
{
  hid_t     file, space, attr;
  hsize_t   n = 2 * out->phys->dim;
  PetscReal dom[6];
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "dx", PETSC_REAL, &out->phys->dx));
  for (PetscInt d = 0; d < out->phys->dim; d++) { dom[d] = out->grid->lo[d]; dom[out->phys->dim + d] = out->grid->hi[d]; }
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  PetscCheck((space = H5Screate_simple(1, &n, NULL)) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not make the domain attribute's space");
  PetscCheck((attr = H5Acreate2(file, "domain", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not create the domain attribute");
  PetscCheck(H5Awrite(attr, H5T_NATIVE_DOUBLE, dom) >= 0 && H5Aclose(attr) >= 0 && H5Sclose(space) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not write the domain attribute");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective: one file, every owned particle's id, kind and the snapshot's fields (the field table,
 * particles.h); written under a temporary name and renamed when complete. */
PetscErrorCode IOWriteParticles(Output *out, const char *path)
{
  PetscViewer v;
  char        tmp[PETSC_MAX_PATH_LEN];
  Particles   P = out->phys->P;
  FieldId     fields[FIELD_COUNT];
  PetscInt    nfields = ParticlesSnapshotFields(P, fields);

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  PetscCall(PetscViewerHDF5Open(out->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(DatasetWriteInts(v, out->comm, "id", P->n, P->id));
  PetscCall(DatasetWriteInts(v, out->comm, "kind", P->n, P->kind));
  if (out->phys->nb->nparticles != *out->run.next_id) { /* ids no longer 0..N-1 (outflow): the points' indices for the XDMF's topology */
    PetscInt *vertex, first = 0, n = P->n;
    PetscCallMPI(MPI_Exscan(&n, &first, 1, MPIU_INT, MPI_SUM, out->comm));
    if (!out->rank) first = 0;
    PetscCall(PetscMalloc1(n, &vertex));
    for (PetscInt i = 0; i < n; i++) vertex[i] = first + i;
    PetscCall(DatasetWriteInts(v, out->comm, "vertex", n, vertex));
    PetscCall(PetscFree(vertex));
  }
  for (PetscInt k = 0; k < nfields; k++) PetscCall(DatasetWriteReals(v, out->comm, P->f[fields[k]].name, P->n, P->f[fields[k]].width, P->f[fields[k]].a));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "time", PETSC_REAL, &out->phys->t));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "step", PETSC_INT, &out->phys->step));
  PetscCall(WriteDomain(v, out));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(IORenameOnRoot(out, tmp, path));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A grid's Polyvertex topology with its connectivity, the points' indices: ParaView's default
 * reader (Xdmf3) makes no cell without one, and then draws nothing (the legacy reader numbers the
 * points itself).  The ids are 0..next_id-1 (the scene hands them out in turn), so while no
 * particle has left (N == next_id) the file's own `id` lists every point once, in some order; once
 * the outflow has removed some, a snapshot carries the indices 0..N-1 as `vertex` (IOWriteParticles),
 * and a single file (last_good.h5, a checkpoint) has them here as text (~6 bytes a particle, once). */
static void WriteVertices(Output *out, FILE *f, PetscInt N, const char *h5, PetscBool snapshot)
{
  fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\">\n", (int)N);
  if (N == *out->run.next_id || snapshot) fprintf(f, "     <DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/%s</DataItem>\n", (int)N, (int)sizeof(PetscInt), h5, N == *out->run.next_id ? "id" : "vertex");
  else {
    fprintf(f, "     <DataItem Dimensions=\"%d\" NumberType=\"Int\" Format=\"XML\">", (int)N);
    for (PetscInt i = 0; i < N; i++) fprintf(f, i % 20 ? " %d" : "\n      %d", (int)i);
    fprintf(f, "\n     </DataItem>\n");
  }
  fprintf(f, "    </Topology>\n");
}

/* Field fid of the HDF5 file h5 as an attribute of its N points, by the field table's XDMF type
 * (particles.h); nothing for XDMF_NONE (x: the geometry). */
static void WriteAttribute(FILE *f, Particles P, FieldId fid, PetscInt N, const char *h5)
{
  const char *name = P->f[fid].name, *type = NULL;
  switch (FieldTable[fid].xdmf) {
  case XDMF_NONE: return;
  case XDMF_SCALAR: break;
  case XDMF_VECTOR: type = "Vector"; break;
  case XDMF_SYM: type = P->dim == 3 ? "Tensor6" : "Vector"; break; /* 2D: xx, xy, yy as a 3-vector */
  }
  if (!type) fprintf(f, "    <Attribute Name=\"%s\" Center=\"Node\"><DataItem Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem></Attribute>\n", name, (int)N, h5, name);
  else fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\"><DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem></Attribute>\n", name, type, (int)N, (int)P->f[fid].width, h5, name);
}

/* OUTDIR/xmf: a temporal collection over n HDF5 files in OUTDIR (rewritten each time): the
 * snapshots particles_NNNNN.h5 (one = NULL), or the one file `one`; tN: (t, particles) per file. */
static PetscErrorCode WriteXDMF(Output *out, const char *xmf, PetscInt n, const char *one, const PetscReal *tN)
{
  char           path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE          *f;
  const PetscInt D = out->phys->dim;
  FieldId        fields[FIELD_COUNT];
  const PetscInt nfields = ParticlesSnapshotFields(out->phys->P, fields);

  PetscFunctionBeginUser;
  int err = 0;
  if (out->rank) PetscFunctionReturn(RootCheck(out, 0, xmf));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", out->dir, xmf));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  if (!(f = fopen(tmp, "w"))) PetscFunctionReturn(RootCheck(out, errno, xmf));
  fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt s = 0; s < n; s++) {
    char           h5[PETSC_MAX_PATH_LEN];
    const PetscInt N = (PetscInt)tN[2 * s + 1];
    if (N < 0) continue; /* a snapshot of a restarted run that is not in this directory (outdir.c) */
    if (one) PetscCall(PetscStrncpy(h5, one, sizeof(h5)));
    else PetscCall(PetscSNPrintf(h5, sizeof(h5), "particles_%05" PetscInt_FMT ".h5", s));
    fprintf(f, "   <Grid Name=\"step%05d\" GridType=\"Uniform\">\n    <Time Value=\"%.9g\"/>\n", (int)s, (double)tN[2 * s]);
    WriteVertices(out, f, N, h5, (PetscBool)!one);
    fprintf(f, "    <Geometry GeometryType=\"%s\">\n     <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/x</DataItem>\n    </Geometry>\n", D == 3 ? "XYZ" : "XY", (int)N, (int)D, h5);
    fprintf(f, "    <Attribute Name=\"id\" Center=\"Node\"><DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/id</DataItem></Attribute>\n", (int)N, (int)sizeof(PetscInt), h5);
    fprintf(f, "    <Attribute Name=\"kind\" Center=\"Node\"><DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/kind</DataItem></Attribute>\n", (int)N, (int)sizeof(PetscInt), h5);
    for (PetscInt k = 0; k < nfields; k++) WriteAttribute(f, out->phys->P, fields[k], N, h5);
    fprintf(f, "   </Grid>\n");
  }
  fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
  fclose(f);
  if (rename(tmp, path)) err = errno;
  PetscCall(RootCheck(out, err, xmf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOWriteXDMF(Output *out)
{
  PetscFunctionBeginUser;
  PetscCall(WriteXDMF(out, "particles.xmf", out->nsnap, NULL, out->snaps));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOWriteXDMFOne(Output *out, const char *xmf, const char *h5, PetscReal t, PetscInt N)
{
  const PetscReal tN[2] = {t, (PetscReal)N};
  PetscFunctionBeginUser;
  PetscCall(WriteXDMF(out, xmf, 1, h5, tN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSnapshot(Output *out)
{
  char path[PETSC_MAX_PATH_LEN];
  PetscReal bytes;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "particles_%05" PetscInt_FMT ".h5", out->nsnap));
  PetscCall(IOSpaceSnapshot(out, &bytes));
  PetscCall(IOSpaceReserve(out, path, bytes, &ok));
  if (!ok) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogStagePush(out->stage));
  if (!out->phys->isph) { /* WCSPH: the pressure of the stored density, by the equation of state (Eq. 20) */
    Particles        P   = out->phys->P;
    const PetscReal *rho = PField(P, FIELD_RHO);
    PetscReal       *p   = PField(P, FIELD_P);
    for (PetscInt a = 0; a < P->n + P->ng; a++)
      if (KindIsFluid(P->kind[a])) p[a] = EOSPressure(&out->phys->fl, rho[a]);
  }
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/particles_%05" PetscInt_FMT ".h5", out->dir, out->nsnap));
  PetscCall(IOSpacePushWrite(path));
  PetscCall(IOWriteParticles(out, path));
  PetscCall(IOSpacePopWrite());
  if (out->nsnap >= out->snap_cap) {
    PetscReal *t;
    out->snap_cap = 2 * out->snap_cap + 16;
    PetscCall(PetscMalloc1(2 * out->snap_cap, &t));
    if (out->nsnap) PetscCall(PetscArraycpy(t, out->snaps, 2 * out->nsnap));
    PetscCall(PetscFree(out->snaps));
    out->snaps = t;
  }
  out->snaps[2 * out->nsnap]     = out->phys->t;
  out->snaps[2 * out->nsnap + 1] = (PetscReal)out->phys->nb->nparticles;
  out->nsnap++;
  PetscCall(WriteXDMF(out, "particles.xmf", out->nsnap, NULL, out->snaps));
  out->next_snap = OutputNextTime(out->next_snap, out->snap_interval, out->phys->t + 1e-12 * out->t_end);
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOProbes(Output *out)
{
  PetscReal vals[OUTPUT_MAX_PROBES];
  PetscInt  ncol = 1 + out->scene.nprobes;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(out->stage));
  PetscCall(out->scene.probe(out->scene.ctx, vals));
  for (PetscInt k = 0; k < out->scene.nprobes; k++) /* the state is finite (guard.h); a probe may still not be */
    if (PetscIsInfOrNanReal(vals[k])) PetscCall(PetscPrintf(out->comm, "sphfsi: warning: probe %s is %g at t = %g (written so to probes.csv)\n", out->scene.probe_names[k], (double)vals[k], (double)out->phys->t));
  if (!out->rank) {
    PetscReal *row;
    if (out->nprobe_rows == out->cap_probe_rows) {
      PetscReal *rows;
      out->cap_probe_rows = 2 * out->cap_probe_rows + 256;
      PetscCall(PetscMalloc1(out->cap_probe_rows * ncol, &rows));
      if (out->nprobe_rows) PetscCall(PetscArraycpy(rows, out->probe_rows, out->nprobe_rows * ncol));
      PetscCall(PetscFree(out->probe_rows));
      out->probe_rows = rows;
    }
    row    = out->probe_rows + out->nprobe_rows * ncol;
    row[0] = out->phys->t;
    PetscCall(PetscArraycpy(row + 1, vals, out->scene.nprobes));
  }
  out->nprobe_rows++;
  if (out->probe_interval > 0)
    out->next_probe = OutputNextTime(out->next_probe, out->probe_interval, out->phys->t + 1e-12 * out->t_end);
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A JSON number, or null when it is not finite (JSON has no NaN). */
static void JsonReal(FILE *f, const char *key, PetscReal v)
{
  if (PetscIsInfOrNanReal(v)) fprintf(f, "  \"%s\": null,\n", key);
  else fprintf(f, "  \"%s\": %.9g,\n", key, (double)v);
}

/* The scenes print their errors with %g: write s to f with every value that is not finite (nan,
 * -nan, inf, -inf after ": ", ", " or "[", before ",", "]", "}" or the end) written null. */
static void JsonPutsFinite(FILE *f, const char *s)
{
  for (const char *c = s; *c; c++) {
    const char *v, *e;
    fputc(*c, f);
    if (*c == '[') v = c + 1;
    else if ((*c == ':' || *c == ',') && c[1] == ' ') v = c + 2;
    else continue;
    e = v + (*v == '-');
    if ((strncmp(e, "nan", 3) && strncmp(e, "inf", 3)) || (e[3] && e[3] != ',' && e[3] != ']' && e[3] != '}')) continue;
    if (v == c + 2) fputc(' ', f);
    fputs("null", f);
    c = e + 2; /* the loop's c++ steps past the token */
  }
}

static void JsonString(FILE *f, const char *key, const char *v)
{
  fprintf(f, "  \"%s\": \"", key);
  for (const char *c = v; *c; c++) {
    if (*c == '"' || *c == '\\') fputc('\\', f);
    if (*c == '\n') fputs("\\n", f);
    else if ((unsigned char)*c >= 32) fputc(*c, f);
  }
  fprintf(f, "\",\n");
}

/* Peak resident memory of this process in bytes (getrusage: kB on Linux); 0 when unknown. */
static double PeakResidentBytes(void)
{
  struct rusage ru;
  return getrusage(RUSAGE_SELF, &ru) ? 0.0 : 1024.0 * (double)ru.ru_maxrss;
}

/* Which physics modules this run built (a scene allocates only what it needs). */
static void JsonModules(FILE *f, const Physics *ph)
{
  fprintf(f, "  \"modules\": [");
  if (ph->has_fluid) fprintf(f, "\"%s\"", FluidSchemes[ph->fluid]);
  if (ph->isph) fprintf(f, ", \"pressure_matrix\"");
  if (ph->solid) fprintf(f, "%s\"solid\"", ph->has_fluid ? ", " : "");
  if (ph->solid && ph->isph && ph->solid->implicit) fprintf(f, ", \"implicit_interface\"");
  fprintf(f, "],\n  \"pressure_matrix\": %s,\n", ph->isph ? "true" : "false");
}

PetscErrorCode IOSummary(Output *out, const char *status, const char *message, PetscBool with_errors)
{
  char            path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE           *f = NULL;
  int             err = 0;
  double          rss = PeakResidentBytes(), rss_sum = 0;
  const Physics  *ph   = out->phys;
  const PetscReal wall = *out->run.wall_used + *out->run.wall_loop; /* this run's loop and those before a restart */
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Reduce(&rss, &rss_sum, 1, MPI_DOUBLE, MPI_SUM, 0, out->comm));
  if (!out->rank) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/summary.json", out->dir));
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
    if (!(f = fopen(tmp, "w"))) err = errno;
  }
  PetscCall(RootCheck(out, err, "summary.json"));
  if (!out->rank) {
    fprintf(f, "{\n  \"version\": \"%s\",\n  \"commit\": \"%s\",\n", SPHFSIVersion(), SPHFSICommit());
    fprintf(f, "  \"case\": \"%s\",\n  \"dim\": %d,\n  \"fluid\": \"%s\",\n  \"ranks\": %d,\n", out->scene.name, (int)ph->dim, ph->has_fluid ? FluidSchemes[ph->fluid] : "none", out->size);
    JsonString(f, "status", out->fault.set ? "io_error" : status);
    if (out->fault.set) JsonString(f, "message", out->fault.msg);
    else if (message) JsonString(f, "message", message);
    if (out->restart[0]) JsonString(f, "restarted_from", out->restart);
    fprintf(f, "  \"checkpoints\": %d,\n", (int)out->nckpt);
    if (out->ckpt_t >= 0) JsonReal(f, "checkpoint_t", out->ckpt_t); /* what checkpoint.h5 holds now */
    else fprintf(f, "  \"checkpoint_t\": null,\n");
    fprintf(f, "  \"particles\": %d,\n  \"steps\": %d,\n", (int)ph->nb->nparticles, (int)ph->step);
    JsonReal(f, "t_end", ph->t);
    JsonReal(f, "dx", ph->dx);
    JsonReal(f, "wall_s", wall);
    JsonReal(f, "particle_steps_per_s", *out->run.particle_steps / PetscMax(wall, 1e-9));
    if (ph->isph && ph->isph->ppe->nsolve) fprintf(f, "  \"ksp_its_mean\": %.4g,\n  \"ksp_its_max\": %d,\n", (double)(ph->isph->ppe->its_sum / ph->isph->ppe->nsolve), (int)ph->isph->ppe->its_max);
    else fprintf(f, "  \"ksp_its_mean\": null,\n  \"ksp_its_max\": null,\n");
    JsonReal(f, "mass_rel_drift", *out->run.mass0 > 0 ? (*out->run.mass - *out->run.mass0) / *out->run.mass0 : 0);
    if (ph->solid) fprintf(f, "  \"c0_solid\": %.6g,\n  \"solid_substeps_max\": %d,\n  \"solid_formulation\": \"%s\",\n  \"solid_law\": \"%s\",\n", (double)ph->sl.c0, (int)ph->solid->nsub_max, SolidFormulations[ph->solid->formulation], ph->solid->formulation == SOLID_TOTAL ? SolidLaws[ph->sl.law] : "hypo-elastic");
    if (ph->nb->skin > 0) fprintf(f, "  \"neighbour_skin_dx\": %.6g,\n  \"neighbour_rebuilds\": %d,\n", (double)(ph->nb->skin / ph->dx), (int)ph->nb->nrebuild); /* this run's (-wcsph_skin) */
    if (ph->has_fluid) fprintf(f, "  \"c0\": %.6g,\n", (double)ph->fl.c0);
    else fprintf(f, "  \"c0\": null,\n");
    JsonModules(f, ph);
    fprintf(f, "  \"bytes_per_particle\": %d,\n  \"repartitions\": %d,\n", (int)ParticlesBytesPerParticle(ph->P), (int)ph->decomp->nrepartition);
    fprintf(f, "  \"ranks_empty_max\": %d,\n  \"ranks_without_fluid_max\": %d,\n", (int)ph->decomp->empty_max, (int)ph->decomp->nofluid_max); /* at the imbalance checks of this run */
    JsonReal(f, "peak_resident_bytes", rss_sum); /* all ranks, MPI/PETSc/hypre included */
    JsonReal(f, "peak_resident_bytes_per_particle", ph->nb->nparticles > 0 ? rss_sum / ph->nb->nparticles : 0);
    fprintf(f, "  \"fields\": [");
    for (PetscInt k = 0, first = 1; k < FIELD_COUNT; k++)
      if (ph->P->f[k].on) { fprintf(f, "%s\"%s\"", first ? "" : ", ", ph->P->f[k].name); first = 0; }
    fprintf(f, "],\n  \"errors\": {");
  }
  if (out->scene.errors && with_errors) { /* collective; rank 0 writes through a memory stream, made valid JSON */
    char  *buf = NULL;
    size_t len = 0;
    FILE  *mem = NULL;
    if (!out->rank) {
      mem = open_memstream(&buf, &len);
      if (!mem) err = errno;
    }
    PetscCall(out->scene.errors(out->scene.ctx, mem));
    if (mem) {
      fclose(mem);
      JsonPutsFinite(f, buf);
      free(buf);
    }
  }
  if (!out->rank) { /* the reference files the errors above lacked (filled by the scene's errors) */
    fprintf(f, "},\n  \"reference_missing\": [%s]\n}\n", out->refdata->missing ? out->refdata->missing : "");
    fclose(f);
    if (rename(tmp, path)) err = errno;
  }
  PetscCall(RootCheck(out, err, "summary.json"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
