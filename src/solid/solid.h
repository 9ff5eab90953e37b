/* Hypo-elastic solids by WCSPH (sections 2.2 and 2.4): pressure from the equation of state Eq. 20
 * with c0^2 = K / rho0, deviatoric stress from the Jaumann rate (Eqs. 7-8, 35-40), momentum Eq. 23
 * with artificial viscosity (Eq. 24) and artificial stress (Eqs. 25-34).  Explicit and per rank.
 * Particles of kind `clamp` are the part of a body held fixed: their density and stress evolve
 * like the solid's, so the stress field runs on into the clamp, but they never move. */
#pragma once
#include "physics/physics.h"

typedef enum { SOLID_GRAD_STANDARD = 0, SOLID_GRAD_CORRECTED } SolidGradient;
extern const char *const SolidGradients[];
/* updated: the seed's hypo-elastic scheme (Jaumann rate, neighbours and gradients in the current
 * configuration, artificial stress);  total: total-Lagrangian, a hyper-elastic (neo-Hookean)
 * stress from the deformation gradient, gradients in the reference configuration corrected once,
 * hourglass control (solid_total.c). */
typedef enum { SOLID_UPDATED = 0, SOLID_TOTAL } SolidFormulation;
extern const char *const SolidFormulations[];
extern const char *const SolidLaws[]; /* -solid_law: SolidLaw of <sphfsi/material.h> */

struct _p_Solid {
  SolidFormulation formulation;
  SolidGradient gradient;
  PetscReal     damping;   /* mass-proportional damping rate (1/s) for static solutions by dynamic relaxation; 0 = off */
  PetscBool     clamp_face; /* total: a clamp is a boundary face in the fits, not material (solid_total.c) */
  PetscBool     faces_placed; /* the clamp's face points are in X0 (done at the first SolidPrepare) */
  PetscBool     quadrature; /* total, order 2: second-order quadrature of each particle's cell (solid_terms.h) */
  PetscInt      order;     /* total: polynomial order the reference gradient reproduces (1 or 2) */
  PetscReal     hourglass; /* total: hourglass-control coefficient alpha (Ganzenmueller 2015); 0 = off */
  PetscReal     h_factor;  /* total: h / dx of the solid's own pairs (-solid_h_factor; default the run's -h_factor) */
  PetscReal     h_ratio;   /* total: h_factor / the run's: scales each particle's h in the reference fit (exactly 1 by default) */
  PetscReal    *f0;        /* total: (dW/dr)/r of each pair of nl in the reference configuration (0: not neighbours there) */
  PetscInt      cap_ref;
  /* total: arrays over the solid particles only (solid_total.c), not particle fields, which every
   * fluid particle, migration, checkpoint and the run guard's copy would carry (117 reals a particle
   * in 3D).  Each is recomputed where it is used: G at every SolidPrepare, F and Q in every
   * SolidRates. */
  PetscInt     *slot;      /* each owned and ghost particle's index in them (-1: not a solid): owned solids
                              0 .. nown - 1 in order, then the ghosts; set at every SolidPrepare */
  PetscInt      nown, nslot, cap_slot;
  PetscReal    *G0;        /* owned solids: the reference fit operator G (NB x NB, row-major) */
  PetscReal    *Fd, *Qd;   /* owned and ghost solids: deformation gradient F (D x D) and dW/dA Q (D x NB), row-major */
  PetscInt      cap_G0, cap_FQ;
  PetscSF       sf_slot;   /* owners' slots to their ghosts' (HaloSlotSF) */
  PetscInt      npair_ref; /* total: number of reference-configuration pairs of the whole body, counted at the first SolidPrepare */
  Cells         nl;       /* neighbours of owned solids within 2 h + skin: valid while no solid moved skin / 2 */
  PetscReal     skin;     /* in units of dx */
  PetscReal    *xref;     /* positions of owned particles when nl was built */
  PetscInt      cap_xref, nrebuild; /* rebuilds forced by solid motion */
  PetscBool     repulsion; /* Eq. 41 on fluid-solid pairs (WCSPH fluid) */
  PetscReal     repulsion_scale; /* Eq. 41's pair sum next to a flat solid scaled to the paper's (2D, h = 1.3 dx: 1 there) */
  PetscReal     nrm_min;   /* |sum V grad W| below this: not a surface particle, no normal */
  PetscBool     subcycle;  /* multi-rate: solid sub-steps inside the fluid step */
  PetscReal     cfl;       /* Courant number of the solid's step */
  PetscBool     implicit;  /* ISPH: the solid's rows of the pressure equation answer its acceleration (ppe.c) */
  PetscBool     mean_acc;  /* ISPH, implicit: those rows start from its mean acceleration over the last fluid step */
  PetscReal     transit;   /* ISPH: fluid step <= transit * (solid extent) / c0_solid; 0 = no limit */
  PetscReal     row_stiffness; /* ISPH, implicit: weight of the bonds' stiffness in a solid row's mass, m + w dt^2 k / 4 (ppe.c) */
  PetscReal     extent;    /* largest side of the moving solids' bounding box at the start (0: not yet known) */
  PetscReal    *R;     /* artificial stress (symmetric, dim.h's order) of owned + ghost particles, Eqs. 32-34 */
  PetscInt      cap_R;
  PetscReal     support[3];      /* force of the supports on the owned clamp particles at the last rates (N/m in 2D, N in 3D; reduce to sum) */
  PetscReal     support_mean[3]; /* its mean over the sub-steps of the last fluid step */
  PetscReal     load[3], load_mean[3]; /* the fluid's force on the owned moving solid particles, the same way */
  PetscInt      nsub_last, nsub_max; /* solid sub-steps in the last / any fluid step (progress line, summary) */
};

