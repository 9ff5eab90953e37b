/* Common includes and compatibility across PETSc versions (3.18 and newer). */
#pragma once
#include <sphfsi/base.h> /* PETSc's types, PETSC_SUCCESS on older versions, RoundToInt */
#include <petscviewer.h>

/* The program's exit statuses besides 0 (docs/cluster.md, "Exit statuses") */
#define SIM_EXIT_BAD_INPUT 2 /* bad input found while setting up: one line on stderr (main.c) */
#define SIM_EXIT_STOPPED 3 /* stopped by a signal or -max_wall_time; checkpoint written */
#define SIM_EXIT_FAULT   4 /* numerical fault; last good state written */
#define SIM_EXIT_IO      5 /* output could not be written (disk full, quota): one line; the last complete checkpoint is kept */
