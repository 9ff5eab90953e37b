/* Walls of wall + dummy particles (section 2.5).  With WCSPH their pressure is extrapolated from
 * the fluid (Adami, Hu & Adams 2012), which holds the hydrostatic balance and keeps fluid out;
 * with ISPH it comes from the pressure Poisson equation (ppe.c). */
#pragma once
#include <sphfsi/sim.h>

/* Pressure, density and viscous velocity of owned wall/dummy particles, then ghosts refreshed. */
PetscErrorCode BoundaryWallState(Sim sim);
/* Only the no-slip velocity seen by the viscous term (ISPH), then ghosts refreshed. */
PetscErrorCode BoundaryWallVelocity(Sim sim);
