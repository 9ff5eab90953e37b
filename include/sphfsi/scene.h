/* Writing a scene: its operations (SceneOps), the run's settings a scene reads and sets through the
 * handle Sim, and the builders that add particles (blocks, boxes, tanks, points, zoned water, a
 * hydrostatic start) and measure (pressure probes, level gauges).  The built-in scenes of src/scenes/
 * use nothing else; docs/api.md has an example. */
#ifndef SPHFSI_SCENE_H
#define SPHFSI_SCENE_H
#include <sphfsi/base.h>
#include <sphfsi/material.h>
#include <sphfsi/options.h>
#include <sphfsi/particles.h>
#include <sphfsi/refdata.h>
#include <stdio.h>

SPHFSI_EXTERN_C_BEGIN

#define SCENE_MAX_PROBES 16

/* A scene: a name for -case, its operations, and its probes (columns of probes.csv). */
typedef struct _SceneOps SceneOps;
struct _SceneOps {
  const char *name;
  const char *help;
  /* Read the scene's options; set the spacing (SimSetSpacing, unless -dx was given), the end time
   * (unless -t_end was given), the domain, periodicity, gravity, the media and their material
   * defaults, the reference speed. */
  PetscErrorCode (*create)(Sim sim);
  /* Add the particles (the fields are allocated by then). */
  PetscErrorCode (*populate)(Sim sim);
  /* Optional: overwrite the velocity of particles whose motion the scene prescribes (called in each
   * solid step after the first half kick, so the drift and the strain rate see it). */
  PetscErrorCode (*prescribe)(Sim sim);
  PetscInt    nprobes;
  const char *probe_names[SCENE_MAX_PROBES];
  /* Probe values (collective; every rank gets them). */
  PetscErrorCode (*probe)(Sim sim, PetscReal *vals);
  /* Errors against the scene's reference, as JSON members ("name": value, ...); f is NULL except on
   * rank 0 (collective). */
  PetscErrorCode (*errors)(Sim sim, FILE *json);
  PetscErrorCode (*destroy)(Sim sim);
};

/* In the scene's create: state of the scene that changes during a run, which checkpoints save and a
 * restart restores (in the order registered): a probe history, or one running value. */
PetscErrorCode SceneKeepSeries(Sim sim, Series *s);
PetscErrorCode SceneKeepReal(Sim sim, PetscReal *r);

/* The run, as the scene sees it.  The getters return values (no error can occur); the setters are
 * for the scene's create, before the run sets itself up. */
MPI_Comm SimComm(Sim sim);
/* The scene's own data: set in create, read in the other operations. */
void          *SimSceneContext(Sim sim);
PetscErrorCode SimSetSceneContext(Sim sim, void *ctx);
/* 2 or 3: the scene's choice in create (2 by default; its -dim option, if it has one). */
PetscInt       SimDim(Sim sim);
PetscErrorCode SimSetDim(Sim sim, PetscInt dim);
/* The particle spacing dx (-dx; negative until the scene chooses one). */
PetscReal      SimSpacing(Sim sim);
PetscErrorCode SimSetSpacing(Sim sim, PetscReal dx);
/* The simulated time, the step number, the end time (-t_end; negative until the scene chooses). */
PetscReal      SimTime(Sim sim);
PetscInt       SimStep(Sim sim);
PetscReal      SimEndTime(Sim sim);
PetscErrorCode SimSetEndTime(Sim sim, PetscReal t_end);
/* The domain box, its corners' 3 coordinates (the vertical is the last direction), and its periodic
 * directions; the grid of cells covers the box. */
