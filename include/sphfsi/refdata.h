/* Reference curves and probe histories: a scene keeps its probes' histories as Series, loads the
 * reference's columns from the reference data (CSV with '#' comments) and reports the errors in
 * summary.json (SceneOps.errors). */
#ifndef SPHFSI_REFDATA_H
#define SPHFSI_REFDATA_H
#include <sphfsi/base.h>
#include <stdio.h>

SPHFSI_EXTERN_C_BEGIN

typedef struct _n_Series Series;
struct _n_Series {
  PetscInt   n, cap;
  PetscReal *t, *y;
};

PetscErrorCode SeriesAppend(Series *s, PetscReal t, PetscReal y);
PetscErrorCode SeriesDestroy(Series *s);
/* Drop the points with y >= ymax (a reference measured beyond what the scene's geometry can hold). */
void SeriesKeepBelow(Series *s, PetscReal ymax);
/* Linear interpolation (clamped to the ends). */
PetscReal SeriesAt(const Series *s, PetscReal t);

/* The largest value of a series for t in [t0, t1] and its time (-PETSC_MAX_REAL, 0 if none). */
void SeriesPeak(const Series *s, PetscReal t0, PetscReal t1, PetscReal *v, PetscReal *t);

/* Where the reference files are looked for, and those that were not found: the driver owns one
 * (SimRefData in <sphfsi/scene.h>) and hands it to the scenes, whose errors read the files, and to summary.json. */
typedef struct {
  PetscMPIInt rank;                    /* only rank 0 reads the files */
  char        dir[PETSC_MAX_PATH_LEN]; /* -refdata_dir; empty: $SPHFSI_REFDATA or the default folders */
  char       *missing;                 /* rank 0: the files not found, "a.csv", "b.csv" (NULL: none) */
} RefData;

/* Open FILE of the reference data for reading, on rank 0 (*f NULL on the others): from -refdata_dir,
 * else $SPHFSI_REFDATA, else the first of PREFIX/share/sphfsi/refdata (installed), <exe dir>/refdata,
 * the source tree's (REFDATA at build time) and ../shared/refdata from the current directory that
 * holds it.  Not found: *f NULL, one warning line on stdout per file and the file in
 * summary.json's reference_missing (rd->missing). */
PetscErrorCode RefDataOpen(RefData *rd, const char *file, FILE **f);

/* Load columns xcol, ycol of FILE of the reference data (RefDataOpen). On rank 0 only; *found says
 * whether the file was there with those columns. */
PetscErrorCode RefDataLoad(RefData *rd, const char *file, const char *xcol, const char *ycol, Series *ref, PetscBool *found);

/* Relative errors |sim - ref| / |ref| at the reference points with ref.t in [t0, t1], where the
 * simulated series is sampled at ref.t * tscale and its values divided by yscale. */
PetscErrorCode SeriesCompare(const Series *sim, const Series *ref, PetscReal tscale, PetscReal yscale, PetscReal t0, PetscReal t1, PetscBool relative, PetscReal *rms, PetscReal *max, PetscInt *npts);
SPHFSI_EXTERN_C_END
#endif
