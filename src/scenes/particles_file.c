/* A case from a file of particles (-case file): positions and kinds in an HDF5 file that a user writes,
 * e.g. with h5py (tools/particles_file.py), or a snapshot of an earlier run (particles_NNNNN.h5),
 * which has the same schema.  docs/geometry.md gives the schema:
 *   x     N x D float   positions (D = 2 or 3)                                        required
 *   kind  N int         0 fluid, 1 wall, 2 dummy (wall rows behind the first), 3 solid, 4 clamp   required
 *   id    N int         global ids, each of 0..N-1 once                    default: the row index
 *   m     N float       mass                                    default: rho0 of its medium dx^D
 *   h     N float       smoothing length                                   default: h_factor dx
 *   rho   N float       density         default: rho0 (the fluid at rest: hydrostatic, -file_hydrostatic)
 *   v     N x D float   velocity                                                   default: 0
 *   p     N float       pressure                                                   default: 0 (or hydrostatic)
 * and the attributes of "/" (each also an option, which wins): dx (-dx), domain (-domain: x0,y0,x1,y1 or
 * x0,y0,z0,x1,y1,z1).  Every rank reads a contiguous share of the rows; migration then gives each particle
 * to its owner.  Probes: front_x, v_max (as -case boxes). */
#include <sphfsi.h>
#include <petscviewerhdf5.h>

/* An HDF5 call that returns a negative value on failure: the error names the file and the call. */
#define H5Try(call, path) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "%s: HDF5 failed in %s", path, #call); \
  } while (0)

typedef struct {
  char       path[PETSC_MAX_PATH_LEN];
  PetscInt   n, N, first;                    /* this rank's rows [first, first + n) of N */
  PetscInt  *id, *kind;                      /* this rank's rows */
  PetscReal *x, *m, *h, *rho, *v, *p;        /* NULL when the file has no such dataset */
  PetscInt64 count[KIND_COUNT];              /* particles of each kind in the file */
  PetscBool  hydrostatic;
} ParticlesFile;