const PetscReal *SimDomainLo(Sim sim);
const PetscReal *SimDomainHi(Sim sim);
PetscErrorCode   SimSetDomain(Sim sim, PetscInt d, PetscReal lo, PetscReal hi);
PetscBool        SimPeriodic(Sim sim, PetscInt d);
PetscErrorCode   SimSetPeriodic(Sim sim, PetscInt d, PetscBool periodic);
/* Gravity, 3 components (-gravity overrides what the scene sets). */
const PetscReal *SimGravity(Sim sim);
PetscReal        SimGravityNorm(Sim sim);
PetscErrorCode   SimSetGravity(Sim sim, PetscReal gx, PetscReal gy, PetscReal gz);
/* Which media the scene has: only their fields are allocated and their physics computed. */
PetscBool      SimHasFluid(Sim sim);
PetscBool      SimHasSolid(Sim sim);
PetscErrorCode SimSetMedia(Sim sim, PetscBool fluid, PetscBool solid);
/* The materials: a scene sets its defaults in create (the options then override them). */
FluidMaterial *SimFluidMaterial(Sim sim);
SolidMaterial *SimSolidMaterial(Sim sim);
/* The fluid is incompressible (-fluid isph) rather than weakly compressible (wcsph). */
PetscBool SimFluidIncompressible(Sim sim);
/* The largest speed the scene expects (WCSPH's sound speed is 10 times it unless -fluid_c0 is given). */
PetscErrorCode SimSetReferenceSpeed(Sim sim, PetscReal v_ref);
/* The fluid fills the domain: no free surface (ISPH pins the pressure's constant). */
PetscBool      SimConfined(Sim sim);
PetscErrorCode SimSetConfined(Sim sim, PetscBool confined);
/* Fluid leaving the domain box is removed (an open boundary), and the mass that left. */
PetscBool      SimOutflow(Sim sim);
PetscErrorCode SimSetOutflow(Sim sim, PetscBool outflow);
PetscReal      SimFluidMassOut(Sim sim);
/* The kernel: rows of wall particles that cover its support, and h / dx (-h_factor). */
PetscInt  SimKernelRows(Sim sim);
PetscReal SimKernelHFactor(Sim sim);
/* The reference data's locations (for RefDataLoad, RefDataOpen). */
RefData *SimRefData(Sim sim);
/* The solid: kinetic and strain energy (collective); the fluid's force on the moving solid and the
 * clamps' force on it, dim components each, means over the sub-steps of the last fluid step. */
PetscErrorCode   SimSolidEnergy(Sim sim, PetscReal *ekin, PetscReal *estrain);
const PetscReal *SimSolidLoad(Sim sim);
const PetscReal *SimSolidSupport(Sim sim);
/* The force of the fluid on body k > 0 (N/m in 2D, N in 3D): the walls and solids whose field "body"
 * is k (enable it in create with SimEnableField(sim, "body") and set it in populate), summed over
 * their pairs with the fluid as the momentum equation exchanges them, at the current state
 * (collective; drag and lift on a cylinder, loads on a structure); with -fluid_force_gauge (WCSPH's
 * default) the pressure measured from its mean over those pairs, so that a uniform pressure pushes
 * no body (docs/turek_hron.md). */
PetscErrorCode SimBodyForce(Sim sim, PetscInt k, PetscReal force[3]);
/* The same for bodies k, ..., k + n - 1 (n <= 8) in one pass over the pairs: force[j] is body k + j's. */
PetscErrorCode SimBodyForces(Sim sim, PetscInt k, PetscInt n, PetscReal force[][3]);

/* Open boundaries: an inlet with a prescribed velocity, an outlet at a given pressure, each a buffer
 * of fluid particles `rows` deep outside a plane normal to a coordinate axis.  The scene fills the
 * buffers with fluid as it fills the rest (its fluid reaches `rows` spacings past the plane) and sets
 * the domain's ends at the buffers' far ends.  An inlet's buffer particles move with the profile and
 * the one that crosses the plane joins the fluid, a new one taking its place at the buffer's far end;
 * fluid crossing an outlet's plane joins its buffer (its pressure held at `pressure`, its velocity
 * frozen) and leaves at the domain's end (docs/open_boundaries.md). */
