/* sphfsi: Smoothed Particle Hydrodynamics for fluid-structure interaction, as a library.  A program
 * of one's own starts sphfsi, registers its scenes (and, if it wants them, the built-in ones), runs
 * the case the options name (-case NAME, -options_file FILE) and finishes:
 *
 *   int main(int argc, char **argv)
 *   {
 *     int status;
 *     if (SPHFSIInitialize(&argc, &argv, NULL, &status)) return status;
 *     PetscCall(SPHFSIRegisterScene(&MyScene));
 *     PetscCall(SPHFSIRun(&status));
 *     PetscCall(SPHFSIFinalize());
 *     return status;
 *   }
 *
 * A scene is written against <sphfsi/scene.h> (docs/api.md). */
#ifndef SPHFSI_H
#define SPHFSI_H
#include <sphfsi/base.h>
#include <sphfsi/material.h>
#include <sphfsi/options.h>
#include <sphfsi/particles.h>
#include <sphfsi/refdata.h>
#include <sphfsi/scene.h>
#include <sphfsi/shapes.h>

/* The interface's version: what this header declares.  Before 1.0 a minor version may change the
 * interface (docs/api.md, "Stability"); the patch version never does. */
#define SPHFSI_VERSION_MAJOR 0
#define SPHFSI_VERSION_MINOR 9
#define SPHFSI_VERSION_PATCH 0
#define SPHFSI_VERSION_GE(major, minor, patch) \
  (SPHFSI_VERSION_MAJOR > (major) || (SPHFSI_VERSION_MAJOR == (major) && (SPHFSI_VERSION_MINOR > (minor) || (SPHFSI_VERSION_MINOR == (minor) && SPHFSI_VERSION_PATCH >= (patch)))))

SPHFSI_EXTERN_C_BEGIN

/* Start MPI, PETSc (help: the program's -help text; NULL: sphfsi's) and the signal handlers that
 * stop a run cleanly.  Returns PETSC_TRUE when the program is to end at once with *status: after
 * -version (printed), a missing -options_file (one line, status 2), or a failed start. */
PetscBool SPHFSIInitialize(int *argc, char ***argv, const char help[], int *status);
/* Make a scene available to -case ops->name (ops must outlive the run; at most 64 scenes). */
PetscErrorCode SPHFSIRegisterScene(const SceneOps *ops);
/* The scenes that come with sphfsi (bin/sphfsi registers them all). */
PetscErrorCode SPHFSIRegisterBuiltinScenes(void);
/* Set up the case of the options on PETSC_COMM_WORLD and run it.  *status is the program's exit
 * status: 0 done (or -help listed), 2 bad input (one line on stderr), 3 stopped by a signal or
 * -max_wall_time (checkpoint written), 4 numerical fault (last good state written), 5 output could not
 * be written.  An internal error returns its PETSc error code. */
PetscErrorCode SPHFSIRun(int *status);
PetscErrorCode SPHFSIFinalize(void);
/* The library's version ("0.9.0") and the commit it was built from. */
const char *SPHFSIVersion(void);
const char *SPHFSICommit(void);

SPHFSI_EXTERN_C_END
#endif
