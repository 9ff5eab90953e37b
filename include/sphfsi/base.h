/* sphfsi's public interface, the part every public header shares: PETSc's types, C and C++ linkage,
 * the run's handle (Sim) and small numeric helpers. */
#ifndef SPHFSI_BASE_H
#define SPHFSI_BASE_H
#include <petscsys.h>
#ifndef PETSC_SUCCESS
  #define PETSC_SUCCESS 0
#endif

#ifdef __cplusplus
  #define SPHFSI_EXTERN_C_BEGIN extern "C" {
  #define SPHFSI_EXTERN_C_END   }
#else
  #define SPHFSI_EXTERN_C_BEGIN
  #define SPHFSI_EXTERN_C_END
#endif

SPHFSI_EXTERN_C_BEGIN

/* The run, as a scene sees it: an opaque handle.  A scene reads and sets what it needs through the
 * accessors of <sphfsi/scene.h> and <sphfsi/particles.h>. */
typedef struct _p_Sim *Sim;

/* nearest integer */
static inline PetscInt RoundToInt(PetscReal x) { return (PetscInt)PetscFloorReal(x + 0.5); }

SPHFSI_EXTERN_C_END
#endif
