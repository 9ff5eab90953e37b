#pragma once
#include <sphfsi/base.h>

/* OUTDIR/options_used: the options of this run, so that -options_file OUTDIR/options_used repeats
 * it: every option given (-options_file expanded), then `chosen` ("-name value" lines: values the
 * scene or the scheme computed where the option's default means "choose", e.g. -t_end, -c0), each
 * written unless given.  The other defaults are those of the version and commit in `header`
 * (-help lists them). */
PetscErrorCode OptionsUsedWrite(MPI_Comm comm, const char *outdir, const char *header, const char *chosen);
