#pragma once
#include "base/base.h"

/* OUTDIR/options_used: the options of this run, so that -options_file OUTDIR/options_used repeats
 * it: every option given (-options_file expanded), then `chosen` ("-name value" lines: values the
 * scene or the scheme computed where the option's default means "choose", e.g. -t_end, -fluid_c0), then
 * the defaults the run read (below), each written unless given.  PETSc's own options (the PPE's
 * solver) keep the defaults of the PETSc version in `header`. */
PetscErrorCode OptionsUsedWrite(MPI_Comm comm, const char *outdir, const char *header, const char *chosen);

/* Every option of the program's own that a run reads goes through these wrappers of PETSc's
 * PetscOptionsReal/Int/Bool/EList (the same arguments, inside a PetscOptionsBegin block): the value
 * it ends with, given or default, is recorded, and options_used lists the defaults too.  Not
 * recorded: a negative number, this code's "the scene chooses" default (-dx -1, -t_end -1, ...),
 * which written back would be read as given; and an option whose caller asks whether it was set
 * (`set` not NULL: its presence means something, e.g. a gauge of -case boxes).  The rerun's default
 * is the same anyway. */
PetscErrorCode OptionsRecord(const char *prefix, const char *name, const char *value, const void *set);
PetscErrorCode OptionsRecordReal(const char *prefix, const char *name, PetscReal v, const void *set);
PetscErrorCode OptionsRecordInt(const char *prefix, const char *name, PetscInt v, const void *set);
/* OptReal, OptInt, OptBool, OptEList (<sphfsi/options.h>) record the full name: the block's prefix
 * (PetscOptionsBegin's, PetscOptionsObject->prefix) and the name, "-wcsph_shift" for "-shift" in the
 * block of the prefix "wcsph_". */
#include <sphfsi/options.h>

/* An option renamed when the modules took their prefixes (issue 47: -alpha is -wcsph_alpha, -rho0
 * -fluid_rho0, ...): in the module's PetscOptionsBegin block, before the new name is read,
 * OptDeprecated("-alpha", "-wcsph_alpha") lets the old name work on, for this version, with PETSc's
 * one-line note (PetscOptionsDeprecated, "deprecated as of version OPT_RENAMED_IN").  Both names are
 * full, the prefix included: PETSc 3.18 looks the old name up under the block's prefix, which the old
 * name does not carry.  Given both names, the new one wins (a restart from an older checkpoint
 * inherits its old names under those given now).  The pair is remembered for OptionsRenamed. */
#define OPT_RENAMED_IN "0.9.0"
PetscErrorCode OptionsDeprecated(PetscOptionItems *PetscOptionsObject, const char *old, const char *now);
#define OptDeprecated(old, now) OptionsDeprecated(PetscOptionsObject, old, now)

/* The option string `all` ("-name value -flag ...", PetscOptionsGetAll's form) with the old names that
 * this run's modules declared (OptDeprecated) replaced by the new ones, into *out (PetscFree it):
 * a checkpoint's options compared with this run's. */
PetscErrorCode OptionsRenameAll(const char *all, char **out);
