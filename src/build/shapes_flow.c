/* The periodic arrays' flow probe of -case boxes (-flow_probe, shapes.h; docs/geometry.md): the
 * superficial velocity and the drag per obstacle, against Sangani & Acrivos and Zick & Homsy. */
#include "build/shapes.h"
#include "base/refdata.h"

PetscInt ShapesFlowColumns(Shapes S) { return S->flow ? 2 : 0; }

/* u_mean = sum_f V_f v_x,f / |domain|: the superficial velocity, the flow rate through a section
 * over the width (continuity makes every section's flow rate the same, so the mean over the sections
 * is the volume integral over the length).  drag = F / (mu u_mean) with F = rho0 g_x |domain| /
 * (obstacle shapes): the force per obstacle of the pressure-driven flow with the same velocity field.
 * A body force rho g on the water is a mean pressure gradient G = rho g: writing p = p' - G x turns the
 * one flow into the other.  In the pressure-driven flow a cell's momentum balance is G |cell| = F (the
 * pressure acts on the cell's faces, all water), which is the F of the tables (Sangani & Acrivos;
 * Basilisk's test src/test/cylinders.c compares the same way); the walls of the body-force flow
 * hold rho g times the water's volume only, F less the "buoyancy" of -G x on the obstacle.  At a
 * steady state, so per unit length in 2D. */
static PetscErrorCode FlowValues(Sim sim, const struct _n_Shapes *S, PetscReal *vals)
{
  Particles        P = sim->P;
  const PetscInt   D = P->dim;
  const PetscReal *v = PField(P, FIELD_V), *m = PField(P, FIELD_M), *rho = PField(P, FIELD_RHO);
  PetscReal        s = 0;
  PetscInt         nobs = 0;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < P->n; a++)
    if (KindIsFluid(P->kind[a])) s += SceneFluidVolume(sim, m[a], rho[a]) * v[D * a];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &s, 1, MPIU_REAL, MPI_SUM, sim->comm));
  for (PetscInt i = 0; i < S->n; i++) nobs += S->s[i].kind == SHAPE_WALL;
  vals[0] = s / S->flow_measure;
  vals[1] = vals[0] != 0 && sim->phys.fl.mu > 0 ? sim->phys.fl.rho0 * sim->phys.g[0] * S->flow_measure / PetscMax(nobs, 1) / (sim->phys.fl.mu * vals[0]) : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShapesFlowProbe(Sim sim, Shapes S, PetscReal *vals)
{
  PetscFunctionBeginUser;
  if (!S->flow) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FlowValues(sim, S, vals));
  PetscCall(SeriesAppend(&S->drag, sim->phys.t, vals[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The drag's mean over the run's last tenth against the reference at the obstacles' area (volume)
 * fraction phi: Sangani & Acrivos 1982 (2D, F / (mu U)), Zick & Homsy 1982 (3D, K = F / (6 pi mu a U)),
 * interpolated linearly in log(drag) between the tabulated fractions; and at phi_lattice, 1 - the
 * water's volume (m / rho0) over the domain's: the fraction the particles make (the lattice points a
 * circle holds differ from its area by a few, at 20 particles across the cell 0.11 for 0.1). */
static PetscReal TableAt(const Series *tab, PetscReal phi)
{
  if (tab->n < 2 || phi < tab->t[0] || phi > tab->t[tab->n - 1]) return 0;
  for (PetscInt k = 1; k < tab->n; k++)
    if (phi <= tab->t[k]) {
      const PetscReal f = (phi - tab->t[k - 1]) / (tab->t[k] - tab->t[k - 1]);
      return PetscExpReal((1 - f) * PetscLogReal(tab->y[k - 1]) + f * PetscLogReal(tab->y[k]));
    }
  return 0;
}

PetscErrorCode ShapesFlowErrors(Sim sim, Shapes S, FILE *f)
{
  const PetscInt D = sim->phys.dim;
  PetscReal      solid = 0, mean = 0, w = 0, phi, phil, vals[2], ref = 0, refl = 0, fac = 1, mw = 0, *m = PField(sim->P, FIELD_M);
  PetscInt       nobs = 0, iw = 0;
  Series         tab = {0, 0, NULL, NULL};
  PetscBool      found = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (!S->flow) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FlowValues(sim, S, vals));
  for (PetscInt i = 0; i < S->n; i++)
    if (S->s[i].kind == SHAPE_WALL) { solid += GeomMeasure(&S->s[i].g); nobs++; iw = i; }
  for (PetscInt a = 0; a < sim->P->n; a++) mw += KindIsFluid(sim->P->kind[a]) ? m[a] : 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &mw, 1, MPIU_REAL, MPI_SUM, sim->comm));
  phi  = solid / S->flow_measure;
  phil = 1 - mw / sim->phys.fl.rho0 / S->flow_measure;
  for (PetscInt k = 0; k < S->drag.n; k++)
    if (S->drag.t[k] >= 0.9 * sim->phys.t) { mean += S->drag.y[k]; w += 1; }
  mean = w > 0 ? mean / w : vals[1];
  if (nobs == 1 && S->s[iw].g.type == GEOM_SPHERE) { /* one cylinder (sphere) a cell */
    PetscCall(RefDataLoad(&sim->refdata, D == 3 ? "zick_homsy1982_simple_cubic_sphere_array_drag.csv" : "sangani_acrivos1982_square_cylinder_array_drag.csv", "phi", D == 3 ? "K" : "drag", &tab, &found));
    if (D == 3) fac = 6 * PETSC_PI * S->s[iw].g.r; /* K = drag / (6 pi a) */
    if (found) { ref = TableAt(&tab, phi); refl = TableAt(&tab, phil); }
  }
  if (f) {
    fprintf(f, "\"drag_mean_last_tenth\": %.9g, \"drag_final\": %.9g, \"u_mean_final\": %.9g, \"re\": %.6g, \"phi\": %.9g, \"phi_lattice\": %.9g", (double)mean, (double)vals[1], (double)vals[0], (double)(vals[0] * (sim->dom_hi[0] - sim->dom_lo[0]) * sim->phys.fl.rho0 / sim->phys.fl.mu), (double)phi, (double)phil);
    if (ref > 0) fprintf(f, ", \"%s\": %.9g, \"%s\": %.9g, \"drag_rel_err\": %.6g", D == 3 ? "K" : "drag_coefficient", (double)(mean / fac), D == 3 ? "K_reference" : "drag_reference", (double)ref, (double)(mean / fac / ref - 1));
    if (refl > 0) fprintf(f, ", \"drag_reference_phi_lattice\": %.9g, \"drag_rel_err_phi_lattice\": %.6g", (double)refl, (double)(mean / fac / refl - 1));
    if (ref > 0) fprintf(f, ", \"reference\": \"%s, interpolated in log(drag) between its fractions\"", D == 3 ? "Zick & Homsy 1982, simple cubic array of spheres" : "Sangani & Acrivos 1982, square array of cylinders");
  }
  PetscCall(SeriesDestroy(&tab));
  PetscFunctionReturn(PETSC_SUCCESS);
}