static PetscErrorCode FreeRows(ParticlesFile *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c->x));
  PetscCall(PetscFree(c->kind));
  PetscCall(PetscFree(c->id));
  PetscCall(PetscFree(c->m));
  PetscCall(PetscFree(c->h));
  PetscCall(PetscFree(c->rho));
  PetscCall(PetscFree(c->v));
  PetscCall(PetscFree(c->p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The dimensions of a dataset, or *rank = 0 when the file has none of that name. */
static PetscErrorCode DatasetShape(hid_t file, const char *path, const char *name, int *rank, hsize_t dims[])
{
  hid_t ds, sp;
  PetscFunctionBeginUser;
  *rank = 0;
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  H5Try(ds = H5Dopen2(file, name, H5P_DEFAULT), path);
  H5Try(sp = H5Dget_space(ds), path);
  *rank = H5Sget_simple_extent_ndims(sp);
  PetscCheck(*rank >= 1 && *rank <= 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: dataset %s has %d dimensions: a particle field has 1 (N) or 2 (N x D)", path, name, *rank);
  H5Try(H5Sget_simple_extent_dims(sp, dims, NULL), path);
  H5Try(H5Sclose(sp), path);
  H5Try(H5Dclose(ds), path);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rows [first, first + n) of dataset `name` (width values a row) into a new array (NULL when absent
 * and not required); the file's number type converted to `type` by HDF5. */
static PetscErrorCode ReadRows(MPI_Comm comm, hid_t file, const char *path, const char *name, PetscInt N, PetscInt width, PetscInt first, PetscInt n, hid_t type, size_t size, PetscBool required, void **out)
{
  int     rank;
  hsize_t dims[2], start[2] = {(hsize_t)first, 0}, count[2] = {(hsize_t)n, (hsize_t)width};
  hid_t   ds, fsp, msp;
  PetscFunctionBeginUser;
  *out = NULL;
  PetscCall(DatasetShape(file, path, name, &rank, dims));
  PetscCheck(rank || !required, comm, PETSC_ERR_FILE_UNEXPECTED, "%s has no dataset %s (the particles' %s): see docs/geometry.md for the schema", path, name, !strcmp(name, "x") ? "positions, N x D" : "kinds");
  if (!rank) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(dims[0] == (hsize_t)N && (width == 1 ? rank == 1 || dims[1] == 1 : rank == 2 && dims[1] == (hsize_t)width), comm, PETSC_ERR_FILE_UNEXPECTED, "%s: dataset %s is %d%s%d, not %d x %d (N particles x its width)", path, name, (int)dims[0], rank == 2 ? " x " : "", rank == 2 ? (int)dims[1] : 1, (int)N, (int)width);
  PetscCall(PetscMalloc(size * (size_t)(n * width + 1), out));
  H5Try(ds = H5Dopen2(file, name, H5P_DEFAULT), path);
  H5Try(fsp = H5Dget_space(ds), path);
  H5Try(H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, count, NULL), path);
  H5Try(msp = H5Screate_simple(rank, count, NULL), path);
  H5Try(H5Dread(ds, type, msp, fsp, H5P_DEFAULT, *out), path);
  H5Try(H5Sclose(msp), path);
  H5Try(H5Sclose(fsp), path);
  H5Try(H5Dclose(ds), path);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The file's dimension, size and this rank's rows, read; the options' dx and domain, else the file's. */
static PetscErrorCode ReadFile(Sim sim, ParticlesFile *c, PetscReal dom[], PetscBool dom_set)
{
  PetscViewer v;
  hid_t       file, itype;
  hsize_t     dims[2];
  int         rank;
  PetscMPIInt size, me;
  PetscBool   has;
  void       *buf;
  PetscInt    D;
  PetscFunctionBeginUser;
  {
    PetscBool exists;
    PetscCall(PetscTestFile(c->path, 'r', &exists));
    PetscCheck(exists, SimComm(sim), PETSC_ERR_FILE_OPEN, "-particles_file %s: no such file (or not readable)", c->path);
  }
  PetscCall(PetscViewerHDF5Open(SimComm(sim), c->path, FILE_MODE_READ, &v));
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  PetscCall(DatasetShape(file, c->path, "x", &rank, dims));
  PetscCheck(rank == 2 && (dims[1] == 2 || dims[1] == 3), SimComm(sim), PETSC_ERR_FILE_UNEXPECTED, "%s: dataset x (the positions) must be N x 2 or N x 3%s", c->path, rank ? "" : ", and the file has none");
  D = (PetscInt)dims[1];
  PetscCall(SimSetDim(sim, D));
  c->N     = (PetscInt)dims[0];
  PetscCheck(c->N > 0, SimComm(sim), PETSC_ERR_FILE_UNEXPECTED, "%s holds no particles", c->path);
  PetscCallMPI(MPI_Comm_size(SimComm(sim), &size));
  PetscCallMPI(MPI_Comm_rank(SimComm(sim), &me));
  c->n     = c->N / size + (me < c->N % size);
  c->first = me * (c->N / size) + PetscMin(me, c->N % size);
  PetscCall(PetscDataTypeToHDF5DataType(PETSC_INT, &itype));
  PetscCall(ReadRows(SimComm(sim), file, c->path, "x", c->N, D, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_TRUE, &buf)); c->x = (PetscReal *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "kind", c->N, 1, c->first, c->n, itype, sizeof(PetscInt), PETSC_TRUE, &buf)); c->kind = (PetscInt *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "id", c->N, 1, c->first, c->n, itype, sizeof(PetscInt), PETSC_FALSE, &buf)); c->id = (PetscInt *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "m", c->N, 1, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_FALSE, &buf)); c->m = (PetscReal *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "h", c->N, 1, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_FALSE, &buf)); c->h = (PetscReal *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "rho", c->N, 1, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_FALSE, &buf)); c->rho = (PetscReal *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "v", c->N, D, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_FALSE, &buf)); c->v = (PetscReal *)buf;
  PetscCall(ReadRows(SimComm(sim), file, c->path, "p", c->N, 1, c->first, c->n, H5T_NATIVE_DOUBLE, sizeof(PetscReal), PETSC_FALSE, &buf)); c->p = (PetscReal *)buf;
  if (SimSpacing(sim) <= 0) {
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "dx", &has));
    PetscCheck(has, SimComm(sim), PETSC_ERR_USER_INPUT, "%s has no attribute dx: give the particle spacing with -dx", c->path);
    PetscReal dx;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "dx", PETSC_REAL, NULL, &dx));
    PetscCall(SimSetSpacing(sim, dx));
  }
  if (!dom_set) {
    PetscInt n = 2 * D;
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "domain", &has));
    PetscCheck(has, SimComm(sim), PETSC_ERR_USER_INPUT, "%s has no attribute domain: give the computational box with -domain %s", c->path, D == 3 ? "x0,y0,z0,x1,y1,z1" : "x0,y0,x1,y1");
    {
      hid_t   at, sp;
      hssize_t len;
      H5Try(at = H5Aopen_by_name(file, "/", "domain", H5P_DEFAULT, H5P_DEFAULT), c->path);
      H5Try(sp = H5Aget_space(at), c->path);
      len = H5Sget_simple_extent_npoints(sp);
      PetscCheck(len == n, SimComm(sim), PETSC_ERR_FILE_UNEXPECTED, "%s: attribute domain has %d numbers, not %d (%s)", c->path, (int)len, (int)n, D == 3 ? "x0,y0,z0,x1,y1,z1" : "x0,y0,x1,y1");
      H5Try(H5Aread(at, H5T_NATIVE_DOUBLE, dom), c->path);
      H5Try(H5Sclose(sp), c->path);
      H5Try(H5Aclose(at), c->path);
    }
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Create(Sim sim)
{
  ParticlesFile *c;
  PetscReal      dom[6], top = -PETSC_MAX_REAL, low = PETSC_MAX_REAL, lo[3], hi[3];
  PetscInt       n, D, up, bad = -1;
  PetscBool      set, dom_set;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  PetscCall(SimSetSceneContext(sim, c));
  c->hydrostatic = PETSC_TRUE;
  n              = 6;
  PetscOptionsBegin(SimComm(sim), NULL, "Scene file: particles from an HDF5 file (docs/geometry.md)", "");
  PetscCall(PetscOptionsString("-particles_file", "HDF5 file of particles: datasets x (N x D), kind (N), optional id, m, h, rho, v, p; attributes dx, domain (a snapshot particles_NNNNN.h5 of a run is one)", "", c->path, c->path, sizeof(c->path), &set));
  PetscCall(PetscOptionsRealArray("-domain", "Computational box x0,y0,x1,y1 (3D: x0,y0,z0,x1,y1,z1) (m); default: the file's attribute domain", "", dom, &n, &dom_set));
  PetscCall(OptBool("-file_hydrostatic", "Fluid without a density in the file starts hydrostatic below its highest particle + dx/2 (else at rho0)", "", c->hydrostatic, &c->hydrostatic, NULL));
  PetscOptionsEnd();
  PetscCheck(set && c->path[0], SimComm(sim), PETSC_ERR_USER_INPUT, "Scene file needs -particles_file FILE.h5 (docs/geometry.md gives its schema)");
  PetscCall(ReadFile(sim, c, dom, dom_set));
  D  = SimDim(sim);
  up = D - 1;
  PetscCheck(!dom_set || n == 2 * D, SimComm(sim), PETSC_ERR_USER_INPUT, "-domain takes %d numbers in this %dD file, not %d", (int)(2 * D), (int)D, (int)n);
  for (PetscInt d = 0; d < D; d++) {
    PetscCall(SimSetDomain(sim, d, dom[d], dom[D + d]));
    PetscCheck(dom[D + d] > dom[d], SimComm(sim), PETSC_ERR_ARG_OUTOFRANGE, "The domain's high corner must exceed its low corner in every direction (-domain or the file's attribute)");
    lo[d] = PETSC_MAX_REAL; hi[d] = -PETSC_MAX_REAL;
  }
  if (D == 3) PetscCall(SimSetGravity(sim, SimGravity(sim)[0], 0, -9.81));
  for (PetscInt a = 0; a < c->n; a++) {
    const PetscInt k = c->kind[a];
    if (k < 0 || k >= KIND_COUNT) { bad = c->first + a; continue; }
    c->count[k]++;
    for (PetscInt d = 0; d < D; d++) { lo[d] = PetscMin(lo[d], c->x[D * a + d]); hi[d] = PetscMax(hi[d], c->x[D * a + d]); }
    if (KindIsFluid(k)) { top = PetscMax(top, c->x[D * a + up]); low = PetscMin(low, c->x[D * a + up]); }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, SimComm(sim)));
  PetscCheck(bad < 0, SimComm(sim), PETSC_ERR_FILE_UNEXPECTED, "%s: particle %d has a kind outside 0..4 (0 fluid, 1 wall, 2 dummy, 3 solid, 4 clamp)", c->path, (int)bad);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, c->count, KIND_COUNT, MPIU_INT64, MPI_SUM, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lo, D, MPIU_REAL, MPIU_MIN, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, hi, D, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &top, 1, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &low, 1, MPIU_REAL, MPIU_MIN, SimComm(sim)));
  for (PetscInt d = 0; d < D; d++) PetscCheck(lo[d] >= SimDomainLo(sim)[d] && hi[d] <= SimDomainHi(sim)[d], SimComm(sim), PETSC_ERR_ARG_INCOMP, "%s: particles reach %g..%g in direction %d, outside the domain %g..%g", c->path, (double)lo[d], (double)hi[d], (int)d + 1, (double)SimDomainLo(sim)[d], (double)SimDomainHi(sim)[d]);
  PetscCall(SimSetMedia(sim, (PetscBool)(c->count[KIND_FLUID] > 0), (PetscBool)(c->count[KIND_SOLID] > 0)));
  PetscCheck(SimHasFluid(sim) || SimHasSolid(sim), SimComm(sim), PETSC_ERR_USER_INPUT, "%s has no fluid (kind 0) and no solid (kind 3) particle", c->path);
  PetscCheck(!SimHasSolid(sim) || c->count[KIND_CLAMP] > 0, SimComm(sim), PETSC_ERR_ARG_INCOMP, "%s has a solid (kind 3) and no clamp (kind 4): a free solid is not supported", c->path);
  if (SimEndTime(sim) < 0) PetscCall(SimSetEndTime(sim, 1.0));
  /* c0 = 10 x the speed of a fall over the fluid's height (as -case boxes) */
  if (SimHasFluid(sim)) PetscCall(SimSetReferenceSpeed(sim, PetscSqrtReal(2 * SimGravityNorm(sim) * (top - low + SimSpacing(sim)))));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Populate(Sim sim)
{
  ParticlesFile *c = (ParticlesFile *)SimSceneContext(sim);
  const PetscInt D = SimDim(sim);
  PetscInt       first;
  PetscReal      vol = 1, top = -PETSC_MAX_REAL;
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &first));
  for (PetscInt k = 0; k < KIND_COUNT; k++) PetscCall(SceneCount(sim, (ParticleKind)k, c->count[k]));
  if (SceneCounting(sim)) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt d = 0; d < D; d++) vol *= SimSpacing(sim);
  for (PetscInt a = 0; a < c->n; a++) {
    const PetscInt  k    = c->kind[a];
    const PetscReal rho0 = KindIsSolid(k) ? SimSolidMaterial(sim)->rho0 : SimFluidMaterial(sim)->rho0;
    PetscCall(SimAddParticle(sim, c->id ? c->id[a] : c->first + a, (ParticleKind)k, c->x + D * a, c->m ? c->m[a] : rho0 * vol, c->h ? c->h[a] : SimKernelHFactor(sim) * SimSpacing(sim), c->rho ? c->rho[a] : rho0));
    if (KindIsFluid(k)) top = PetscMax(top, c->x[D * a + D - 1]);
  }
  PetscCall(SimSetNextId(sim, c->N));
  if (c->v) {
    PetscReal *v;
    PetscCall(SimGetField(sim, "v", NULL, &v));
    PetscCall(PetscArraycpy(v + D * first, c->v, D * c->n));
    PetscCall(SimRestoreField(sim, "v", NULL, &v));
  }
  if (c->p) {
    PetscReal *p;
    PetscCall(SimGetField(sim, "p", NULL, &p));
    PetscCall(PetscArraycpy(p + first, c->p, c->n));
    PetscCall(SimRestoreField(sim, "p", NULL, &p));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &top, 1, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  if (!c->rho && c->hydrostatic && SimHasFluid(sim)) PetscCall(SceneHydrostaticDensity(sim, first, top + 0.5 * SimSpacing(sim)));
  if (c->id) { /* each of 0..N-1 once: all in range, and their sum and sum of squares those of 0..N-1 */
    PetscInt64 s[3] = {0, 0, 0};
    for (PetscInt a = 0; a < c->n; a++) {
      s[0] += c->id[a] < 0 || c->id[a] >= c->N;
      s[1] += c->id[a];
      s[2] += (PetscInt64)c->id[a] * c->id[a];
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 3, MPIU_INT64, MPI_SUM, SimComm(sim)));
    PetscCheck(!s[0] && s[1] == (PetscInt64)c->N * (c->N - 1) / 2 && s[2] == (PetscInt64)c->N * (c->N - 1) * (2 * c->N - 1) / 6, SimComm(sim), PETSC_ERR_FILE_UNEXPECTED, "%s: dataset id must hold each of 0..%d once", c->path, (int)c->N - 1);
  }
  PetscCall(FreeRows(c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Probe(Sim sim, PetscReal *vals)
{
  const PetscReal *x;
  const PetscInt  *kind;
  PetscReal        front = -PETSC_MAX_REAL;
  PetscInt         n, D = SimDim(sim);
  PetscFunctionBeginUser;
  PetscCall(SimGetLocalSize(sim, &n));
  PetscCall(SimGetField(sim, "kind", NULL, &kind));
  PetscCall(SimGetField(sim, "x", NULL, &x));
  for (PetscInt a = 0; a < n; a++)
    if (KindIsFluid(kind[a])) front = PetscMax(front, x[D * a]);
  PetscCall(SimRestoreField(sim, "kind", NULL, &kind));
  PetscCall(SimRestoreField(sim, "x", NULL, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &front, 1, MPIU_REAL, MPIU_MAX, SimComm(sim)));
  vals[0] = front > -PETSC_MAX_REAL ? front + 0.5 * SimSpacing(sim) : 0;
  PetscCall(SceneMaxSpeed(sim, &vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Destroy(Sim sim)
{
  ParticlesFile *c = (ParticlesFile *)SimSceneContext(sim);
  PetscFunctionBeginUser;
  if (c) PetscCall(FreeRows(c));
  PetscCall(PetscFree(c));
  PetscCall(SimSetSceneContext(sim, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const SceneOps SceneParticlesFile = {
  .name = "file", .help = "particles from an HDF5 file (-particles_file; a snapshot of a run is one)",
  .create = Create, .populate = Populate, .probe = Probe, .destroy = Destroy,
  .nprobes = 2, .probe_names = {"front_x", "v_max"},
};
