#include "base/refdata.h"
#include "base/version.h"
#include <unistd.h>

#define REFDATA_MAX_DIRS 4

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

/* The folders a reference file is looked for in, so that a run finds it from any current directory
 * (docs/options.md, -refdata_dir).  -refdata_dir DIR, else $SPHFSI_REFDATA, is the only one: the
 * user chose it (*why names which).  Otherwise, in order (*why NULL):
 *   PREFIX/share/sphfsi/refdata  an installed program (make install: <exe dir> is PREFIX/bin)
 *   <exe dir>/refdata            a copy beside the program (bin/sphfsi and refdata/ copied elsewhere)
 *   SphfsiSourceRefData()        the source tree's data ($(abspath $(REFDATA)) at build time)
 *   ../shared/refdata            from the current directory (a checkout's root), the last resort
 * <exe dir> comes from /proc/self/exe (absolute, no symbolic links, so its textual parent is
 * PREFIX); a folder whose path would not fit is left out. */
static PetscErrorCode RefDataDirs(const RefData *rd, char dirs[REFDATA_MAX_DIRS][PETSC_MAX_PATH_LEN], PetscInt *n, const char **why)
{
  const char *env = getenv("SPHFSI_REFDATA");
  char        exe[PETSC_MAX_PATH_LEN], *slash;
  ssize_t     len;

  PetscFunctionBeginUser;
  *n   = 0;
  *why = rd->dir[0] ? "-refdata_dir" : env && env[0] ? "$SPHFSI_REFDATA" : NULL;
  if (*why) {
    PetscCall(PetscStrncpy(dirs[(*n)++], rd->dir[0] ? rd->dir : env, PETSC_MAX_PATH_LEN));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  len = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (len > 0) {
    char bin[PETSC_MAX_PATH_LEN];
    exe[len] = 0;
    if ((slash = strrchr(exe, '/'))) *slash = 0;
    PetscCall(PetscStrncpy(bin, exe, sizeof(bin))); /* <exe dir> */
    if ((slash = strrchr(exe, '/'))) *slash = 0;    /* PREFIX */
    if (snprintf(dirs[*n], PETSC_MAX_PATH_LEN, "%s/share/sphfsi/refdata", exe) < PETSC_MAX_PATH_LEN) (*n)++;
    if (snprintf(dirs[*n], PETSC_MAX_PATH_LEN, "%s/refdata", bin) < PETSC_MAX_PATH_LEN) (*n)++;
  }
  PetscCall(PetscStrncpy(dirs[(*n)++], SphfsiSourceRefData(), PETSC_MAX_PATH_LEN));
  PetscCall(PetscStrncpy(dirs[(*n)++], "../shared/refdata", PETSC_MAX_PATH_LEN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Add FILE to rd->missing unless it is there; *added says whether it was new (a scene may
 * read one file for several columns: one warning per file). */
static PetscErrorCode NoteMissing(RefData *rd, const char *file, PetscBool *added)
{
  char   item[PETSC_MAX_PATH_LEN], *list;
  size_t old = rd->missing ? strlen(rd->missing) : 0, len;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(item, sizeof(item), "\"%s\"", file));
  *added = (PetscBool)!(old && strstr(rd->missing, item));
  if (!*added) PetscFunctionReturn(PETSC_SUCCESS);
  len = old + strlen(item) + 3;
  PetscCall(PetscMalloc1(len, &list));
  PetscCall(PetscSNPrintf(list, len, "%s%s%s", old ? rd->missing : "", old ? ", " : "", item));
  PetscCall(PetscFree(rd->missing));
  rd->missing = list;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RefDataOpen(RefData *rd, const char *file, FILE **f)
{
  char        dirs[REFDATA_MAX_DIRS][PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN];
  const char *why;
  PetscInt    n;
  PetscBool   added = PETSC_FALSE;

  PetscFunctionBeginUser;
  *f = NULL;
  if (rd->rank) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(RefDataDirs(rd, dirs, &n, &why));
  for (PetscInt k = 0; k < n && !*f; k++)
    if (snprintf(path, sizeof(path), "%s/%s", dirs[k], file) < (int)sizeof(path)) *f = fopen(path, "r");
  if (*f) {
    PetscCall(PetscInfo(NULL, "Reference %s\n", path));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(NoteMissing(rd, file, &added));
  if (!added) PetscFunctionReturn(PETSC_SUCCESS);
  /* one line on stdout, from rank 0 alone (the others have returned): a batch log shows it */
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "sphfsi: warning: reference data %s not found in ", file));
  for (PetscInt k = 0; k < n; k++) PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s%s", k ? ", " : "", dirs[k]));
  if (why) PetscCall(PetscPrintf(PETSC_COMM_SELF, " (%s): summary.json has no errors against it\n", why));
  else PetscCall(PetscPrintf(PETSC_COMM_SELF, ": summary.json has no errors against it (-refdata_dir DIR or $SPHFSI_REFDATA names the folder)\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RefDataLoad(RefData *rd, const char *file, const char *xcol, const char *ycol, Series *ref, PetscBool *found)
{
  char  line[4096];
  FILE *f;
  int   ix = -1, iy = -1;

  PetscFunctionBeginUser;
  *found = PETSC_FALSE;
  PetscCall(RefDataOpen(rd, file, &f));
  if (!f) PetscFunctionReturn(PETSC_SUCCESS);
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

#define ROW_MAX_COLS 32
PetscErrorCode RefDataRow(RefData *rd, MPI_Comm comm, const char *file, const char *const key[2], const char *const val[2], PetscInt n, const char *const col[], PetscReal out[], PetscBool *found)
{
  PetscReal *buf; /* the columns, then whether the row was found */
  char       line[4096];
  FILE      *f;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(n + 1, &buf));
  PetscCall(RefDataOpen(rd, file, &f)); /* a missing file is reported there */
  if (f) {
    int ik[2] = {-1, key[1] ? -1 : -2}, *ic;
    PetscCall(PetscMalloc1(n, &ic));
    for (PetscInt q = 0; q < n; q++) ic[q] = -1;
    while (fgets(line, sizeof(line), f)) {
      char *tok, *rest = line, *v[ROW_MAX_COLS] = {NULL};
      int   nt = 0;
      if (line[0] == '#' || line[0] == '\n') continue;
      line[strcspn(line, "\r\n")] = 0;
      while ((tok = strsep(&rest, ",")) && nt < ROW_MAX_COLS) v[nt++] = tok;
      if (ik[0] == -1) { /* the header */
        for (int t = 0; t < nt; t++) {
          for (int q = 0; q < 2; q++)
            if (key[q] && !strcmp(v[t], key[q])) ik[q] = t;
          for (PetscInt q = 0; q < n; q++)
            if (!strcmp(v[t], col[q])) ic[q] = t;
        }
        if (ik[0] < 0 || ik[1] == -1) break;
        continue;
      }
      if (ik[0] >= nt || strcasecmp(v[ik[0]], val[0]) || (key[1] && (ik[1] >= nt || strcasecmp(v[ik[1]], val[1])))) continue;
      for (PetscInt q = 0; q < n; q++) buf[q] = ic[q] >= 0 && ic[q] < nt && v[ic[q]][0] ? atof(v[ic[q]]) : 0;
      buf[n] = 1;
      break;
    }
    PetscCall(PetscFree(ic));
    fclose(f);
  }
  PetscCallMPI(MPI_Bcast(buf, (PetscMPIInt)(n + 1), MPIU_REAL, 0, comm));
  *found = (PetscBool)(buf[n] > 0);
  for (PetscInt q = 0; q < n; q++) out[q] = buf[q];
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RefDataDestroy(RefData *rd)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(rd->missing));
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
