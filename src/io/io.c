#include "base/version.h"
#include "io/io.h"
#include "scenes/scene.h"
#include "fluid/isph.h"
#include "solid/solid.h"
#include "run/guard.h"
#include "io/io_space.h"
#include "io/h5.h"
#include <unistd.h>
#include <petscviewerhdf5.h>
#include <sys/stat.h>
#include <errno.h>
#include <sys/resource.h>

/* A failure on rank 0 alone (files it writes) becomes an I/O fault of every rank (io_space.h), not a
 * hang: the run ends with one line and SIM_EXIT_IO. */
static PetscErrorCode RootCheck(Sim sim, int err, const char *what)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, sim->comm));
  if (err) PetscCall(IOFault(&sim->out, "%s writing %s/%s", strerror(err), sim->out.dir, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IORenameOnRoot(Sim sim, const char *tmp, const char *path)
{
  PetscFunctionBeginUser;
  PetscCall(RootCheck(sim, sim->rank || !rename(tmp, path) ? 0 : errno, path));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* probes.csv from every row so far, under a temporary name renamed when complete: the file is
 * always whole, and after a restart it holds the rows up to the checkpoint and on from there. */
PetscErrorCode IOWriteProbes(Sim sim)
{
  char     path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE    *f;
  int      err = 0;
  PetscInt ncol = 1 + sim->scene->nprobes;
  PetscFunctionBeginUser;
  if (sim->rank) PetscFunctionReturn(RootCheck(sim, 0, "probes.csv"));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/probes.csv", sim->out.dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  if (!(f = fopen(tmp, "w"))) PetscFunctionReturn(RootCheck(sim, errno, "probes.csv"));
  fprintf(f, "t");
  for (PetscInt k = 0; k < sim->scene->nprobes; k++) fprintf(f, ",%s", sim->scene->probe_names[k]);
  fprintf(f, "\n");
  for (PetscInt r = 0; r < sim->out.nprobe_rows; r++) {
    const PetscReal *row = sim->out.probe_rows + r * ncol;
    for (PetscInt k = 0; k < ncol; k++) fprintf(f, k ? ",%.9g" : "%.9g", (double)row[k]);
    fprintf(f, "\n");
  }
  if (ferror(f)) err = EIO;
  if (fclose(f) && !err) err = errno;
  if (!err && rename(tmp, path)) err = errno;
  PetscCall(RootCheck(sim, err, "probes.csv"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSetUp(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(IOWriteProbes(sim)); /* the header, or the restarted run's rows */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOFinalize(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(sim->out.probe_rows));
  sim->out.nprobe_rows = sim->out.cap_probe_rows = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The attributes that make a snapshot the input of -case file (src/scenes/particles_file.c): the
 * spacing dx and the computational box, domain = x0,y0[,z0],x1,y1[,z1]. */
static PetscErrorCode WriteDomain(PetscViewer v, Sim sim)
{
  hid_t     file, space, attr;
  hsize_t   n = 2 * sim->phys.dim;
  PetscReal dom[6];
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "dx", PETSC_REAL, &sim->phys.dx));
  for (PetscInt d = 0; d < sim->phys.dim; d++) { dom[d] = sim->dom_lo[d]; dom[sim->phys.dim + d] = sim->dom_hi[d]; }
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  PetscCheck((space = H5Screate_simple(1, &n, NULL)) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not make the domain attribute's space");
  PetscCheck((attr = H5Acreate2(file, "domain", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not create the domain attribute");
  PetscCheck(H5Awrite(attr, H5T_NATIVE_DOUBLE, dom) >= 0 && H5Aclose(attr) >= 0 && H5Sclose(space) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 could not write the domain attribute");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective: one file, every owned particle's id, kind and the snapshot's fields (the field table,
 * particles.h); written under a temporary name and renamed when complete. */
PetscErrorCode IOWriteParticles(Sim sim, const char *path)
{
  PetscViewer v;
  char        tmp[PETSC_MAX_PATH_LEN];
  Particles   P = sim->P;
  FieldId     out[FIELD_COUNT];
  PetscInt    nout = ParticlesSnapshotFields(P, out);

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  PetscCall(PetscViewerHDF5Open(sim->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(DatasetWriteInts(v, sim->comm, "id", P->n, P->id));
  PetscCall(DatasetWriteInts(v, sim->comm, "kind", P->n, P->kind));
  if (sim->nbhd.nparticles != sim->next_id) { /* ids no longer 0..N-1 (outflow): the points' indices for the XDMF's topology */
    PetscInt *vertex, first = 0, n = P->n;
    PetscCallMPI(MPI_Exscan(&n, &first, 1, MPIU_INT, MPI_SUM, sim->comm));
    if (!sim->rank) first = 0;
    PetscCall(PetscMalloc1(n, &vertex));
    for (PetscInt i = 0; i < n; i++) vertex[i] = first + i;
    PetscCall(DatasetWriteInts(v, sim->comm, "vertex", n, vertex));
    PetscCall(PetscFree(vertex));
  }
  for (PetscInt k = 0; k < nout; k++) PetscCall(DatasetWriteReals(v, sim->comm, P->f[out[k]].name, P->n, P->f[out[k]].width, P->f[out[k]].a));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "time", PETSC_REAL, &sim->phys.t));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "step", PETSC_INT, &sim->phys.step));
  PetscCall(WriteDomain(v, sim));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(IORenameOnRoot(sim, tmp, path));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A grid's Polyvertex topology with its connectivity, the points' indices: ParaView's default
 * reader (Xdmf3) makes no cell without one, and then draws nothing (the legacy reader numbers the
 * points itself).  The ids are 0..next_id-1 (the scene hands them out in turn), so while no
 * particle has left (N == next_id) the file's own `id` lists every point once, in some order; once
 * the outflow has removed some, a snapshot carries the indices 0..N-1 as `vertex` (IOWriteParticles),
 * and a single file (last_good.h5, a checkpoint) has them here as text (~6 bytes a particle, once). */
static void WriteVertices(Sim sim, FILE *f, PetscInt N, const char *h5, PetscBool snapshot)
{
  fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\">\n", (int)N);
  if (N == sim->next_id || snapshot) fprintf(f, "     <DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/%s</DataItem>\n", (int)N, (int)sizeof(PetscInt), h5, N == sim->next_id ? "id" : "vertex");
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
static PetscErrorCode WriteXDMF(Sim sim, const char *xmf, PetscInt n, const char *one, const PetscReal *tN)
{
  char           path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE          *f;
  const PetscInt D = sim->phys.dim;
  FieldId        out[FIELD_COUNT];
  const PetscInt nout = ParticlesSnapshotFields(sim->P, out);

  PetscFunctionBeginUser;
  int err = 0;
  if (sim->rank) PetscFunctionReturn(RootCheck(sim, 0, xmf));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", sim->out.dir, xmf));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  if (!(f = fopen(tmp, "w"))) PetscFunctionReturn(RootCheck(sim, errno, xmf));
  fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt s = 0; s < n; s++) {
    char           h5[PETSC_MAX_PATH_LEN];
    const PetscInt N = (PetscInt)tN[2 * s + 1];
    if (N < 0) continue; /* a snapshot of a restarted run that is not in this directory (outdir.c) */
    if (one) PetscCall(PetscStrncpy(h5, one, sizeof(h5)));
    else PetscCall(PetscSNPrintf(h5, sizeof(h5), "particles_%05" PetscInt_FMT ".h5", s));
    fprintf(f, "   <Grid Name=\"step%05d\" GridType=\"Uniform\">\n    <Time Value=\"%.9g\"/>\n", (int)s, (double)tN[2 * s]);
    WriteVertices(sim, f, N, h5, (PetscBool)!one);
    fprintf(f, "    <Geometry GeometryType=\"%s\">\n     <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/x</DataItem>\n    </Geometry>\n", D == 3 ? "XYZ" : "XY", (int)N, (int)D, h5);
    fprintf(f, "    <Attribute Name=\"id\" Center=\"Node\"><DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/id</DataItem></Attribute>\n", (int)N, (int)sizeof(PetscInt), h5);
    fprintf(f, "    <Attribute Name=\"kind\" Center=\"Node\"><DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/kind</DataItem></Attribute>\n", (int)N, (int)sizeof(PetscInt), h5);
    for (PetscInt k = 0; k < nout; k++) WriteAttribute(f, sim->P, out[k], N, h5);
    fprintf(f, "   </Grid>\n");
  }
  fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
  fclose(f);
  if (rename(tmp, path)) err = errno;
  PetscCall(RootCheck(sim, err, xmf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOWriteXDMF(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(WriteXDMF(sim, "particles.xmf", sim->out.nsnap, NULL, sim->out.snaps));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOWriteXDMFOne(Sim sim, const char *xmf, const char *h5, PetscReal t, PetscInt N)
{
  const PetscReal tN[2] = {t, (PetscReal)N};
  PetscFunctionBeginUser;
  PetscCall(WriteXDMF(sim, xmf, 1, h5, tN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSnapshot(Sim sim)
{
  char path[PETSC_MAX_PATH_LEN];
  PetscReal bytes;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "particles_%05" PetscInt_FMT ".h5", sim->out.nsnap));
  PetscCall(IOSpaceSnapshot(&sim->out, &bytes));
  PetscCall(IOSpaceReserve(&sim->out, path, bytes, &ok));
  if (!ok) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogStagePush(sim->stage[STAGE_OUTPUT]));
  if (!sim->phys.isph) { /* WCSPH: the pressure of the stored density, by the equation of state (Eq. 20) */
    const PetscReal *rho = PField(sim->P, FIELD_RHO);
    PetscReal       *p   = PField(sim->P, FIELD_P);
    for (PetscInt a = 0; a < sim->P->n + sim->P->ng; a++)
      if (KindIsFluid(sim->P->kind[a])) p[a] = EOSPressure(&sim->phys.fl, rho[a]);
  }
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/particles_%05" PetscInt_FMT ".h5", sim->out.dir, sim->out.nsnap));
  PetscCall(IOSpacePushWrite(path));
  PetscCall(IOWriteParticles(sim, path));
  PetscCall(IOSpacePopWrite());
  if (sim->out.nsnap >= sim->out.snap_cap) {
    PetscReal *t;
    sim->out.snap_cap = 2 * sim->out.snap_cap + 16;
    PetscCall(PetscMalloc1(2 * sim->out.snap_cap, &t));
    if (sim->out.nsnap) PetscCall(PetscArraycpy(t, sim->out.snaps, 2 * sim->out.nsnap));
    PetscCall(PetscFree(sim->out.snaps));
    sim->out.snaps = t;
  }
  sim->out.snaps[2 * sim->out.nsnap]     = sim->phys.t;
  sim->out.snaps[2 * sim->out.nsnap + 1] = (PetscReal)sim->nbhd.nparticles;
  sim->out.nsnap++;
  PetscCall(WriteXDMF(sim, "particles.xmf", sim->out.nsnap, NULL, sim->out.snaps));
  while (sim->out.next_snap <= sim->phys.t + 1e-12 * sim->t_end) sim->out.next_snap += sim->out.snap_interval;
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOProbes(Sim sim)
{
  PetscReal vals[SCENE_MAX_PROBES];
  PetscInt  ncol = 1 + sim->scene->nprobes;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim->stage[STAGE_OUTPUT]));
  PetscCall(sim->scene->probe(sim, vals));
  for (PetscInt k = 0; k < sim->scene->nprobes; k++) /* the state is finite (guard.h); a probe may still not be */
    if (PetscIsInfOrNanReal(vals[k])) PetscCall(PetscPrintf(sim->comm, "sphfsi: warning: probe %s is %g at t = %g (written so to probes.csv)\n", sim->scene->probe_names[k], (double)vals[k], (double)sim->phys.t));
  if (!sim->rank) {
    PetscReal *row;
    if (sim->out.nprobe_rows == sim->out.cap_probe_rows) {
      PetscReal *rows;
      sim->out.cap_probe_rows = 2 * sim->out.cap_probe_rows + 256;
      PetscCall(PetscMalloc1(sim->out.cap_probe_rows * ncol, &rows));
      if (sim->out.nprobe_rows) PetscCall(PetscArraycpy(rows, sim->out.probe_rows, sim->out.nprobe_rows * ncol));
      PetscCall(PetscFree(sim->out.probe_rows));
      sim->out.probe_rows = rows;
    }
    row    = sim->out.probe_rows + sim->out.nprobe_rows * ncol;
    row[0] = sim->phys.t;
    PetscCall(PetscArraycpy(row + 1, vals, sim->scene->nprobes));
  }
  sim->out.nprobe_rows++;
  if (sim->out.probe_interval > 0)
    while (sim->out.next_probe <= sim->phys.t + 1e-12 * sim->t_end) sim->out.next_probe += sim->out.probe_interval;
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
static void JsonModules(FILE *f, Sim sim)
{
  fprintf(f, "  \"modules\": [");
  if (sim->phys.has_fluid) fprintf(f, "\"%s\"", FluidSchemes[sim->phys.fluid]);
  if (sim->phys.isph) fprintf(f, ", \"pressure_matrix\"");
  if (sim->phys.solid) fprintf(f, "%s\"solid\"", sim->phys.has_fluid ? ", " : "");
  if (sim->phys.solid && sim->phys.isph && sim->phys.solid->implicit) fprintf(f, ", \"implicit_interface\"");
  fprintf(f, "],\n  \"pressure_matrix\": %s,\n", sim->phys.isph ? "true" : "false");
}

PetscErrorCode IOSummary(Sim sim)
{
  char   path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE  *f = NULL;
  int    err = 0;
  double rss = PeakResidentBytes(), rss_sum = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Reduce(&rss, &rss_sum, 1, MPI_DOUBLE, MPI_SUM, 0, sim->comm));
  if (!sim->rank) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/summary.json", sim->out.dir));
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
    if (!(f = fopen(tmp, "w"))) err = errno;
  }
  PetscCall(RootCheck(sim, err, "summary.json"));
  if (!sim->rank) {
    fprintf(f, "{\n  \"version\": \"%s\",\n  \"commit\": \"%s\",\n", SphfsiVersion(), SphfsiCommit());
    fprintf(f, "  \"case\": \"%s\",\n  \"dim\": %d,\n  \"fluid\": \"%s\",\n  \"ranks\": %d,\n", sim->scene->name, (int)sim->phys.dim, sim->phys.has_fluid ? FluidSchemes[sim->phys.fluid] : "none", sim->size);
    JsonString(f, "status", sim->out.fault.set ? "io_error" : (const char *[]){"completed", "stopped", "fault", "io_error"}[sim->guard->state]);
    if (sim->out.fault.set) JsonString(f, "message", sim->out.fault.msg);
    else if (sim->guard->state) JsonString(f, "message", sim->guard->msg);
    if (sim->out.restart[0]) JsonString(f, "restarted_from", sim->out.restart);
    fprintf(f, "  \"checkpoints\": %d,\n", (int)sim->out.nckpt);
    if (sim->out.ckpt_t >= 0) JsonReal(f, "checkpoint_t", sim->out.ckpt_t); /* what checkpoint.h5 holds now */
    else fprintf(f, "  \"checkpoint_t\": null,\n");
    fprintf(f, "  \"particles\": %d,\n  \"steps\": %d,\n", (int)sim->nbhd.nparticles, (int)sim->phys.step);
    JsonReal(f, "t_end", sim->phys.t);
    JsonReal(f, "dx", sim->phys.dx);
    JsonReal(f, "wall_s", sim->wall_used + sim->wall_loop);
    JsonReal(f, "particle_steps_per_s", sim->particle_steps / PetscMax(sim->wall_used + sim->wall_loop, 1e-9));
    if (sim->phys.isph && sim->phys.isph->ppe->nsolve) fprintf(f, "  \"ksp_its_mean\": %.4g,\n  \"ksp_its_max\": %d,\n", (double)(sim->phys.isph->ppe->its_sum / sim->phys.isph->ppe->nsolve), (int)sim->phys.isph->ppe->its_max);
    else fprintf(f, "  \"ksp_its_mean\": null,\n  \"ksp_its_max\": null,\n");
    JsonReal(f, "mass_rel_drift", sim->mass0 > 0 ? (sim->mass - sim->mass0) / sim->mass0 : 0);
    if (sim->phys.solid) fprintf(f, "  \"c0_solid\": %.6g,\n  \"solid_substeps_max\": %d,\n  \"solid_formulation\": \"%s\",\n", (double)sim->phys.sl.c0, (int)sim->phys.solid->nsub_max, SolidFormulations[sim->phys.solid->formulation]);
    if (sim->nbhd.skin > 0) fprintf(f, "  \"neighbour_skin_dx\": %.6g,\n  \"neighbour_rebuilds\": %d,\n", (double)(sim->nbhd.skin / sim->phys.dx), (int)sim->nbhd.nrebuild); /* this run's (-wcsph_skin) */
    if (sim->phys.has_fluid) fprintf(f, "  \"c0\": %.6g,\n", (double)sim->phys.fl.c0);
    else fprintf(f, "  \"c0\": null,\n");
    JsonModules(f, sim);
    fprintf(f, "  \"bytes_per_particle\": %d,\n  \"repartitions\": %d,\n", (int)ParticlesBytesPerParticle(sim->P), (int)sim->decomp->nrepartition);
    fprintf(f, "  \"ranks_empty_max\": %d,\n  \"ranks_without_fluid_max\": %d,\n", (int)sim->decomp->empty_max, (int)sim->decomp->nofluid_max); /* at the imbalance checks of this run */
    JsonReal(f, "peak_resident_bytes", rss_sum); /* all ranks, MPI/PETSc/hypre included */
    JsonReal(f, "peak_resident_bytes_per_particle", sim->nbhd.nparticles > 0 ? rss_sum / sim->nbhd.nparticles : 0);
    fprintf(f, "  \"fields\": [");
    for (PetscInt k = 0, first = 1; k < FIELD_COUNT; k++)
      if (sim->P->f[k].on) { fprintf(f, "%s\"%s\"", first ? "" : ", ", sim->P->f[k].name); first = 0; }
    fprintf(f, "],\n  \"errors\": {");
  }
  if (sim->scene->errors && sim->ready) { /* collective; rank 0 writes through a memory stream, made valid JSON */
    char  *buf = NULL;
    size_t len = 0;
    FILE  *mem = NULL;
    if (!sim->rank) {
      mem = open_memstream(&buf, &len);
      if (!mem) err = errno;
    }
    PetscCall(sim->scene->errors(sim, mem));
    if (mem) {
      fclose(mem);
      JsonPutsFinite(f, buf);
      free(buf);
    }
  }
  if (!sim->rank) { /* the reference files the errors above lacked (filled by the scene's errors) */
    fprintf(f, "},\n  \"reference_missing\": [%s]\n}\n", sim->refdata.missing ? sim->refdata.missing : "");
    fclose(f);
    if (rename(tmp, path)) err = errno;
  }
  PetscCall(RootCheck(sim, err, "summary.json"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
