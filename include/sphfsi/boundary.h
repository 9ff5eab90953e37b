/* Walls of wall + dummy particles (section 2.5).  Their pressure is extrapolated from the fluid
 * (Adami, Hu & Adams 2012), which holds the hydrostatic balance and keeps fluid out. */
#pragma once
#include <sphfsi/sim.h>

/* Pressure, density and viscous velocity of owned wall/dummy particles, then ghosts refreshed. */
PetscErrorCode BoundaryWallState(Sim sim);
