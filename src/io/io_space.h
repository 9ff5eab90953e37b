/* Output that cannot be written: a full disk or quota ends the run with one line and its own exit
 * status (SIM_EXIT_IO), the last complete checkpoint intact.
 *  - Before a snapshot or a checkpoint, rank 0 compares its size (estimated from the particle fields,
 *    with a margin) with the space free to this user in the output directory's file system
 *    (statvfs); a shortage is agreed by all ranks, the file is not begun, and the run stops as an
 *    I/O fault.  This is the common case, and collective-safe.
 *  - A write that fails nevertheless (a quota that statvfs does not show, a file system that fills
 *    meanwhile) fails inside parallel HDF5 on some ranks only, while the others wait in its
 *    collective calls: the rank that sees it prints the one line, removes the half-written file and
 *    ends the job (MPI_Abort with SIM_EXIT_IO). */
#pragma once
#include "io/output.h"

/* Output that cannot be written (collective; every rank passes the same message): recorded in
 * out->fault, the first one kept.  The driver hands it to the guard (GuardCheckIO): the run ends
 * with SIM_EXIT_IO and writes nothing more but summary.json, if that fits. */
PetscErrorCode IOFault(Output *out, const char *fmt, ...) PETSC_ATTRIBUTE_FORMAT(2, 3);
/* Whether `bytes` fit in the output directory (collective); if not, an I/O fault naming `file`. */
PetscErrorCode IOSpaceReserve(Output *out, const char *file, PetscReal bytes, PetscBool *ok);
/* Bytes of a snapshot and of a checkpoint of the current state (collective). */
PetscErrorCode IOSpaceSnapshot(Output *out, PetscReal *bytes);
PetscErrorCode IOSpaceCheckpoint(Output *out, PetscReal *bytes);
/* Around a collective write of `file` (written as file.part, then renamed): any error inside is an
 * I/O fault that ends the job from the rank that sees it (push before, pop after). */
PetscErrorCode IOSpacePushWrite(const char *file);
PetscErrorCode IOSpacePopWrite(void);
