/* What a checkpoint file is before a run reads it: intact, and the options it was written with. */
#include "io/checkpoint.h"
#include <petscviewerhdf5.h>
#include <errno.h>

#define RESTART_SLAB (1 << 20) /* elements read at a time while checking a dataset */

typedef struct {
  char   *why; /* what is wrong (empty: nothing so far) */
  size_t  len;
  void   *buf;
} Check;

/* Read every element of one dataset, a slab of rows at a time: a damaged chunk or index fails here. */
static herr_t ReadDataset(hid_t loc, const char *name, const H5L_info_t *info, void *ctx)
{
  Check  *c = (Check *)ctx;
  hid_t   d, space, type, mem, file;
  hsize_t dims[8], start[8] = {0}, count[8], row = 1;
  int     rank;
  herr_t  bad = 0;
  (void)info;
  if (H5Oexists_by_name(loc, name, H5P_DEFAULT) <= 0) return 0;
  if ((d = H5Dopen2(loc, name, H5P_DEFAULT)) < 0) { snprintf(c->why, c->len, "dataset %s cannot be opened", name); return 1; }
  space = H5Dget_space(d);
  type  = H5Tget_native_type(H5Dget_type(d), H5T_DIR_ASCEND);
  rank  = H5Sget_simple_extent_dims(space, dims, NULL);
  if (rank < 0 || rank > 8 || type < 0) bad = 1;
  for (int k = 1; !bad && k < rank; k++) row *= dims[k];
  if (!bad && rank > 0 && dims[0] > 0 && row > 0) {
    hsize_t rows = RESTART_SLAB / row ? RESTART_SLAB / row : 1;
    size_t  size = H5Tget_size(type);
    if (!c->buf && !(c->buf = malloc((size_t)RESTART_SLAB * 16 + 16 * (size_t)row))) bad = 1;
    for (hsize_t r0 = 0; !bad && r0 < dims[0]; r0 += rows) {
      start[0] = r0;
      count[0] = PetscMin(rows, dims[0] - r0);
      for (int k = 1; k < rank; k++) count[k] = dims[k];
      if (size > 16) { bad = 1; break; }
      mem  = H5Screate_simple(rank, count, NULL);
      file = H5Scopy(space);
      if (H5Sselect_hyperslab(file, H5S_SELECT_SET, start, NULL, count, NULL) < 0 || H5Dread(d, type, mem, file, H5P_DEFAULT, c->buf) < 0) bad = 1;
      H5Sclose(mem);
      H5Sclose(file);
    }
  }
  if (bad) snprintf(c->why, c->len, "dataset %s cannot be read", name);
  if (type >= 0) H5Tclose(type);
  H5Sclose(space);
  H5Dclose(d);
  return bad ? 1 : 0;
}

/* Rank 0: 0 when `path` is a whole sphfsi checkpoint; else why not in `why`.  HDF5 finds a truncated
 * file when it opens it (its end is short of the one its superblock records); damaged metadata or
 * chunks show when every dataset is read through.  The check reads the file once more on one rank:
 * a second or so per GB, against a restart whose collective read would otherwise stop in a trace on
 * some ranks, or hang. */
