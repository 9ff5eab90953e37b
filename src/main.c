static const char help[] = "sphfsi: Smoothed Particle Hydrodynamics for fluid-structure interaction (ISPH/WCSPH fluid, hypo-elastic WCSPH solids).\n"
                           "Usage: mpiexec -n P bin/sphfsi -options_file cases/NAME.opts [-option value ...]\n\n";

#include <sphfsi/sim.h>

int main(int argc, char **argv)
{
  Sim sim;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(SimRun(sim));
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
