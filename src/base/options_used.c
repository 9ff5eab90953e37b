#include "base/options_used.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The options read with their final values (OptionsRecord*): a database of its own, like PETSc's
 * global one, freed at PetscFinalize. */
static PetscOptions recorded = NULL;

static PetscErrorCode RecordedDestroy(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsDestroy(&recorded));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsRecord(const char *prefix, const char *name, const char *value, const void *set)
{
  char full[256];
  PetscFunctionBeginUser;
  if (set) PetscFunctionReturn(PETSC_SUCCESS);
  if (!recorded) {
    PetscCall(PetscOptionsCreate(&recorded));
    PetscCall(PetscRegisterFinalize(RecordedDestroy));
  }
  PetscCall(PetscSNPrintf(full, sizeof(full), "-%s%s", prefix ? prefix : "", name + 1));
  PetscCall(PetscOptionsSetValue(recorded, full, value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsRecordReal(const char *prefix, const char *name, PetscReal v, const void *set)
{
  char buf[64];
  PetscFunctionBeginUser;
  if (set || v < 0 || PetscIsInfOrNanReal(v)) PetscFunctionReturn(PETSC_SUCCESS);
  for (int digits = 15; digits <= 17; digits++) { /* the shortest form that reads back exactly: 1.4, not 1.3999999999999999 */
    PetscCall(PetscSNPrintf(buf, sizeof(buf), "%.*g", digits, (double)v));
    if (strtod(buf, NULL) == (double)v) break;
  }
  PetscCall(OptionsRecord(prefix, name, buf, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsRecordInt(const char *prefix, const char *name, PetscInt v, const void *set)
{
  char buf[32];
  PetscFunctionBeginUser;
  if (set || v < 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSNPrintf(buf, sizeof(buf), "%" PetscInt_FMT, v));
  PetscCall(OptionsRecord(prefix, name, buf, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The renamed options the modules declared (OptDeprecated): old and new name. */
static struct {
  const char *old, *now;
} renamed[32];
static int nrenamed = 0;

PetscErrorCode SPHOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char man[], PetscReal cur, PetscReal *val, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsReal(opt, text, man, cur, val, set));
  PetscCall(OptionsRecordReal(PetscOptionsObject->prefix, opt, *val, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHOptionsInt(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char man[], PetscInt cur, PetscInt *val, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsInt(opt, text, man, cur, val, set));
  PetscCall(OptionsRecordInt(PetscOptionsObject->prefix, opt, *val, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHOptionsBool(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char man[], PetscBool cur, PetscBool *val, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsBool(opt, text, man, cur, val, set));
  PetscCall(OptionsRecordInt(PetscOptionsObject->prefix, opt, (PetscInt)*val, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHOptionsEList(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char man[], const char *const *list, PetscInt n, const char cur[], PetscInt *val, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsEList(opt, text, man, list, n, cur, val, set));
  PetscCall(OptionsRecord(PetscOptionsObject->prefix, opt, list[*val], set));
  PetscFunctionReturn(PETSC_SUCCESS);
}


PetscErrorCode OptionsDeprecated(PetscOptionItems *PetscOptionsObject, const char *old, const char *now)
{
  char          *prefix = PetscOptionsObject->prefix, value[PETSC_MAX_PATH_LEN] = "";
  PetscBool      given_old, given_now;
  PetscErrorCode ierr;
  int            k;
  PetscFunctionBeginUser;
  for (k = 0; k < nrenamed && strcmp(renamed[k].old, old); k++) {}
  if (k == nrenamed) {
    PetscCheck(nrenamed < (int)(sizeof(renamed) / sizeof(renamed[0])), PETSC_COMM_SELF, PETSC_ERR_PLIB, "More than %d renamed options", nrenamed);
    renamed[nrenamed].old   = old; /* string literals */
    renamed[nrenamed++].now = now;
  }
  PetscCall(PetscOptionsHasName(PetscOptionsObject->options, NULL, old, &given_old));
  if (!given_old) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscOptionsGetString(PetscOptionsObject->options, NULL, now, value, sizeof(value), &given_now));
  PetscOptionsObject->prefix = NULL; /* both names are full */
  ierr                       = PetscOptionsDeprecated(old, now, OPT_RENAMED_IN, NULL);
  PetscOptionsObject->prefix = prefix;
  PetscCall(ierr);
  if (given_now) PetscCall(PetscOptionsSetValue(PetscOptionsObject->options, now, value[0] ? value : NULL)); /* the new name wins */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsRenameAll(const char *all, char **out)
{
  size_t len = strlen(all), longest = 0;
  char  *copy, *tok, *rest;
  PetscFunctionBeginUser;
  for (int k = 0; k < nrenamed; k++) longest = PetscMax(longest, strlen(renamed[k].now));
  PetscCall(PetscCalloc1(len + (len / 2 + 1) * longest + 1, out)); /* every name replaced by the longest */
  PetscCall(PetscStrallocpy(all, &copy));
  for (rest = copy; (tok = strsep(&rest, " "));) {
    const char *name = tok;
    if (!*tok) continue;
    for (int k = 0; k < nrenamed; k++)
      if (!strcmp(tok, renamed[k].old)) name = renamed[k].now;
    if ((*out)[0]) strcat(*out, " ");
    strcat(*out, name);
  }
  PetscCall(PetscFree(copy));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The options of a database, one a line ("-name value"), into a string to free(). */
static PetscErrorCode OneALine(PetscOptions db, char **out)
{
  char  *all, *tok, *rest;
  size_t len = 0;
  FILE  *mem;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(db, &all));
  mem = open_memstream(out, &len);
  PetscCheck(mem, PETSC_COMM_SELF, PETSC_ERR_MEM, "Out of memory");
  for (rest = all; (tok = strsep(&rest, " "));) { /* one option a line: a value follows its name */
    if (!*tok) continue;
    if (tok[0] == '-' && !(tok[1] >= '0' && tok[1] <= '9') && tok[1] != '.') fprintf(mem, "%s%s", ftell(mem) ? "\n" : "", tok);
    else fprintf(mem, " %s", tok);
  }
  fprintf(mem, "\n");
  fclose(mem);
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether option `name` starts a line of `list`. */
static PetscBool Listed(const char *list, const char *name)
{
  size_t n = strlen(name);
  for (const char *p = strstr(list, name); p; p = strstr(p + 1, name))
    if ((p == list || p[-1] == '\n') && (p[n] == ' ' || p[n] == '\n' || p[n] == 0)) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode OptionsUsedWrite(MPI_Comm comm, const char *outdir, const char *header, const char *chosen)
{
  PetscMPIInt rank;
  char        path[PETSC_MAX_PATH_LEN], *given = NULL, *defaults = NULL, *copy = NULL, *tok, *rest;
  FILE       *f;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/options_used", outdir));
  PetscCall(OneALine(NULL, &given));
  if ((f = fopen(path, "w"))) {
    fprintf(f, "# %s\n# options given\n%s# chosen by the scene and the schemes (not given)\n", header, given);
    PetscCall(PetscStrallocpy(chosen ? chosen : "", &copy));
    for (rest = copy; (tok = strsep(&rest, "\n"));) {
      char name[256];
      if (sscanf(tok, "%255s", name) == 1 && (name[0] == '#' || !Listed(given, name))) fprintf(f, "%s\n", tok);
    }
    if (recorded) { /* the defaults the run read, unless given or chosen above */
      PetscCall(OneALine(recorded, &defaults));
      fprintf(f, "# defaults of this version that the run read\n");
      for (rest = defaults; (tok = strsep(&rest, "\n"));) {
        char name[256];
        if (sscanf(tok, "%255s", name) == 1 && !Listed(given, name) && !(chosen && Listed(chosen, name))) fprintf(f, "%s\n", tok);
      }
    }
    fclose(f);
  } else PetscCall(PetscPrintf(PETSC_COMM_SELF, "sphfsi: warning: cannot write %s\n", path));
  PetscCall(PetscFree(copy));
  free(given);
  free(defaults);
  PetscFunctionReturn(PETSC_SUCCESS);
}
