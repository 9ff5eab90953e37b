#pragma once
#include <stdio.h>

/* The program's version (file VERSION) and the commit it was built from (git, "+modified" when the
 * tree had changes; "unknown" outside a git checkout), set at build time. */
const char *SPHFSIVersion(void);
const char *SPHFSICommit(void);

/* One line each: sphfsi's version and commit, then the libraries it runs on (PETSc, hypre, METIS,
 * HDF5, MPI).  Safe before MPI and PETSc are initialised (-version does not start them). */
void SphfsiVersionPrint(FILE *f);

/* The absolute path of the source tree's reference data at build time (Makefile: $(abspath
 * $(REFDATA)), by default ../shared/refdata beside the checkout), one place src/base/refdata.c looks. */
const char *SphfsiSourceRefData(void);
