static const char help[] = "sphfsi: Smoothed Particle Hydrodynamics for fluid-structure interaction (ISPH/WCSPH fluid, hypo-elastic WCSPH solids).\n"
                           "Usage: mpiexec -n P bin/sphfsi -options_file cases/NAME.opts [-option value ...]\n\n";

#include <sphfsi/sim.h>
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

int main(int argc, char **argv)
{
  Sim sim;
  if (CheckOptionsFiles(argc, argv)) return 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(SimRun(sim));
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
