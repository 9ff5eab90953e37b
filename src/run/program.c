/* The program sphfsi as library calls (<sphfsi.h>): start, run the case of the options, finish.  bin/sphfsi
 * is these and the built-in scenes (src/app/main.c). */
static const char help[] = "sphfsi: Smoothed Particle Hydrodynamics for fluid-structure interaction (ISPH/WCSPH fluid, hypo-elastic WCSPH solids).\n"
                           "Usage: mpiexec -n P bin/sphfsi -options_file cases/NAME.opts [-option value ...]   (bin/sphfsi -version: version and libraries)\n"
                           "Exit status: 0 done; 2 bad input (one line on stderr says which option or file, and what is allowed); 3 stopped by a signal or -max_wall_time (checkpoint written: -restart it); 4 numerical fault (last good state written); 5 output could not be written (disk full, quota; the last complete checkpoint is kept); other: internal error (PETSc's trace).\n\n";

#include "run/sim.h"
#include "run/guard.h"
#include "base/version.h"
#include "base/options_used.h"
#include "io/outdir.h"
#include "run/scene_registry.h"
#include <sphfsi.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

/* The MPI rank before MPI is initialised, from the launcher's environment (0 without one). */
static int LauncherRank(void)
{
  const char *vars[] = {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"};
  for (size_t k = 0; k < sizeof(vars) / sizeof(vars[0]); k++)
    if (getenv(vars[k])) return atoi(getenv(vars[k]));
  return 0;
}

/* PETSc cannot report a missing options file before it is initialised: say it here, on the first
 * rank only.  The others go on into MPI_Init, which waits for the first; that one exits with its
 * line written, and the launcher then ends them (had they exited at once, the launcher could end
 * the first before it wrote: with Open MPI's -mca odls_base_sigkill_timeout 0, it did). */
static int CheckOptionsFiles(int argc, char **argv)
{
  if (LauncherRank() != 0) return 0;
  for (int k = 1; k < argc - 1; k++) {
    FILE *f;
    if (strcmp(argv[k], "-options_file") && strcmp(argv[k], "-options_file_yaml")) continue;
    if (!(f = fopen(argv[k + 1], "r"))) {
      fprintf(stderr, "sphfsi: error: cannot open the options file given by -options_file: %s (run from the source directory, or give its full path)\n", argv[k + 1]);
      return SIM_EXIT_BAD_INPUT;
    }
    fclose(f);
  }
  return 0;
}

/* Bad input found while setting up (a value out of range, an unknown type, an unused option, an
 * unreadable restart file) ends the run with one line and SIM_EXIT_BAD_INPUT, without PETSc's banner;
 * internal errors (and errors only some ranks see) keep PETSc's trace and abort. */
static struct {
  PetscBool quiet;         /* the error being raised is bad input, seen by every rank */
  char      message[1024]; /* its one line */
} bad_input;

static PetscBool IsInputError(PetscErrorCode n)
{
  return (PetscBool)(n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_ARG_OUTOFRANGE || n == PETSC_ERR_ARG_WRONG || n == PETSC_ERR_ARG_INCOMP || n == PETSC_ERR_ARG_UNKNOWN_TYPE || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_READ || n == PETSC_ERR_FILE_UNEXPECTED);
}

/* PETSc's "Input string abc has no numeric value" does not say which option: name it.  An error
 * handler cannot raise errors: no PetscCall in it. */
static void NameTheOption(const char *mess, char *line, size_t len)
{
  const char *forms[] = {"Input string %255s has no", "Unknown logical value: %255s"};
  char        bad[256];
  for (int k = 0; k < 2; k++) {
    char *all = NULL, *tok, *rest, *prev = NULL;
    if (sscanf(mess, forms[k], bad) != 1 || PetscOptionsGetAll(NULL, &all)) continue;
    for (rest = all; (tok = strsep(&rest, " "));) {
      if (*tok && !strcmp(tok, bad) && prev && prev[0] == '-') snprintf(line, len, "option %s has the value '%s', which is not %s", prev, bad, k ? "a logical value (true/false)" : strstr(mess, "integer") ? "an integer" : "a number");
      if (*tok) prev = tok;
    }
    (void)PetscFree(all);
  }
}

static PetscErrorCode SetUpErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) {
    int size = 0, world = 1;
    (void)MPI_Comm_size(comm, &size);
    (void)MPI_Comm_size(PETSC_COMM_WORLD, &world);
    /* PETSc's options parsing raises on PETSC_COMM_SELF (an unknown -fluid: PETSC_ERR_USER), but
     * every rank parses the same options */
    const PetscBool parsing = (PetscBool)(fun && !strncmp(fun, "PetscOptions", 12));
    bad_input.quiet         = (PetscBool)(mess && ((IsInputError(n) && size == world) || (parsing && (IsInputError(n) || n == PETSC_ERR_USER))));
    if (bad_input.quiet) {
      snprintf(bad_input.message, sizeof(bad_input.message), "%s", mess);
      NameTheOption(mess, bad_input.message, sizeof(bad_input.message));
      for (char *c = bad_input.message; *c; c++)
        if (*c == '\n') *c = ' ';
    }
  }
  if (bad_input.quiet) return n;
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

