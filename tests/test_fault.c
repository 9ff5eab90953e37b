/* A NaN that appears in a step stops the run (guard.h): exit status 4, a message naming the field,
 * the particle and the step, and the last good state written, finite and restartable.  The NaN is
 * let in through gravity after 15 steps of a dam break (the state itself was checked finite then),
 * so it first shows in step 16; the last good state is the copy of step 10.  Run on 2 ranks. */
#include "run/sim.h"
#include <sphfsi.h>
#include "run/guard.h"
#include <math.h>

int main(int argc, char **argv)
{
  Sim         sim;
  char        msg[1024];
  PetscInt    status, bad = 0;
  const char *good = "out/test_fault/last_good.h5";

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsSetValue(NULL, "-case", "dam_break"));
  PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
  PetscCall(PetscOptionsSetValue(NULL, "-t_end", "0.05"));
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_fault"));
  PetscCall(PetscOptionsSetValue(NULL, "-max_steps", "15"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(SimRun(sim));
  PetscCheck(sim->exit_status == 0 && sim->phys.step == 15, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The first 15 steps did not run cleanly");
  sim->phys.g[1]      = NAN; /* the state is finite; the next step's accelerations are not */
  sim->max_steps = 1000;
  PetscCall(SimRun(sim));
  status = sim->exit_status;
  PetscCall(PetscStrncpy(msg, sim->guard->msg, sizeof(msg)));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "guard message: %s\n", msg));
  PetscCheck(status == SIM_EXIT_FAULT, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Exit status %d after a NaN, expected %d", (int)status, SIM_EXIT_FAULT);
  PetscCheck(strstr(msg, "= nan at particle id") && strstr(msg, "after step 16 "), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The message does not name the NaN, the particle and step 16");
  PetscCheck(sim->guard->good.i[0] == 10, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The last good state is of step %d, expected 10", (int)sim->guard->good.i[0]);
  PetscCall(SimDestroy(&sim));

  /* the last good state loads, at step 10, every field finite */
  PetscCall(PetscOptionsSetValue(NULL, "-restart", good));
  PetscCall(PetscOptionsSetValue(NULL, "-max_steps", "10"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_fault/restart"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  for (PetscInt f = 0; f < FIELD_COUNT; f++)
    for (PetscInt k = 0; sim->P->f[f].on && k < sim->P->n * sim->P->f[f].width; k++) bad += PetscIsInfOrNanReal(sim->P->f[f].a[k]);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCheck(!bad && sim->phys.step == 10, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "last_good.h5: %d non-finite values, step %d (expected 0, 10)", (int)bad, (int)sim->phys.step);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "fault: a NaN in step 16 stops the run with status %d and its message; last_good.h5 (step 10) loads, every field finite\n", (int)status));
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
