/* The force of the fluid on a named body (SimBodyForce, body_force.c) does not depend on the
 * pressure's gauge with -fluid_force_gauge (WCSPH's default, set here for ISPH too): a run's
 * pressure, raised by a constant on every particle (fluid, walls, ghosts, and the solids' view of
 * it), gives the same force to round-off, as the stress integral over a closed surface does.  The
 * momentum exchanged (-fluid_force_gauge 0) moves by the constant times the discrete sum of the
 * pairs' normals, which is not zero over disordered particles: the test requires that too, so
 * that it can fail.  Default: Turek-Hron CFD1 at 2 across the flag (its walls), 60 steps; another
 * scene with -case and its options (the solid flag: -turek_hron_case fsi2).  -shift Pa (1000). */
#include "run/sim.h"
#include "fluid/boundary.h"
#include <sphfsi.h>

/* p + c wherever a pair reads a pressure. */
static void ShiftPressure(Sim sim, PetscReal c)
{
  Particles  P  = sim->P;
  PetscReal *p  = PField(P, FIELD_P), *fv = PField(P, FIELD_FVIEW);
  for (PetscInt a = 0; a < P->n + P->ng; a++) {
    p[a] += c;
    if (fv && KindIsSolid(P->kind[a])) fv[3 * a] += c;
  }
}

static PetscErrorCode Force(Sim sim, PetscBool gauge, PetscReal f[3])
{
  PetscFunctionBeginUser;
  sim->phys.fl.force_gauge = gauge;
  PetscCall(SimBodyForce(sim, 1, f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim       sim;
  PetscReal c = 1000, f0[3], f1[3], r0[3], r1[3], dg = 0, dr = 0, scale = 0;
  PetscBool other;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-shift", &c, NULL));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-case", &other));
  if (!other) {
    PetscCall(PetscOptionsSetValue(NULL, "-case", "turek_hron"));
    PetscCall(PetscOptionsSetValue(NULL, "-turek_hron_case", "cfd1"));
    PetscCall(PetscOptionsSetValue(NULL, "-flag_ny", "2"));
  }
  PetscCall(PetscOptionsSetValue(NULL, "-max_steps", "60"));
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-progress_every", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_interval", "0"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(PetscStrncpy(sim->out.dir, "out/test_body_force", sizeof(sim->out.dir)));
  PetscCall(SimSetUp(sim));
  PetscCall(SimRun(sim));

  PetscCall(Force(sim, PETSC_TRUE, f0));
  PetscCall(Force(sim, PETSC_FALSE, r0));
  ShiftPressure(sim, c);
  PetscCall(Force(sim, PETSC_TRUE, f1));
  PetscCall(Force(sim, PETSC_FALSE, r1));
  for (PetscInt i = 0; i < 3; i++) {
    dg    = PetscMax(dg, PetscAbsReal(f1[i] - f0[i]));
    dr    = PetscMax(dr, PetscAbsReal(r1[i] - r0[i]));
    scale = PetscMax(scale, PetscAbsReal(r1[i]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "body_force (%s, %s, %d steps): the pressure raised by %g Pa moves the force by %.2e N/m with the gauge (bound 1e-9 of %.3g), by %.3g N/m as the momentum exchanged (must be > 0)\n", sim->scene->name, sim->phys.isph ? "isph" : "wcsph", (int)sim->phys.step, (double)c, (double)dg, (double)scale, (double)dr));
  PetscCheck(dg <= 1e-9 * scale, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The force with -fluid_force_gauge depends on the pressure's gauge: %g N/m for %g Pa", (double)dg, (double)c);
  PetscCheck(dr > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The momentum exchanged does not move with the gauge: the test shifted no pressure the force reads");
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
