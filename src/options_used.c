#include <sphfsi/options_used.h>
#include <stdio.h>
#include <string.h>

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
  char        path[PETSC_MAX_PATH_LEN], *all = NULL, *given = NULL, *copy = NULL, *tok, *rest;
  size_t      len = 0;
  FILE       *mem, *f;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/options_used", outdir));
  PetscCall(PetscOptionsGetAll(NULL, &all));
  mem = open_memstream(&given, &len);
  PetscCheck(mem, PETSC_COMM_SELF, PETSC_ERR_MEM, "Out of memory for %s", path);
  for (rest = all; (tok = strsep(&rest, " "));) { /* one option a line: a value follows its name */
    if (!*tok) continue;
    if (tok[0] == '-' && !(tok[1] >= '0' && tok[1] <= '9') && tok[1] != '.') fprintf(mem, "%s%s", ftell(mem) ? "\n" : "", tok);
    else fprintf(mem, " %s", tok);
  }
  fprintf(mem, "\n");
  fclose(mem);
  if ((f = fopen(path, "w"))) {
    fprintf(f, "# %s\n# options given\n%s# chosen by the scene and the schemes (not given)\n", header, given);
    PetscCall(PetscStrallocpy(chosen ? chosen : "", &copy));
    for (rest = copy; (tok = strsep(&rest, "\n"));) {
      char name[256];
      if (sscanf(tok, "%255s", name) == 1 && (name[0] == '#' || !Listed(given, name))) fprintf(f, "%s\n", tok);
    }
    fclose(f);
  } else PetscCall(PetscPrintf(PETSC_COMM_SELF, "sphfsi: warning: cannot write %s\n", path));
  PetscCall(PetscFree(copy));
  free(given);
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}