static int CheckFile(const char *path, char *why, size_t len)
{
  FILE         *fp = fopen(path, "rb");
  unsigned char sig[8] = {0};
  H5E_auto2_t   fn;
  void         *data;
  hid_t         f;
  Check         c = {why, len, NULL};
  why[0] = 0;
  if (!fp) { snprintf(why, len, "cannot be opened (%s)", strerror(errno)); return 1; }
  if (fread(sig, 1, 8, fp) != 8 || memcmp(sig, "\211HDF\r\n\032\n", 8)) snprintf(why, len, "is not an HDF5 file: give a checkpoint (OUTDIR/checkpoint.h5 or OUTDIR/last_good.h5)");
  fclose(fp);
  if (why[0]) return 1;
  H5Eget_auto2(H5E_DEFAULT, &fn, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* the verdict is one line, not HDF5's error stack */
  if ((f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0) snprintf(why, len, "is damaged: HDF5 cannot open it (truncated, e.g. by a full disk or an interrupted copy, or corrupt)");
  else {
    if (H5Aexists(f, "format") <= 0) snprintf(why, len, "is not an sphfsi checkpoint (snapshots particles_*.h5 cannot be restarted from; use checkpoint.h5 or last_good.h5 of a run)");
    else if (H5Literate(f, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, ReadDataset, &c) != 0 && !why[0]) snprintf(why, len, "is damaged: its datasets cannot be read");
    if (why[0] && strncmp(why, "is ", 3)) { /* "dataset x cannot be ...": say what it means */
      const char *pre = "is damaged (truncated or corrupt): "; /* shorter than the callers' len (512) */
      size_t      np = strlen(pre), n = PetscMin(strlen(why), len - np - 1);
      memmove(why + np, why, n); /* the message shifted right in place, cut to fit */
      memcpy(why, pre, np);
      why[np + n] = 0;
    }
    H5Fclose(f);
  }
  free(c.buf);
  H5Eset_auto2(H5E_DEFAULT, fn, data);
  return why[0] != 0;
}

/* The option string a checkpoint was written with (rank 0; NULL if none).  The caller frees it. */
static char *ReadOptions(const char *path)
{
  hid_t f, a, t;
  char *s = NULL;
  if ((f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0) return NULL;
  if (H5Aexists(f, "options") > 0 && (a = H5Aopen(f, "options", H5P_DEFAULT)) >= 0) {
    t = H5Aget_type(a);
    if (H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t)) {
      size_t n = H5Tget_size(t);
      if ((s = calloc(n + 1, 1)) && H5Aread(a, t, s) < 0) { free(s); s = NULL; }
    }
    H5Tclose(t);
    H5Aclose(a);
  }
  H5Fclose(f);
  return s;
}

/* Options a restart never takes from its checkpoint: where it reads and writes, the limits of one job
 * (-max_steps counts from the run's start, so the checkpoint's would end the restart at once), and
 * one-off requests. */
static PetscBool NotInherited(const char *name)
{
  const char *skip[] = {"-restart", "-output_dir", "-overwrite", "-help", "-version", "-options_file", "-options_file_yaml", "-max_memory", "-max_steps", "-max_wall_time"};
  for (size_t k = 0; k < sizeof(skip) / sizeof(skip[0]); k++)
    if (!strcmp(name, skip[k])) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode CheckpointInheritOptions(MPI_Comm comm)
{
  char        path[PETSC_MAX_PATH_LEN] = "", why[512] = "", *all = NULL;
  PetscBool   set;
  PetscMPIInt rank;
  int         len = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(NULL, NULL, "-restart", path, sizeof(path), &set));
  if (!set || !path[0]) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && !CheckFile(path, why, sizeof(why))) {
    all = ReadOptions(path);
    len = all ? (int)strlen(all) + 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(why, sizeof(why), MPI_CHAR, 0, comm));
  PetscCheck(!why[0], comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s %s", path, why);
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  if (!len) PetscFunctionReturn(PETSC_SUCCESS);
  if (rank) PetscCall(PetscCalloc1(len, &all));
  else {
    char *copy;
    PetscCall(PetscMalloc1(len, &copy));
    PetscCall(PetscArraycpy(copy, all, len));
    free(all);
    all = copy;
  }
  PetscCallMPI(MPI_Bcast(all, len, MPI_CHAR, 0, comm));
  /* "-name value -flag -name2 value2 ...": each option the command line does not give */
  for (char *p = all; *p;) {
    char  name[256] = "", value[PETSC_MAX_PATH_LEN] = "";
    char *end;
    while (*p == ' ') p++;
    if (*p != '-') { p += *p ? 1 : 0; continue; }
    end = p + strcspn(p, " ");
    snprintf(name, sizeof(name), "%.*s", (int)(end - p), p);
    p = end;
    while (*p == ' ') p++;
    if (*p && !(p[0] == '-' && !(p[1] >= '0' && p[1] <= '9') && p[1] != '.')) { /* a value, not the next option */
      end = p + strcspn(p, " ");
      snprintf(value, sizeof(value), "%.*s", (int)(end - p), p);
      p = end;
    }
    if (NotInherited(name)) continue;
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, name, value[0] ? value : NULL));
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}