/* Creates ph->solid and reads its options under the prefix -solid_ (the scene's material defaults
 * are in ph->sl), and with a fluid the coupling's under -fsi_; then the set-up (fields, neighbour
 * list), before ParticlesSetUp. */
PetscErrorCode SolidSetFromOptions(Physics *ph);
PetscErrorCode SolidSetUp(Physics *ph);
PetscErrorCode SolidDestroy(Solid *s);
/* Neighbour list of the solids after a rebuild (SimRebuild): the sub-steps move the solids
 * without a rebuild until one has moved half the skin. */
PetscErrorCode SolidPrepare(Physics *ph);
/* Before the sub-steps of a fluid step: reset the means over them (acceleration, support). */
PetscErrorCode SolidBeginSubsteps(Physics *ph);
/* Pressure, artificial stress and accelerations of solids at the current state (after
 * SolidPrepare or a sub-step). */
PetscErrorCode SolidRates(Physics *ph);
/* ISPH + solid: the largest fluid step, -fsi_dt_transit times the solid's extent over its c0
 * (PETSC_MAX_REAL without a limit); collective at its first call, which SimSetUp makes on the
 * solids as built. */
PetscErrorCode SolidTransitLimit(Physics *ph, PetscReal *dt);
/* Step limit from the solid sound speed: cfl h / (c0 + |v|), and the force limit. */
PetscErrorCode SolidTimeStep(Physics *ph, PetscReal *dt);
/* One kick-drift-kick step of length dt of the solids (fluids held still): ghosts refreshed, no
 * rebuild unless a solid has moved half the skin since SolidPrepare. */
PetscErrorCode SolidStep(Physics *ph, PetscReal dt);
/* Kinetic and strain energy of owned solids at the state of the last SolidRates (collective):
 * strain energy density
 * S:S / (4 G) + P^2 / (2 K), S_zz = -(S_xx + S_yy) in plane strain (2D). */
PetscErrorCode SolidEnergy(Physics *ph, PetscReal *ekin, PetscReal *estrain);
PetscErrorCode SolidView(Physics *ph, PetscViewer v);
