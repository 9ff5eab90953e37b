#include <sphfsi/refdata.h>
#include <unistd.h>

PetscErrorCode SeriesAppend(Series *s, PetscReal t, PetscReal y)
{
  PetscFunctionBeginUser;
  if (s->n == s->cap) {
    PetscReal *nt, *ny;
    s->cap = 2 * s->cap + 64;
    PetscCall(PetscMalloc2(s->cap, &nt, s->cap, &ny));
    if (s->n) { PetscCall(PetscArraycpy(nt, s->t, s->n)); PetscCall(PetscArraycpy(ny, s->y, s->n)); }
    PetscCall(PetscFree2(s->t, s->y));
    s->t = nt; s->y = ny;
  }
  s->t[s->n] = t; s->y[s->n] = y; s->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SeriesDestroy(Series *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(s->t, s->y));
  s->n = s->cap = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SeriesPeak(const Series *s, PetscReal t0, PetscReal t1, PetscReal *v, PetscReal *t)
{
  *v = -PETSC_MAX_REAL; *t = 0;
  for (PetscInt k = 0; k < s->n; k++)
    if (s->t[k] >= t0 && s->t[k] <= t1 && s->y[k] > *v) { *v = s->y[k]; *t = s->t[k]; }
}

PetscReal SeriesAt(const Series *s, PetscReal t)
{
  PetscInt lo = 0, hi = s->n - 1;
  if (!s->n) return 0;
  if (t <= s->t[0]) return s->y[0];
  if (t >= s->t[hi]) return s->y[hi];
  while (hi - lo > 1) { PetscInt mid = (lo + hi) / 2; if (s->t[mid] <= t) lo = mid; else hi = mid; }
  return s->y[lo] + (s->y[hi] - s->y[lo]) * (t - s->t[lo]) / (s->t[hi] - s->t[lo]);
}

/* An installed program (make install) finds its data beside it: <prefix>/bin/sphfsi reads
 * <prefix>/share/sphfsi/refdata.  False when that folder does not exist (running from the source tree). */
static PetscBool InstalledRefData(char *dir, size_t len)
{
  char  exe[PETSC_MAX_PATH_LEN];
  char *slash;
  ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n <= 0) return PETSC_FALSE;
  exe[n] = 0;
  if (!(slash = strrchr(exe, '/'))) return PETSC_FALSE;
  *slash = 0; /* <prefix>/bin */
  if (snprintf(dir, len, "%s/../share/sphfsi/refdata", exe) >= (int)len) return PETSC_FALSE;
  return (PetscBool)(access(dir, R_OK) == 0);
}

PetscErrorCode RefDataLoad(Sim sim, const char *file, const char *xcol, const char *ycol, Series *ref, PetscBool *found)
{
  char        dir[PETSC_MAX_PATH_LEN] = "../shared/refdata", path[PETSC_MAX_PATH_LEN], line[4096];
  const char *env = getenv("SPHFSI_REFDATA");
  FILE       *f;
  int         ix = -1, iy = -1;

  PetscFunctionBeginUser;
  *found = PETSC_FALSE;
  if (sim->refdata_dir[0]) PetscCall(PetscStrncpy(dir, sim->refdata_dir, sizeof(dir))); /* -refdata_dir */
  else if (env) PetscCall(PetscStrncpy(dir, env, sizeof(dir)));
  else if (!InstalledRefData(dir, sizeof(dir))) PetscCall(PetscStrncpy(dir, "../shared/refdata", sizeof(dir)));
  if (sim->rank) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", dir, file));
  if (!(f = fopen(path, "r"))) {
    PetscCall(PetscInfo(NULL, "Reference %s not found: no errors reported against it\n", path));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  while (fgets(line, sizeof(line), f)) {
    char *tok, *rest = line;
    int   col = 0;
    double vx = 0, vy = 0;
    if (line[0] == '#' || line[0] == '\n') continue;
    if (ix < 0) { /* header */
      line[strcspn(line, "\r\n")] = 0;
      while ((tok = strsep(&rest, ","))) {
        while (*tok == ' ' || *tok == '"') tok++;
        if (!strncmp(tok, xcol, strlen(xcol)) && (tok[strlen(xcol)] == 0 || tok[strlen(xcol)] == '"')) ix = col;
        if (!strncmp(tok, ycol, strlen(ycol)) && (tok[strlen(ycol)] == 0 || tok[strlen(ycol)] == '"')) iy = col;
        col++;
      }
      if (ix < 0 || iy < 0) break;
      continue;
    }
    line[strcspn(line, "\r\n")] = 0;
    while ((tok = strsep(&rest, ","))) {
      if (col == ix) vx = atof(tok);
      if (col == iy) vy = atof(tok);
      col++;
    }
    PetscCall(SeriesAppend(ref, vx, vy));
  }
  fclose(f);
  *found = (PetscBool)(ix >= 0 && iy >= 0 && ref->n > 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SeriesKeepBelow(Series *s, PetscReal ymax)
{
  PetscInt n = 0;
  for (PetscInt k = 0; k < s->n; k++)
    if (s->y[k] < ymax) { s->t[n] = s->t[k]; s->y[n] = s->y[k]; n++; }
  s->n = n;
}

PetscErrorCode SeriesCompare(const Series *sim, const Series *ref, PetscReal tscale, PetscReal yscale, PetscReal t0, PetscReal t1, PetscBool relative, PetscReal *rms, PetscReal *max, PetscInt *npts)
{
  PetscReal s2 = 0;
  PetscFunctionBeginUser;
  *max = 0; *npts = 0;
  for (PetscInt k = 0; k < ref->n; k++) {
    PetscReal e;
    if (ref->t[k] < t0 || ref->t[k] > t1) continue;
    e = SeriesAt(sim, ref->t[k] * tscale) / yscale - ref->y[k];
    if (relative) e /= PetscAbsReal(ref->y[k]);
    e = PetscAbsReal(e);
    s2 += e * e;
    *max = PetscMax(*max, e);
    (*npts)++;
  }
  *rms = *npts ? PetscSqrtReal(s2 / *npts) : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
