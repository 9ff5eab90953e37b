#include "io/outdir.h"
#include "io/io.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* A verdict of rank 0 that every rank acts on: a code (0: fine) and its line. */
typedef struct {
  int  code;
  char msg[PETSC_MAX_PATH_LEN + 512];
} Verdict;

static PetscErrorCode Share(Output *out, Verdict *v)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(v, (PetscMPIInt)sizeof(*v), MPI_BYTE, 0, out->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* mkdir -p on rank 0; every rank learns whether it worked, and checks that it sees the directory
 * too (on a cluster the output must be on a file system that every node shares).  The probe file
 * has a name of this run (no node can have it cached as absent), and a rank that does not see it
 * looks again for a few seconds (network file systems cache directory entries). */
static PetscErrorCode MakeDir(Output *out, const char *dir)
{
  int  msg[2] = {0, (int)getpid()}, blind = 0; /* error, name of the probe */
  char probe[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&msg[1], 1, MPI_INT, 0, out->comm));
  PetscCall(PetscSNPrintf(probe, sizeof(probe), "%s/.sphfsi_probe_%d", dir, msg[1]));
  if (!out->rank) {
    char path[PETSC_MAX_PATH_LEN];
    PetscCall(PetscStrncpy(path, dir, sizeof(path)));
    for (char *p = path + 1; *p; p++)
      if (*p == '/') { *p = 0; if (mkdir(path, 0775) && errno != EEXIST) msg[0] = errno; *p = '/'; }
    if (mkdir(path, 0775) && errno != EEXIST) msg[0] = errno;
    if (!msg[0]) {
      FILE *f;
      if (!(f = fopen(probe, "w"))) msg[0] = errno;
      else fclose(f);
    }
  }
  PetscCallMPI(MPI_Bcast(msg, 1, MPI_INT, 0, out->comm));
  PetscCheck(!msg[0], out->comm, PETSC_ERR_FILE_OPEN, "Cannot create or write the output directory %s (%s): choose another -output_dir", dir, strerror(msg[0]));
  for (int k = 0; out->rank && k < 20 && access(probe, R_OK); k++) PetscCall(PetscSleep(0.25));
  if (out->rank && access(probe, R_OK)) blind = out->rank;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &blind, 1, MPI_INT, MPI_MAX, out->comm));
  if (!out->rank) remove(probe);
  PetscCheck(!blind, out->comm, PETSC_ERR_FILE_OPEN, "Rank %d cannot see the output directory %s that rank 0 created: on a cluster, -output_dir must be on a file system that every node shares (give an absolute path there)", blind, dir);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void LockPath(Output *out, char *path, size_t len) { (void)PetscSNPrintf(path, len, "%s/%s", out->dir, OUTDIR_LOCK); }

/* Whether process pid of this host has ended: gone, or a zombie (killed, not yet reaped: a launcher
 * that exits before it reaps its ranks leaves them so for a moment). */
static PetscBool Ended(int pid)
{
  char  path[64], line[256], *close;
  FILE *f;
  if (kill(pid, 0) && errno == ESRCH) return PETSC_TRUE;
  (void)PetscSNPrintf(path, sizeof(path), "/proc/%d/stat", pid);
  if (!(f = fopen(path, "r"))) return PETSC_FALSE;
  close = fgets(line, sizeof(line), f) ? strrchr(line, ')') : NULL; /* "pid (comm) S ..." */
  fclose(f);
  return (PetscBool)(close && close[1] == ' ' && close[2] == 'Z');
}

/* Rank 0: create the lock, or say whose it is.  0: taken; EEXIST: held by a live run (v->msg says
 * whose); another errno: the lock could not be written. */
