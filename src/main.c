static const char help[] = "sphfsi: Smoothed Particle Hydrodynamics for fluid-structure interaction (ISPH/WCSPH fluid, hypo-elastic WCSPH solids).\n"
                           "Usage: mpiexec -n P bin/sphfsi -options_file cases/NAME.opts [-option value ...]\n"
                           "Exit status: 0 done; 3 stopped by a signal or -max_wall_time (checkpoint written: -restart it); 4 numerical fault (last good state written); other: bad input or error.\n\n";

#include <sphfsi/sim.h>
#include <sphfsi/guard.h>
#include <stdio.h>
#include <string.h>

/* PETSc cannot report a missing options file before it is initialised: say it here. */
static int CheckOptionsFiles(int argc, char **argv)
{
  for (int k = 1; k < argc - 1; k++) {
    FILE *f;
    if (strcmp(argv[k], "-options_file") && strcmp(argv[k], "-options_file_yaml")) continue;
    if (!(f = fopen(argv[k + 1], "r"))) {
      fprintf(stderr, "sphfsi: cannot open the options file given by -options_file: %s (run from the source directory, or give its full path)\n", argv[k + 1]);
      return 1;
    }
    fclose(f);
  }
  return 0;
}

/* PETSc's "Input string abc has no numeric value" does not say which option: name it, then let the
 * usual handler print the error.  An error handler cannot raise errors: no PetscCall in it. */
static PetscErrorCode NameTheOption(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  const char *forms[] = {"Input string %255s has no", "Unknown logical value: %255s"};
  char        bad[256];
  if (p == PETSC_ERROR_INITIAL && mess)
    for (int k = 0; k < 2; k++) {
      char *all = NULL, *tok, *rest, *prev = NULL;
      if (sscanf(mess, forms[k], bad) != 1 || PetscOptionsGetAll(NULL, &all)) continue;
      for (rest = all; (tok = strsep(&rest, " "));) {
        if (*tok && !strcmp(tok, bad) && prev && prev[0] == '-') (void)PetscErrorPrintf("sphfsi: option %s has the value '%s', which is not %s\n", prev, bad, k ? "a logical value (true/false)" : strstr(mess, "integer") ? "an integer" : "a number");
        if (*tok) prev = tok;
      }
      (void)PetscFree(all);
    }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

/* Options nobody read are an error: a misspelt -t_ned would otherwise pass silently.  The scheme
 * families (-isph_*, -wcsph_*, -ppe_*, -fsi_implicit, -fsi_dt_transit, PETSc's -ksp_*, -pc_*) and PETSc's
 * own (-log_*, ...) only warn: a case file may carry them for the other fluid scheme.  -unused_options warn: only warnings. */
static PetscErrorCode CheckUnusedOptions(MPI_Comm comm)
{
  const char *petsc[] = {"isph_", "wcsph_", "ppe_", "fsi_implicit", "fsi_dt_transit", "ksp_", "pc_", "mat_", "vec_", "sf_", "log", "info", "malloc", "options_", "viewer", "history", "on_error", "no_signal_handler", "fp_trap", "check_pointer_intensity", "memory_view", "error_output", "help", "nox", "use_gpu_aware_mpi", "unused_options"};
  const char *modes[] = {"error", "warn", "UnusedMode", "UNUSED_", NULL};
  PetscInt    n, mode = 0, nbad = 0;
  char      **names, **values, list[2048] = "";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Options check", "");
  PetscCall(PetscOptionsEList("-unused_options", "Options that this run does not read (misspelt, or of another scene or scheme): error or warn", "", modes, 2, modes[0], &mode, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++) {
    PetscBool family = PETSC_FALSE;
    for (size_t j = 0; j < sizeof(petsc) / sizeof(petsc[0]); j++)
      if (!strncmp(names[k], petsc[j], strlen(petsc[j]))) family = PETSC_TRUE;
    if (family) {
      PetscCall(PetscPrintf(comm, "sphfsi: warning: option -%s is not used by this run\n", names[k]));
      continue;
    }
    nbad++;
    PetscCall(PetscStrlcat(list, " -", sizeof(list)));
    PetscCall(PetscStrlcat(list, names[k], sizeof(list)));
    if (values[k]) {
      PetscCall(PetscStrlcat(list, " ", sizeof(list)));
      PetscCall(PetscStrlcat(list, values[k], sizeof(list)));
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  if (nbad && mode == 1) PetscCall(PetscPrintf(comm, "sphfsi: warning: option(s) not used by this run:%s\n", list));
  PetscCheck(!nbad || mode == 1, comm, PETSC_ERR_USER_INPUT, "Option(s) not used by this run:%s.  Misspelt, or for another scene or scheme? -help lists the options this run reads; -unused_options warn runs anyway", list);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim      sim;
  PetscInt status;
  if (CheckOptionsFiles(argc, argv)) return 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(GuardInstallSignals());
  PetscCall(PetscPushErrorHandler(NameTheOption, NULL));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(CheckUnusedOptions(PETSC_COMM_WORLD));
  PetscCall(PetscPopErrorHandler());
  PetscCall(SimRun(sim));
  status = sim->exit_status;
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return (int)status;
}
