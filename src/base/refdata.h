/* Reference curves and probe histories (the public part: <sphfsi/refdata.h>); where the reference
 * files are looked for: RefDataOpen. */
#pragma once
#include "base/base.h"
#include <sphfsi/refdata.h>

/* Free the list of missing files. */
PetscErrorCode RefDataDestroy(RefData *rd);
