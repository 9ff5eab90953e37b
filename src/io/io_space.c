#include "io/io_space.h"
#include <errno.h>
#include <sys/statvfs.h>
#include <unistd.h>

#define IO_SPACE_MARGIN 1.1     /* HDF5's headers and chunk rounding over the raw data */
#define IO_SPACE_SLACK  65536.0 /* bytes: attributes, the XDMF, probes.csv and summary.json beside it */

PetscErrorCode IOFault(Output *out, const char *fmt, ...)
{
  va_list ap;
  size_t  len;
  PetscFunctionBeginUser;
  if (out->fault.set) PetscFunctionReturn(PETSC_SUCCESS);
  va_start(ap, fmt);
  PetscCall(PetscVSNPrintf(out->fault.msg, sizeof(out->fault.msg), fmt, &len, ap));
  va_end(ap);
  out->fault.set = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSpaceReserve(Output *out, const char *file, PetscReal bytes, PetscBool *ok)
{
  double free_bytes = -1, need = IO_SPACE_MARGIN * (double)bytes + IO_SPACE_SLACK;
  PetscFunctionBeginUser;
  if (!out->rank) {
    struct statvfs fs;
    if (!statvfs(out->dir, &fs)) free_bytes = (double)fs.f_bavail * (double)fs.f_frsize; /* what this user may fill */
  }
  PetscCallMPI(MPI_Bcast(&free_bytes, 1, MPI_DOUBLE, 0, out->comm));
  *ok = (PetscBool)(free_bytes < 0 || free_bytes >= need); /* unknown: try, and let a failed write say it */
  if (!*ok) PetscCall(IOFault(out, "no space left on device writing %s/%s (it needs about %.3g MB, %.3g MB are free): free space or give another -output_dir, then continue from the last checkpoint", out->dir, file, need / 1e6, free_bytes / 1e6));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Bytes per particle of a snapshot's or a checkpoint's fields (the field table), id and kind included. */
static PetscReal FieldBytes(Particles P, PetscBool snapshot)
{
  FieldId   out[FIELD_COUNT];
  PetscInt  n = 0;
  PetscReal b = 2 * sizeof(PetscInt);
  if (snapshot) n = ParticlesSnapshotFields(P, out);
  else
    for (PetscInt f = 0; f < FIELD_COUNT; f++)
      if (ParticlesCheckpointField(P, (FieldId)f)) out[n++] = (FieldId)f;
  for (PetscInt k = 0; k < n; k++) b += P->f[out[k]].width * sizeof(PetscReal);
  return b;
}

PetscErrorCode IOSpaceSnapshot(Output *out, PetscReal *bytes)
{
  PetscFunctionBeginUser;
  *bytes = (PetscReal)out->phys->nb->nparticles * FieldBytes(out->phys->P, PETSC_TRUE);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSpaceCheckpoint(Output *out, PetscReal *bytes)
{
  PetscFunctionBeginUser;
  *bytes = (PetscReal)out->phys->nb->nparticles * FieldBytes(out->phys->P, PETSC_FALSE) + (PetscReal)out->nprobe_rows * (1 + out->scene.nprobes) * sizeof(PetscReal) + (PetscReal)GridNumCells(out->grid) * sizeof(PetscInt) + 2.0 * out->nsnap * sizeof(PetscReal);
  for (PetscInt k = 0; k < out->scene.nkept_series; k++) *bytes += 2.0 * out->scene.kept_series[k]->n * sizeof(PetscReal);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static char writing[PETSC_MAX_PATH_LEN]; /* the file being written (IOSpacePushWrite) */

/* An error handler may not raise errors: plain C only. */
static PetscErrorCode WriteFailed(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  int  err = errno, rank = 0;
  char part[PETSC_MAX_PATH_LEN + 8];
  (void)comm; (void)line; (void)fun; (void)file; (void)n; (void)ctx;
  if (p != PETSC_ERROR_INITIAL) return n;
  (void)MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  fprintf(stderr, "sphfsi: error: rank %d could not write %s: %s (exit status %d; the last complete checkpoint is kept)\n", rank, writing, err == ENOSPC || err == EDQUOT || err == EIO || err == EROFS ? strerror(err) : mess ? mess : "HDF5 error", SIM_EXIT_IO);
  fflush(stderr);
  (void)snprintf(part, sizeof(part), "%s.part", writing);
  (void)unlink(part);
  MPI_Abort(MPI_COMM_WORLD, SIM_EXIT_IO);
  return n;
}

PetscErrorCode IOSpacePushWrite(const char *file)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(writing, file, sizeof(writing)));
  PetscCall(PetscPushErrorHandler(WriteFailed, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IOSpacePopWrite(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPopErrorHandler());
  writing[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