typedef enum { OPEN_INLET = 0, OPEN_OUTLET } OpenBoundaryKind;
typedef enum { PROFILE_UNIFORM = 0, PROFILE_PARABOLIC, PROFILE_TABLE } OpenProfile;
typedef struct {
  OpenBoundaryKind kind;
  PetscInt         axis;      /* the plane's normal: 0 x, 1 y, 2 z */
  PetscInt         side;      /* -1: the buffer lies below the plane (an inlet feeding +axis, an outlet of -axis flow); +1: above */
  PetscReal        plane;     /* the plane's coordinate along axis */
  PetscReal        lo[3], hi[3]; /* the cross-section: the other coordinates' range (axis's entries unused) */
  PetscInt         rows;      /* buffer depth in spacings (0: the kernel's reach, SimKernelRows) */
  OpenProfile      profile;   /* inlet: uniform, parabolic (zero at the section's edges), or a table */
  PetscReal        velocity;  /* inlet: the mean normal speed into the domain (m/s, > 0) */
  PetscReal        ramp;      /* inlet: the speed grows as (1 - cos(pi t / ramp)) / 2 until ramp (s; 0: none) */
  char             table[PETSC_MAX_PATH_LEN]; /* inlet, PROFILE_TABLE: a file of lines "s u" (s the cross-section coordinate, m; u m/s) */
  PetscReal        pressure;  /* outlet: the pressure held in its buffer (Pa) */
} OpenBoundarySpec;
#define SCENE_MAX_OPEN 4
/* In create: add one (at most SCENE_MAX_OPEN).  Bad input (a profile pointing out of the domain, a buffer thinner
 * than the kernel's reach, an inlet overlapping an outlet, a table that cannot be read) stops the run
 * before its first step with one line. */
PetscErrorCode SimAddOpenBoundary(Sim sim, const OpenBoundarySpec *spec);
/* In a scene's options block: inlets and outlets as data, -inlet_K and -outlet_K (K = 1..4) each a
 * buffer box filled with water (its depth along the flow a whole number of spacings), with
 * -inlet_K_direction / -outlet_K_direction (+x, -x, +y, ...: the flow's direction in or out),
 * -inlet_K_velocity, -inlet_K_profile uniform|parabolic|table, -inlet_K_table FILE, -inlet_K_ramp,
 * -outlet_K_pressure.  The n specs read go to SimAddOpenBoundary once the domain is set. */
PetscErrorCode SceneOpenBoundaryOptions(Sim sim, PetscOptionItems *PetscOptionsObject, OpenBoundarySpec spec[], PetscInt *n);
/* The fluid mass that entered through the inlets and left through the outlets (and the domain's
 * ends) so far (kg, or kg/m in 2D). */
PetscReal SimFluidMassIn(Sim sim);

/* Builders */
/* A scene that adds particles without the builders below: the scene's n particles of a kind (the
 * whole scene's, on every rank) for the size guard, which first runs the scene's populate only to
 * count (SceneCounting: then add nothing). */
PetscErrorCode SceneCount(Sim sim, ParticleKind kind, PetscInt64 n);
PetscBool      SceneCounting(Sim sim);
/* A 3D scene from a 2D layout: between Begin and End, the builders below take x, y points and boxes
 * of the 2D layout (as in a 2D scene) and each point becomes n points at z = z0 + (k + 1/2) dz (its
 * mass rho0 dx^2 dz), in the order of the 2D layout, layer by layer. */
PetscErrorCode SceneExtrudeBegin(Sim sim, PetscInt n, PetscReal z0, PetscReal dz);
PetscErrorCode SceneExtrudeEnd(Sim sim);
/* The dimension of the layout the builders take: 2 while extruding, else the scene's. */
PetscInt SceneLayoutDim(Sim sim);
/* Add a lattice of n[0] x n[1] (x n[2] in 3D) particles of spacing dx whose first centre is lo,
 * ids from SimNextId (x fastest); each rank keeps every size-th particle. */
PetscErrorCode SceneAddBlock(Sim sim, ParticleKind kind, const PetscReal lo[], const PetscInt n[], PetscReal dx, PetscReal rho0);
/* Add one particle at p (coordinates of the layout) spaced s[d] along each direction: mass rho0
 * times the spacings' product, smoothing length from dx, the next id (kept by rank id % size). */
