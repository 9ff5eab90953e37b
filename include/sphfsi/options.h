/* A scene's options: PETSc's PetscOptionsReal/Int/Bool/EList, inside a PetscOptionsBegin block, with
 * the value the run ends with recorded in OUTDIR/options_used (so that -options_file of that file
 * repeats the run).  Same arguments as PETSc's. */
#ifndef SPHFSI_OPTIONS_H
#define SPHFSI_OPTIONS_H
#include <sphfsi/base.h>

SPHFSI_EXTERN_C_BEGIN

/* Not recorded: a negative number (this code's "the scene chooses" default, e.g. -dx -1), and an
 * option whose caller asks whether it was set (`set` not NULL: its presence means something). */
PetscErrorCode SPHOptionsReal(PetscOptionItems *items, const char opt[], const char text[], const char man[], PetscReal cur, PetscReal *val, PetscBool *set);
PetscErrorCode SPHOptionsInt(PetscOptionItems *items, const char opt[], const char text[], const char man[], PetscInt cur, PetscInt *val, PetscBool *set);
PetscErrorCode SPHOptionsBool(PetscOptionItems *items, const char opt[], const char text[], const char man[], PetscBool cur, PetscBool *val, PetscBool *set);
PetscErrorCode SPHOptionsEList(PetscOptionItems *items, const char opt[], const char text[], const char man[], const char *const *list, PetscInt n, const char cur[], PetscInt *val, PetscBool *set);

/* In a PetscOptionsBegin block (whose PetscOptionsObject they pass on) */
#define OptReal(opt, text, man, cur, val, set)           SPHOptionsReal(PetscOptionsObject, opt, text, man, cur, val, set)
#define OptInt(opt, text, man, cur, val, set)            SPHOptionsInt(PetscOptionsObject, opt, text, man, cur, val, set)
#define OptBool(opt, text, man, cur, val, set)           SPHOptionsBool(PetscOptionsObject, opt, text, man, cur, val, set)
#define OptEList(opt, text, man, list, n, cur, val, set) SPHOptionsEList(PetscOptionsObject, opt, text, man, list, n, cur, val, set)

SPHFSI_EXTERN_C_END
#endif