/* Options nobody read are an error: a misspelt -t_ned would otherwise pass silently.  Exceptions:
 * - the other fluid scheme's families (-isph_*, -ppe_*, -fsi_implicit, -fsi_dt_transit in a WCSPH
 *   run; -wcsph_*, and -alpha, -delta, their old names, in an ISPH run) pass silently: a case file
 *   carries both schemes' settings;
 * - this scheme's families and PETSc's own (-log_*, -mat_*, ...) warn: some are read only in some
 *   set-ups (e.g. -isph_blend with -isph_source blend);
 * - unprefixed -ksp_* / -pc_* are an error with a hint: the pressure solver reads -ppe_ksp_*, -ppe_pc_*.
 * -unused_options warn: only warnings. */
static PetscErrorCode CheckUnusedOptions(MPI_Comm comm, FluidScheme fluid)
{
  const struct {
    const char *prefix;
    int         owner; /* -1: PETSc's own; else the FluidScheme that reads it */
  } families[] = {
    {"isph_", FLUID_ISPH}, {"ppe_", FLUID_ISPH}, {"fsi_implicit", FLUID_ISPH}, {"fsi_dt_transit", FLUID_ISPH}, {"wcsph_", FLUID_WCSPH},
    {"alpha", FLUID_WCSPH}, {"delta", FLUID_WCSPH}, /* the old names of -wcsph_alpha, -wcsph_delta (deprecated in 0.9.0) */
    {"mat_", -1}, {"vec_", -1}, {"sf_", -1}, {"log", -1}, {"info", -1}, {"malloc", -1}, {"options_", -1}, {"viewer", -1}, {"history", -1}, {"on_error", -1}, {"no_signal_handler", -1}, {"fp_trap", -1}, {"check_pointer_intensity", -1}, {"memory_view", -1}, {"error_output", -1}, {"help", -1}, {"nox", -1}, {"use_gpu_aware_mpi", -1}, {"unused_options", -1},
  };
  const char *modes[] = {"error", "warn", "UnusedMode", "UNUSED_", NULL};
  PetscInt    n, mode = 0, nbad = 0, nsolver = 0;
  char      **names, **values, list[2048] = "";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Options check", "");
  PetscCall(OptEList("-unused_options", "Options that this run does not read (misspelt, or of another scene or scheme): error or warn", "", modes, 2, modes[0], &mode, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++) {
    int owner = -2; /* -2: no family */
    for (size_t j = 0; j < sizeof(families) / sizeof(families[0]); j++)
      if (!strncmp(names[k], families[j].prefix, strlen(families[j].prefix))) owner = families[j].owner;
    if (owner >= 0 && owner != (int)fluid) continue; /* the other scheme's */
    if (owner != -2) {
      PetscCall(PetscPrintf(comm, "sphfsi: warning: option -%s is not used by this run\n", names[k]));
      continue;
    }
    nbad++;
    if (!strncmp(names[k], "ksp_", 4) || !strncmp(names[k], "pc_", 3)) nsolver++;
    PetscCall(PetscStrlcat(list, " -", sizeof(list)));
    PetscCall(PetscStrlcat(list, names[k], sizeof(list)));
    if (values[k]) {
      PetscCall(PetscStrlcat(list, " ", sizeof(list)));
      PetscCall(PetscStrlcat(list, values[k], sizeof(list)));
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  if (nbad && mode == 1) PetscCall(PetscPrintf(comm, "sphfsi: warning: option(s) not used by this run:%s\n", list));
  PetscCheck(!nsolver || mode == 1, comm, PETSC_ERR_USER_INPUT, "Option(s) not used by this run:%s.  The pressure equation's solver reads its options with the prefix -ppe_ (-ppe_ksp_rtol, -ppe_pc_type, ...)", list);
  PetscCheck(!nbad || mode == 1, comm, PETSC_ERR_USER_INPUT, "Option(s) not used by this run:%s.  Misspelt, or for another scene or scheme? -help lists the options this run reads; -unused_options warn runs anyway", list);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Scene, schemes, decomposition and the options check: everything before the first step. */
static PetscErrorCode SetUp(Sim *sim)
{
  PetscFunctionBeginUser;
  PetscCall(SimCreate(PETSC_COMM_WORLD, sim));
  PetscCall(SimSetFromOptions(*sim));
  PetscCall(SimSetUp(*sim));
  if (!(*sim)->help && (*sim)->ready) PetscCall(CheckUnusedOptions(PETSC_COMM_WORLD, (*sim)->phys.fluid));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -help without a scene: PETSc printed the generic options; name the scenes, whose options -help
 * lists once one is chosen. */
static PetscBool HelpWithoutScene(void)
{
  PetscBool help = PETSC_FALSE, scene = PETSC_FALSE;
  char      names[512];
  if (PetscOptionsHasHelp(NULL, &help) || !help) return PETSC_FALSE;
  if (PetscOptionsHasName(NULL, NULL, "-case", &scene) || scene) return PETSC_FALSE;
  if (PetscOptionsHasName(NULL, NULL, "-restart", &scene) || scene) return PETSC_FALSE;
  if (SceneListNames(names, sizeof(names))) return PETSC_FALSE;
  (void)PetscPrintf(PETSC_COMM_WORLD, "\nsphfsi: -help with -case NAME (or -options_file cases/NAME.opts) lists every option of that case's modules with its value; NAME is one of: %s\n", names);
  return PETSC_TRUE;
}

/* A stop requested while setting up: nothing was computed, nothing to checkpoint. */
static PetscErrorCode StoppedInSetUp(Sim sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(sim->comm, "sphfsi: stopped: %s; nothing was computed, so no checkpoint was written: start the run again (exit status %d)\n", sim->guard->msg, SIM_EXIT_STOPPED));
  PetscCall(SimWriteSummary(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscBool SPHFSIInitialize(int *argc, char ***argv, const char help_text[], int *status)
{
  *status = 0;
  for (int k = 1; k < *argc; k++) /* ours, not PETSc's banner; MPI and PETSc are not started */
    if (!strcmp((*argv)[k], "-version") || !strcmp((*argv)[k], "--version")) {
      if (LauncherRank() == 0) SphfsiVersionPrint(stdout);
      return PETSC_TRUE;
    }
  if ((*status = CheckOptionsFiles(*argc, *argv))) return PETSC_TRUE;
  for (int k = 1; k < *argc; k++) /* --help as -help (PETSc knows the one dash) */
    if (!strcmp((*argv)[k], "--help")) (*argv)[k] = (char *)"-help";
  if ((*status = (int)PetscInitialize(argc, argv, NULL, help_text ? help_text : help))) return PETSC_TRUE;
  if ((*status = (int)GuardInstallSignals())) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode SPHFSIRun(int *status)
{
  Sim            sim = NULL;
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  *status = 0;
  if (HelpWithoutScene()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscPushErrorHandler(SetUpErrorHandler, NULL));
  ierr = SetUp(&sim);
  PetscCall(PetscPopErrorHandler());
  if (!ierr && sim->help) { /* listed while setting up: nothing to run */
    PetscCall(SimDestroy(&sim));
    PetscCall(PetscOptionsClear(NULL));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!ierr && !sim->ready) { /* a signal during set-up */
    PetscCall(StoppedInSetUp(sim));
    PetscCall(SimDestroy(&sim));
    *status = SIM_EXIT_STOPPED;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!ierr) { /* OUTDIR/options_used: -options_file it to repeat the run */
    char header[256], chosen[512];
    PetscCall(PetscSNPrintf(header, sizeof(header), "sphfsi %s (commit %s): the options of this run, given, chosen and defaulted; -options_file this file repeats it (PETSc's own solver options not listed keep this PETSc version's defaults)", SPHFSIVersion(), SPHFSICommit()));
    /* the scene's values and -fluid_c0 (10x its speed) at full precision */
    PetscCall(PetscSNPrintf(chosen, sizeof(chosen), "-t_end %.17g\n-gravity %.17g,%.17g", (double)sim->t_end, (double)sim->phys.g[0], (double)sim->phys.g[1]));
    if (sim->phys.dim == 3) PetscCall(PetscSNPrintf(chosen + strlen(chosen), sizeof(chosen) - strlen(chosen), ",%.17g", (double)sim->phys.g[2]));
    PetscCall(PetscSNPrintf(chosen + strlen(chosen), sizeof(chosen) - strlen(chosen), "\n# -dx %.17g (from the scene's options)\n", (double)sim->phys.dx));
    if (sim->phys.has_fluid) PetscCall(PetscSNPrintf(chosen + strlen(chosen), sizeof(chosen) - strlen(chosen), "-fluid_c0 %.17g\n", (double)sim->phys.fl.c0));
    PetscCall(OptionsUsedWrite(PETSC_COMM_WORLD, sim->out.dir, header, chosen));
  }
  if (ierr && bad_input.quiet) { /* every rank has it: one line from rank 0, then a clean exit */
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "sphfsi: error: %s\n", bad_input.message));
    PetscCall(OutDirClose(sim ? &sim->out : NULL)); /* the output directory's lock, if the run got that far */
    PetscCall(PetscOptionsClear(NULL)); /* no "options left" list at PetscFinalize */
    *status = SIM_EXIT_BAD_INPUT;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(ierr);
  PetscCall(SimRun(sim));
  *status = (int)sim->exit_status;
  PetscCall(SimDestroy(&sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFSIFinalize(void) { return PetscFinalize(); }