PetscErrorCode SceneAddPoint(Sim sim, ParticleKind kind, const PetscReal p[], const PetscReal s[], PetscReal dx, PetscReal rho0);
/* Add an nx x ny lattice of spacing dx starting at cell centre (x0, y0), ids from SimNextId;
 * each rank keeps every size-th particle (migration sorts them out later). */
PetscErrorCode SceneAddLattice(Sim sim, ParticleKind kind, PetscReal x0, PetscReal y0, PetscInt nx, PetscInt ny, PetscReal dx, PetscReal rho0);
/* Walls of `rows` rows (first row KIND_WALL, the rest KIND_DUMMY) around the rectangle
 * [x0, x1] x [y0, ...): floor below y0, side walls left of x0 and right of x1 up to y1. */
PetscErrorCode SceneAddTank(Sim sim, PetscReal x0, PetscReal x1, PetscReal y0, PetscReal y1, PetscReal dx, PetscInt rows, PetscBool left, PetscBool right);
/* The spacing of n particles along a side of length extent at nominal spacing dx: n = extent / dx
 * rounded, the spacing dx where the side is a multiple of dx, else extent / n, so that the lattice
 * fills the side exactly (SPHERIC Test 2's 0.55 m column would stand 0.56 m high at dx = 0.02 m). */
PetscReal SceneFitSpacing(PetscReal extent, PetscReal dx, PetscInt *n);
/* A lattice of one kind filling the box b exactly (its low corner, then its high corner: x0,y0,x1,y1
 * in 2D, x0,y0,z0,x1,y1,z1 in 3D) at spacing dx, each side with its whole number of particles
 * (SceneFitSpacing), the first particle half a spacing inside the low corner; mass rho0 times the
 * spacings' product, smoothing length from dx. */
PetscErrorCode SceneAddBox(Sim sim, ParticleKind kind, const PetscReal b[], PetscReal dx, PetscReal rho0);
/* An obstacle of wall particles filling the box b (as SceneAddBox) on a lattice of spacing dx: the
 * particles within dx of the faces that meet water are walls, the others dummies; faces: the low
 * faces, then the high faces (2D: left, bottom, right, top; 3D: x-, y-, z-, x+, y+, z+). */
PetscErrorCode SceneAddWallBox(Sim sim, const PetscReal b[], PetscReal dx, const PetscBool faces[]);
/* Walls of `rows` layers (the layer next to the water KIND_WALL, the rest KIND_DUMMY) around the
 * water box [lo, hi] in any dimension: under its floor and beside it in every horizontal direction,
 * the sides up to `top` (the vertical is the last direction); spaced horizontally as SceneAddBox
 * fills the box, so that the walls stand on its faces, and dx upwards. */
PetscErrorCode SceneAddTankBox(Sim sim, const PetscReal lo[], const PetscReal hi[], PetscReal top, PetscReal dx, PetscInt rows);
/* Domain box (square in 3D) of a tank [0, L] with `rows` rows of wall particles under and beside it, up to y = top. */
void SceneTankDomain(Sim sim, PetscReal L, PetscReal top, PetscInt rows);
/* A dam break: a water column [0, w] x [0, hgt] at hydrostatic density against the upstream wall of a
 * tank [0, L] whose walls reach top - dx (the domain box's top is top). */
PetscErrorCode SceneAddDamBreak(Sim sim, PetscReal w, PetscReal hgt, PetscReal L, PetscReal top, PetscInt rows);
/* Fluid at rest: pressure and density (WCSPH EOS, Eq. 20) of a hydrostatic column with its free
 * surface at height y_surface (y in 2D, z in 3D), for this rank's fluid particles from index `first` on (0: all of them). */
PetscErrorCode SceneHydrostaticDensity(Sim sim, PetscInt first, PetscReal y_surface);
/* Mixed particle sizes (section 3.3): water [0, W] x [0, H] at the coarse spacing dc on [0, W - fine]
 * and at SimSpacing(sim) on [W - fine, W] (next to a gate).  SceneZonesSetUp checks dc and fine (option names
 * -dx_coarse, -fine_width in its messages) and rounds W, fine and H so that the zones tile the water
 * in whole columns and reach the same surface; dc == dx gives one zone (*fine = *W, W and H rounded
 * to dx). */
