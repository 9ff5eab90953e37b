/* Walls of wall + dummy particles (section 2.5), and solids as the fluid sees them (section 2.6).  With WCSPH their pressure is extrapolated from
 * the fluid (Adami, Hu & Adams 2012), which holds the hydrostatic balance and keeps fluid out;
 * with ISPH it comes from the pressure Poisson equation (ppe.c). */
#pragma once
#include "physics/physics.h"

/* Pressure, density and viscous velocity of owned wall/dummy particles (and the fluid view of
 * solids), then ghosts refreshed. */
PetscErrorCode BoundaryWallState(Physics *ph);
/* Only the no-slip velocity seen by the viscous term (ISPH), then ghosts refreshed. */
PetscErrorCode BoundaryWallVelocity(Physics *ph);

/* Particles that bound the fluid: walls and solids.  A solid next to fluid is, to the fluid, a
 * moving wall: its pressure is the fluid's pressure extrapolated onto it (Adami et al. 2012, with
 * the solid's acceleration), its density the fluid's at that pressure and its mass that density
 * times its own volume; FIELD_FVIEW holds (p, rho, m) so, and the pair forces it gets back are the
 * fluid's, reversed (Newton's third law). */
static inline PetscBool KindIsBoundary(PetscInt k) { return (PetscBool)(KindIsWall(k) || KindIsSolid(k)); }

/* Mass, density and pressure of neighbour b as the fluid sees it. */
static inline void FluidView(const PetscReal *fv, PetscInt kind, PetscInt b, const PetscReal *m, const PetscReal *rho, const PetscReal *p, PetscReal *mb, PetscReal *rb, PetscReal *pb)
{
  if (fv && KindIsSolid(kind)) { *pb = fv[3 * b]; *rb = fv[3 * b + 1]; *mb = fv[3 * b + 2]; }
  else { *mb = m[b]; *rb = rho[b]; *pb = p ? p[b] : 0; }
}