static int TakeLock(Output *out, Verdict *v)
{
  char   path[PETSC_MAX_PATH_LEN], host[256] = "", line[512];
  time_t now = time(NULL);
  LockPath(out, path, sizeof(path));
  (void)gethostname(host, sizeof(host) - 1);
  for (int attempt = 0; attempt < 3; attempt++) {
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      size_t n;
      int    bad;
      (void)PetscSNPrintf(line, sizeof(line), "host %s\npid %d\nstarted %ld\n", host, (int)getpid(), (long)now);
      n   = strlen(line);
      bad = write(fd, line, n) != (ssize_t)n;
      if (close(fd) || bad) { int e = errno ? errno : EIO; unlink(path); return e; }
      return 0;
    }
    if (errno != EEXIST) return errno;
    { /* whose?  host and pid from the file, its age from its time stamp */
      char        their[256] = "";
      int         pid = 0;
      struct stat st;
      FILE       *f = fopen(path, "r");
      double      age;
      if (f) {
        if (fscanf(f, "host %255s pid %d", their, &pid) != 2) pid = 0;
        fclose(f);
      }
      if (stat(path, &st)) continue; /* gone meanwhile: try again */
      age = difftime(now, st.st_mtime);
      if (pid == (int)getpid() && !strcmp(their, host)) return -1; /* this process's (another Sim of a test program) */
      for (int k = 0; k < 20 && pid > 0 && !strcmp(their, host) && !Ended(pid); k++) usleep(100000); /* a run being killed: 2 s to end */
      if (pid > 0 && !strcmp(their, host) && Ended(pid)) {
        (void)PetscSNPrintf(v->msg, sizeof(v->msg), "sphfsi: note: %s was left by process %d, which no longer runs on %s: taken over\n", path, pid, host);
      } else if (strcmp(their, host) && age > OUTDIR_STALE_S) {
        (void)PetscSNPrintf(v->msg, sizeof(v->msg), "sphfsi: note: %s of process %d on %s was last refreshed %.0f s ago (more than %.0f s): taken over as stale\n", path, pid, their[0] ? their : "an unknown host", age, OUTDIR_STALE_S);
      } else {
        (void)PetscSNPrintf(v->msg, sizeof(v->msg), "The output directory %s is in use by another run (process %d on %s, lock refreshed %.0f s ago): give another -output_dir, or wait until that run ends (a run that died on another host leaves a lock that is taken over %.0f s after its last refresh; remove %s to take it at once)", out->dir, pid, their[0] ? their : "an unknown host", age, OUTDIR_STALE_S, path);
        return EEXIST;
      }
      printf("%s", v->msg);
      v->msg[0] = 0;
      if (unlink(path) && errno != ENOENT) return errno;
    }
  }
  return EAGAIN;
}

