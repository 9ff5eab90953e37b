#include "base/material.h"
#include "base/options_used.h"

PetscErrorCode FluidMaterialSetFromOptions(MPI_Comm comm, const SPHKernel *kernel, PetscInt dim, PetscReal v_ref, FluidMaterial *fl, PetscReal *start_jitter)
{
  PetscBool norm = PETSC_TRUE, ceiling = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (fl->c0 <= 0) fl->c0 = 10.0 * v_ref;
  PetscOptionsBegin(comm, "fluid_", "Fluid material (both schemes)", "Fluid");
  PetscCall(OptDeprecated("-rho0", "-fluid_rho0"));
  PetscCall(OptDeprecated("-mu", "-fluid_mu"));
  PetscCall(OptDeprecated("-eta", "-fluid_eta"));
  PetscCall(OptDeprecated("-lap_normalise", "-fluid_lap_normalise"));
  PetscCall(OptDeprecated("-c0", "-fluid_c0"));
  PetscCall(OptDeprecated("-xsph", "-fluid_xsph"));
  PetscCall(OptDeprecated("-start_jitter", "-fluid_start_jitter"));
  PetscCall(OptDeprecated("-shift_correct", "-fluid_shift_correct"));
  PetscCall(OptReal("-rho0", "Fluid reference density (kg/m^3)", "", fl->rho0, &fl->rho0, NULL));
  PetscCall(OptReal("-mu", "Fluid dynamic viscosity (Pa s), Eq. 16", "", fl->mu, &fl->mu, NULL));
  PetscCall(OptReal("-eta", "Regularisation eta / h of the laminar viscosity (Eq. 16) and the pressure Laplacian (Eq. 22), r^2 / (r^2 + eta^2 h^2); the paper 0.1, which weakens the nearest pairs by 4 % at h = 2 dx (-fluid_lap_normalise restores the operator's lattice sum)", "", fl->eta, &fl->eta, NULL));
  PetscCall(OptBool("-lap_normalise", "Scale the laminar viscosity (Eq. 16) and the pressure Laplacian (Eq. 22) so that they are exact on the lattice for the run's kernel, h / dx and -fluid_eta (kernel.h)", "", norm, &norm, NULL));
  PetscCall(OptReal("-c0", "Artificial sound speed (m/s), Eq. 20; default 10x the scene's expected maximum speed", "", fl->c0, &fl->c0, NULL));
  PetscCall(OptReal("-xsph", "XSPH epsilon, Eq. 44; 0 = off", "", fl->xsph, &fl->xsph, NULL));
  PetscCall(OptReal("-start_jitter", "Displace each particle of the fluid's start lattice at random by up to this fraction of dx in x and y (by its id: the same on any number of ranks); a perfect lattice gives way all at once where the flow squeezes it (Taylor-Green's stagnation points); 0 = the lattice", "", *start_jitter, start_jitter, NULL));
  PetscCall(OptBool("-shift_correct", "With particle shifting (-wcsph_shift, -isph_shift): correct a shifted particle's velocity to its new place, v += dr . grad v", "", fl->shift_correct, &fl->shift_correct, NULL));
  PetscCall(OptBool("-force_gauge", "Forces on named bodies (-body_force, the Turek-Hron drag and lift) with the pressure measured from the mean over the body's pairs: a uniform pressure then pushes no body, as on any closed surface, where the discrete sum of the pairs' pressure term gives it a push proportional to the particles' disorder (docs/turek_hron.md); 0: the momentum exchanged, as the body gets it; default on with WCSPH, off with ISPH, whose sum does not move with the level", "", fl->force_gauge, &fl->force_gauge, NULL));
  PetscCall(OptBool("-shift_ceiling", "With particle shifting: its coefficient A h |v| dt at most the kernel's monotone limit (0.43 h^2 for the cubic spline at 1.3 dx), past which the shift overshoots the particles' short modes each step (ISPH at A > 1.7 and CFL 0.25: an oscillation from step to step in the forces on a body)", "", ceiling, &ceiling, NULL));
  PetscCall(OptReal("-shift_speed", "With particle shifting: its coefficient A h |v| dt with |v| at least this speed (m/s), so that slow water (a wake, a vortex's core) is shifted too; there A h |v| dt vanishes, and in tension (WCSPH's pressure below 0) its particles clump (Sun et al. 2017 shift every particle at the flow's largest speed); 0 = the particle's own speed", "", fl->shift_vmin, &fl->shift_vmin, NULL));
  PetscOptionsEnd();
  PetscCheck(fl->shift_vmin >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_shift_speed %g must be >= 0 (m/s)", (double)fl->shift_vmin);
  PetscCheck(fl->rho0 > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_rho0 %g must be > 0", (double)fl->rho0);
  PetscCheck(fl->mu >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_mu %g must be >= 0", (double)fl->mu);
  PetscCheck(fl->eta > 0 && fl->eta <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_eta %g must be in (0, 1] (eta / h; the paper 0.1)", (double)fl->eta);
  fl->shift_dmax = ceiling ? KernelShiftCeiling(kernel) : 0;
  fl->lap_kappa = norm ? (PetscReal)dim / KernelLatticeSum(kernel, LATTICE_LAPLACIAN, fl->eta) : 1.0;
  PetscCheck(fl->c0 > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_c0 %g must be > 0", (double)fl->c0);
  PetscCheck(*start_jitter >= 0 && *start_jitter <= 0.25, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_start_jitter %g must be in [0, 0.25] (a fraction of dx)", (double)*start_jitter);
  PetscCheck(fl->xsph >= 0 && fl->xsph <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_xsph %g must be in [0, 1]", (double)fl->xsph);
  PetscFunctionReturn(PETSC_SUCCESS);
}