PetscErrorCode SceneZonesSetUp(Sim sim, PetscReal dc, PetscReal *W, PetscReal *fine, PetscReal *H);
/* The zoned water with its tank: a left wall of height top and the floor up to x_end at each zone's
 * spacing (the fine floor as deep as the coarse one, for coarse particles that drift over it), and a
 * right wall of height top at x_end when right. */
PetscErrorCode SceneAddZonedWater(Sim sim, PetscReal dc, PetscReal W, PetscReal fine, PetscReal H, PetscReal top, PetscInt rows, PetscReal x_end, PetscBool right);
/* Shepard interpolation of the fluid pressure at a point, each neighbour's value carried to the
 * point hydrostatically: p(x0) = sum (p_b + rho_b g.(x0 - x_b)) W / sum W, rho_b by SceneFluidDensity,
 * times the wetted fraction of the kernel's support outside the walls and solids,
 * min(1, sum_fluid V_b W / (1 - sum_boundary V_b W)): a point that is partly dry reads the mean with
 * the air at 0, as a transducer's face does, where Shepard's form alone would carry the wet
 * neighbours' pressure over the dry part (collective). */
PetscErrorCode SceneProbePressure(Sim sim, const PetscReal x0[], PetscReal *p);
/* The same at n points x0[dim * q + i] at once: one pass over the particles and one reduction (collective). */
PetscErrorCode SceneProbePressures(Sim sim, PetscInt n, const PetscReal x0[], PetscReal p[]);
/* Level gauges: the water depth under a point, as the volume of fluid per unit length (2D) or area
 * (3D) on the vertical line through it, sum_b V_b W_col(s), with W_col(s) = int W(sqrt(s^2 + t^2)) dt
 * the kernel integrated along the vertical and s the horizontal distance (a still layer of depth d
 * reads d; spray above the water counts with its volume, not as the surface).  The table is of the
 * run's kernel: initialise it after the scene's create (the run gives the kernel its dimension then). */
#define SCENE_NCOLUMN 200
typedef struct {
  PetscReal w[SCENE_NCOLUMN + 1]; /* h^(d-1) W_col at s / h = 2 k / SCENE_NCOLUMN */
  PetscInt  dim;
} SceneColumnKernel;
void SceneColumnKernelInit(Sim sim, SceneColumnKernel *ck);
/* Depths at n gauges; xg holds each gauge's horizontal position (x in 2D, x,y in 3D) (collective). */
PetscErrorCode SceneWaterDepth(Sim sim, const SceneColumnKernel *ck, PetscInt n, const PetscReal *xg, PetscReal *depth);
/* A fluid particle's density and volume for the probes: rho and m / rho in WCSPH.  ISPH's rho is
 * rho* by summation (Eq. 17), which falls short within 2h of a free surface (to ~0.6 rho0 in a thin
 * sheet), while incompressible water keeps rho0 and the volume m / rho0. */
static inline PetscReal SceneFluidDensity(Sim sim, PetscReal rho)
{
  return SimFluidIncompressible(sim) ? SimFluidMaterial(sim)->rho0 : rho;
}
static inline PetscReal SceneFluidVolume(Sim sim, PetscReal m, PetscReal rho)
{
  return m / SceneFluidDensity(sim, rho);
}
/* Water level at a wall: the fluid's volume in a strip of the given width along the wall over the
 * width, each particle counted with this share of its volume, s its distance from the wall: its
 * volume spread over a slab dx wide (cloud in cell), so that the level changes continuously as
 * particles cross the strip's edge instead of by dx^2 / width (2D) at once. */
static inline PetscReal SceneStripShare(PetscReal s, PetscReal width, PetscReal dx)
{
  return PetscClipInterval((width - s) / dx + 0.5, 0, 1);
}
/* Largest fluid speed (collective). */
PetscErrorCode SceneMaxSpeed(Sim sim, PetscReal *vmax);

SPHFSI_EXTERN_C_END
#endif