/* A file a run writes in its output directory (or such a file half-written, *.part). */
static PetscBool RunFile(const char *name, PetscBool *snapshot, PetscBool *part)
{
  const char *names[] = {"summary.json", "probes.csv", "particles.xmf", "checkpoint.h5", "last_good.h5", "last_good.xmf", "options_used"};
  size_t      n = strlen(name);
  char        base[256];
  int         idx, len = 0;
  *part = (PetscBool)(n > 5 && !strcmp(name + n - 5, ".part"));
  if (n >= sizeof(base)) return PETSC_FALSE;
  (void)PetscSNPrintf(base, sizeof(base), "%.*s", (int)(*part ? n - 5 : n), name);
  *snapshot = (PetscBool)(sscanf(base, "particles_%d.h5%n", &idx, &len) == 1 && len == (int)strlen(base));
  if (*snapshot) return PETSC_TRUE;
  for (size_t k = 0; k < sizeof(names) / sizeof(names[0]); k++)
    if (!strcmp(base, names[k])) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* Rank 0: the run files in the directory (counted, listed in v->msg), removed when `remove`. */
static int EarlierRun(Output *out, PetscBool remove, PetscInt *nfiles, char *list, size_t len)
{
  DIR           *d = opendir(out->dir);
  struct dirent *e;
  PetscInt       nsnap = 0;
  int            err = 0;
  *nfiles = 0;
  list[0] = 0;
  if (!d) return errno;
  while ((e = readdir(d))) {
    PetscBool snapshot, part;
    char      path[PETSC_MAX_PATH_LEN];
    if (!RunFile(e->d_name, &snapshot, &part)) continue;
    (*nfiles)++;
    if (snapshot && !part) nsnap++;
    else if (!part && strlen(list) + strlen(e->d_name) + 4 < len) (void)PetscSNPrintf(list + strlen(list), len - strlen(list), "%s%s", list[0] ? ", " : "", e->d_name);
    (void)PetscSNPrintf(path, sizeof(path), "%s/%s", out->dir, e->d_name);
    if (remove && unlink(path) && !err) err = errno;
  }
  closedir(d);
  if (nsnap) (void)PetscSNPrintf(list + strlen(list), len - strlen(list), "%s%d snapshot(s)", list[0] ? ", " : "", (int)nsnap);
  return err;
}

/* Whether two paths name the same directory (both must exist). */
static PetscBool SameDir(const char *a, const char *b)
{
  struct stat sa, sb;
  return (PetscBool)(!stat(a, &sa) && !stat(b, &sb) && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino);
}

PetscErrorCode OutDirOpen(Output *out)
{
  Verdict v;
  PetscFunctionBeginUser;
  PetscCall(MakeDir(out, out->dir));
  PetscCall(PetscMemzero(&v, sizeof(v)));
  if (!out->rank) {
    v.code = TakeLock(out, &v);
    if (!v.code) out->lock_held = PETSC_TRUE;
    if (v.code == -1) v.code = 0; /* a lock of this very process: not ours to release */
    if (v.code && v.code != EEXIST) (void)PetscSNPrintf(v.msg, sizeof(v.msg), "Cannot write the lock %s/%s (%s): choose another -output_dir", out->dir, OUTDIR_LOCK, strerror(v.code));
  }
  PetscCall(Share(out, &v));
  PetscCheck(!v.code, out->comm, PETSC_ERR_USER_INPUT, "%s", v.msg);
  PetscCall(PetscTime(&out->lock_beat));
  /* a restart goes on in its checkpoint's directory; anything else starts afresh */
  if (!out->rank) {
    char      dir[PETSC_MAX_PATH_LEN], list[512];
    PetscInt  n;
    PetscBool cont = PETSC_FALSE;
    if (out->restart[0]) {
      char *slash;
      PetscCall(PetscStrncpy(dir, out->restart, sizeof(dir)));
      slash = strrchr(dir, '/');
      if (slash) *slash = 0;
      else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
      cont = SameDir(dir, out->dir);
    }
    if (!cont) {
      v.code = EarlierRun(out, out->overwrite, &n, list, sizeof(list));
      if (v.code) (void)PetscSNPrintf(v.msg, sizeof(v.msg), "Cannot remove the earlier run's files in %s (%s)", out->dir, strerror(v.code));
      else if (n && out->overwrite) printf("sphfsi: note: -overwrite: removed the earlier run's files in %s (%s)\n", out->dir, list);
      else if (n) {
        v.code = EEXIST;
        (void)PetscSNPrintf(v.msg, sizeof(v.msg), "The output directory %s holds an earlier run's output (%s): give another -output_dir, -overwrite to replace it, or -restart %s/checkpoint.h5 to continue that run", out->dir, list, out->dir);
      }
    }
  }
  PetscCall(Share(out, &v));
  if (v.code) PetscCall(OutDirClose(out));
  PetscCheck(!v.code, out->comm, PETSC_ERR_USER_INPUT, "%s", v.msg);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OutDirBeat(Output *out)
{
  PetscLogDouble now;
  char           path[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  if (!out->lock_held) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscTime(&now));
  if (now - out->lock_beat < OUTDIR_BEAT_S) PetscFunctionReturn(PETSC_SUCCESS);
  out->lock_beat = now;
  LockPath(out, path, sizeof(path));
  (void)utimensat(AT_FDCWD, path, NULL, 0); /* a lock that cannot be touched only looks older */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OutDirTidyRestart(Output *out)
{
  PetscInt removed = 0, missing = 0;
  PetscFunctionBeginUser;
  if (!out->rank) {
    DIR           *d = opendir(out->dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
      PetscBool snapshot, part;
      int       idx = -1;
      char      path[PETSC_MAX_PATH_LEN];
      if (!RunFile(e->d_name, &snapshot, &part)) continue;
      if (snapshot) (void)sscanf(e->d_name, "particles_%d", &idx);
      if (!part && !(snapshot && idx >= out->nsnap)) continue;
      (void)PetscSNPrintf(path, sizeof(path), "%s/%s", out->dir, e->d_name);
      if (!unlink(path) && !part) removed++;
    }
    if (d) closedir(d);
    /* the snapshots before the checkpoint that this directory lacks (a restart elsewhere) are left
     * out of particles.xmf: a negative particle count marks them */
    for (PetscInt s = 0; s < out->nsnap; s++) {
      char path[PETSC_MAX_PATH_LEN];
      (void)PetscSNPrintf(path, sizeof(path), "%s/particles_%05d.h5", out->dir, (int)s);
      if (access(path, R_OK)) { out->snaps[2 * s + 1] = -1; missing++; }
    }
    if (removed) printf("sphfsi: note: removed %d snapshot(s) written after the checkpoint by the interrupted run: this run writes them again\n", (int)removed);
  }
  PetscCallMPI(MPI_Bcast(&missing, 1, MPIU_INT, 0, out->comm));
  if (out->nsnap) PetscCall(IOWriteXDMF(out));
  if (missing) PetscCall(PetscPrintf(out->comm, "sphfsi: note: %d of the checkpointed run's %d snapshot(s) are not in %s: particles.xmf lists those that are\n", (int)missing, (int)out->nsnap, out->dir));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OutDirClose(Output *out)
{
  char path[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  if (!out || !out->lock_held) PetscFunctionReturn(PETSC_SUCCESS);
  LockPath(out, path, sizeof(path));
  (void)unlink(path);
  out->lock_held = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
