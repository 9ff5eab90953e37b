/* Open boundaries by buffer zones (docs/open_boundaries.md): inlets with a prescribed velocity and
 * outlets at a given pressure, each a buffer of fluid particles outside a plane.  The fluids call it
 * at fixed points of their steps; a run without open boundaries has ph->open NULL and pays nothing.
 *
 * Each buffer particle carries its boundary's number k + 1 in the field open_zone (0: the fluid).
 *   inlet   its velocity is the profile's (OpenImpose), it feels no acceleration (OpenRates); its
 *           density is the fluid's next to it (OpenState: a zero normal gradient, so that the flow
 *           decides the pressure at the inlet).  One that crosses the plane joins the fluid, and a new buffer particle is made
 *           `rows` spacings behind it (OpenAfterDrift marks it, OpenInflow makes it during the
 *           rebuild): ids in the order of the crossing particles' ids, the same on any number of ranks.
 *   outlet  fluid crossing the plane joins the buffer, whose density is the equation of state's at the
 *           outlet's pressure (WCSPH) or whose pressure is the PPE's Dirichlet value (ISPH), and whose
 *           velocity is the fluid's next to it (OpenRates: a zero normal gradient); it leaves at the
 *           domain's end (the outflow). */
#pragma once
#include "physics/physics.h"
#include "base/refdata.h"
#include <sphfsi/scene.h>

#define OPEN_MAX SCENE_MAX_OPEN

typedef struct _n_Open *Open;
struct _n_Open {
  PetscInt         n;
  OpenBoundarySpec b[OPEN_MAX];
  Series           table[OPEN_MAX]; /* PROFILE_TABLE: u against the cross-section coordinate */
  PetscReal        mass_in;         /* fluid mass that crossed an inlet's plane so far (all ranks) */
  PetscInt        *next_id;         /* the run's next particle id (the driver's counter) */
  /* particles to make at the next rebuild (this rank's): their parents' ids and the new positions */
  PetscInt   nnew, capnew;
  PetscInt  *parent, *zone;
  PetscReal *xnew, *mnew, *hnew, *rnew;
};

PetscErrorCode OpenCreate(Open *open);
PetscErrorCode OpenDestroy(Open *open);
/* Check and add one (collective: the bad input's message on every rank). */
PetscErrorCode OpenAdd(Physics *ph, Open open, const OpenBoundarySpec *spec, const PetscReal dom_lo[], const PetscReal dom_hi[]);
/* After the particles are made: the buffers' rows (0: the kernel's reach), the checks that need the
 * kernel, the zone of every fluid particle, the inlets' velocities. */
PetscErrorCode OpenSetUp(Physics *ph);
/* The inlets' buffer velocities at time t (and ISPH's predicted velocities) */
PetscErrorCode OpenImpose(Physics *ph, PetscReal t);
/* WCSPH, before the pressure: an inlet's buffer density is the fluid's next to it (a zero normal
 * gradient: the flow sets the inlet's pressure), an outlet's the equation of state's at its pressure;
 * the ghosts refreshed (one halo exchange of the density a step) */
PetscErrorCode OpenState(Physics *ph);
/* After the fluid's accelerations: buffer particles feel none; an outlet's take the fluid's velocity */
PetscErrorCode OpenRates(Physics *ph);
/* The buffers move as their boundaries say: no shifting or XSPH correction of their positions (an
 * inlet's rows stay a lattice, so that a new particle lands `rows` spacings behind its parent in the
 * gap the row leaves) */
PetscErrorCode OpenNoShift(Physics *ph);
/* After the drift: the outlets' densities, the crossings of the planes, the particles to make (and
 * with any, the next update rebuilds) */
PetscErrorCode OpenAfterDrift(Physics *ph);
/* The neighbourhood's inflow hook: make the marked particles (no ghosts exist then) */
PetscErrorCode OpenInflow(void *ctx);
/* ISPH, particle a's role in the pressure equation: an outlet's buffer gives its Dirichlet rows (p = 0,
 * fs set), an inlet's none (fs cleared: its far end's thin kernel sum is no free surface) and no
 * source (src 0: its velocity is given; its rows carry the fluid's pressure on to a zero normal
 * gradient at its end) */
void OpenPressureRows(const Physics *ph, PetscInt a, PetscReal *fs, PetscReal *src);
