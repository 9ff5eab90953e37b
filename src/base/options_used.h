#pragma once
#include "base/base.h"

/* OUTDIR/options_used: the options of this run, so that -options_file OUTDIR/options_used repeats
 * it: every option given (-options_file expanded), then `chosen` ("-name value" lines: values the
 * scene or the scheme computed where the option's default means "choose", e.g. -t_end, -c0), then
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
PetscErrorCode OptionsRecord(const char *name, const char *value, const void *set);
PetscErrorCode OptionsRecordReal(const char *name, PetscReal v, const void *set);
PetscErrorCode OptionsRecordInt(const char *name, PetscInt v, const void *set);
#define OptReal(opt, text, man, cur, val, set) \
  ({ \
    PetscErrorCode ierr_opt_ = PetscOptionsReal(opt, text, man, cur, val, set); \
    ierr_opt_ ? ierr_opt_ : OptionsRecordReal(opt, *(val), set); \
  })
#define OptInt(opt, text, man, cur, val, set) \
  ({ \
    PetscErrorCode ierr_opt_ = PetscOptionsInt(opt, text, man, cur, val, set); \
    ierr_opt_ ? ierr_opt_ : OptionsRecordInt(opt, *(val), set); \
  })
#define OptBool(opt, text, man, cur, val, set) \
  ({ \
    PetscErrorCode ierr_opt_ = PetscOptionsBool(opt, text, man, cur, val, set); \
    ierr_opt_ ? ierr_opt_ : OptionsRecordInt(opt, (PetscInt) * (val), set); \
  })
#define OptEList(opt, text, man, list, n, cur, val, set) \
  ({ \
    PetscErrorCode ierr_opt_ = PetscOptionsEList(opt, text, man, list, n, cur, val, set); \
    ierr_opt_ ? ierr_opt_ : OptionsRecord(opt, (list)[*(val)], set); \
  })
