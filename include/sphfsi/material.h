/* The media's material constants, as a scene sets its defaults before the options are read
 * (SimFluidMaterial, SimSolidMaterial in <sphfsi/scene.h>), and the fluid's equation of state. */
#ifndef SPHFSI_MATERIAL_H
#define SPHFSI_MATERIAL_H
#include <sphfsi/base.h>

SPHFSI_EXTERN_C_BEGIN

/* A scene sets rho0 and mu; the rest comes from the options (-fluid_*, -wcsph_*) and the scheme. */
typedef struct {
  PetscReal rho0;          /* reference density */
  PetscReal c0;            /* artificial sound speed, Eq. 20 (WCSPH) */
  PetscReal mu;            /* dynamic viscosity, Eq. 16 */
  PetscReal eta;           /* regularisation of Eqs. 16 and 22 over h (-fluid_eta) */
  PetscReal lap_kappa;     /* normalisation of Eqs. 16 and 22: exact on the lattice (-fluid_lap_normalise) */
  PetscReal alpha;         /* artificial viscosity, Eq. 24 (WCSPH) */
  PetscReal wall_av;       /* Eq. 24's coefficient against walls and solids over the scheme's (-wcsph_wall_av, -isph_wall_av) */
  PetscReal delta;         /* density diffusion (delta-SPH), 0 = off */
  PetscReal damper;        /* WCSPH: acoustic damper, Eq. 20's pressure plus damper rho0 c0 h (drho/dt) / rho; 0 = off */
  PetscReal riemann;       /* WCSPH: the acoustic Riemann solver's dissipation with its limiter (Zhang, Hu & Adams 2017), eta; 0 = off */
  PetscReal xsph;          /* XSPH epsilon, Eq. 44, 0 = off */
  PetscReal shift;         /* WCSPH Fickian shifting coefficient A, 0 = off */
  PetscBool shift_correct; /* both schemes: a shifted particle's velocity corrected to its new place */
  PetscReal shift_dmax;    /* both schemes: the ceiling of shifting's A h |v| dt over h^2 (-fluid_shift_ceiling); 0 = none */
  PetscReal shift_vmin;    /* both schemes: shifting's speed at least this (-fluid_shift_speed); 0 = the particle's own */
  PetscBool shift_volume;  /* WCSPH with shifting: the density follows the shifted particle's volume (-wcsph_shift_volume) */
  PetscReal lat_divr;      /* WCSPH with shifting: bulk value of -sum V F r^2, normalises div r */
  PetscBool tic;           /* WCSPH: tensile instability control (-wcsph_tic): a fluid particle in tension takes p_b - p_a from the fluid */
  PetscBool wall_clip;     /* WCSPH: the Adami wall pressure clipped at 0, so that a wall never pulls fluid */
  PetscBool force_gauge;   /* forces on named bodies free of the push a uniform pressure gives the discrete sum (-fluid_force_gauge; WCSPH's default) */
} FluidMaterial;

/* The hyper-elastic law of the total-Lagrangian solid (-solid_law; the updated solid is
 * hypo-elastic and has none): compressible neo-Hookean, or St Venant-Kirchhoff (S = lambda tr(E) I
 * + 2 mu E, E the Green-Lagrange strain; the Turek-Hron benchmark's).  Both take lambda = K - 2 G / 3
 * and mu = G, plane strain in 2D, so they agree at small strain. */
typedef enum { SOLID_LAW_NEO_HOOKEAN = 0, SOLID_LAW_ST_VENANT_KIRCHHOFF } SolidLaw;

/* A scene sets rho0, K and G (and law, if not neo-Hookean); c0 = sqrt(K / rho0) is set up by the
 * solid.  The options give the moduli as -solid_K, -solid_G or as -solid_E, -solid_nu. */
typedef struct {
  PetscReal rho0;  /* reference density */
  PetscReal K, G;  /* bulk and shear modulus */
  PetscReal c0;    /* sqrt(K / rho0), Eq. 20 */
  PetscReal alpha; /* artificial viscosity, Eq. 24 */
  PetscReal eps;   /* artificial stress e, Eqs. 25-31 (0 = off) */
  PetscReal n;     /* exponent of f = W_ab / W(dx, h) in Eq. 23 */
  SolidLaw  law;   /* total-Lagrangian: the stress from F (default neo-Hookean) */
} SolidMaterial;

/* The equation of state, Eq. 20 */
static inline PetscReal EOSPressure(const FluidMaterial *m, PetscReal rho) { return m->c0 * m->c0 * (rho - m->rho0); }
static inline PetscReal EOSDensity(const FluidMaterial *m, PetscReal p) { return m->rho0 + p / (m->c0 * m->c0); }
static inline PetscReal SolidEOSPressure(const SolidMaterial *m, PetscReal rho) { return m->c0 * m->c0 * (rho - m->rho0); }

SPHFSI_EXTERN_C_END
#endif
