/* SPH operators over the neighbour list that several modules and tests share. */
#pragma once
#include "particles/cells.h"

/* Kernel-gradient correction (Bonet & Lok 1999): L_a = [sum_b V_b (x_b - x_a) (x) grad_a W_ab]^-1,
 * stored row-major (dim x dim per owned particle), so that the corrected gradient
 * sum_b V_b (f_b - f_a) L_a grad_a W_ab is exact for linear f.  V_b = m_b / rho_b.  With `keep`,
 * only particles a of the kinds it accepts, summed over neighbours of those kinds (NULL: all). */
PetscErrorCode SPHGradientCorrection(Particles P, Cells C, PetscBool (*keep)(PetscInt), PetscReal *L);
/* Gradient of a scalar field f (owned + ghosts) at owned particles, corrected with L (or NULL). */
PetscErrorCode SPHGradient(Particles P, Cells C, const PetscReal *L, const PetscReal *f, PetscReal *grad);
