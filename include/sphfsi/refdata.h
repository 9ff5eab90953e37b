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

/* Mean and standard deviation of the values with t in [t0, t1] (0, 0 if none): a steady state's. */
void SeriesMean(const Series *s, PetscReal t0, PetscReal t1, PetscReal *mean, PetscReal *std);

/* A periodic history as benchmarks define it (Turek & Hron 2006): over whole periods, mean =
 * (max + min) / 2, amplitude = (max - min) / 2 and the frequency.  The periods are those between
 * upward crossings of the level (max + min) / 2 of the history from t_from on (linear interpolation
 * between samples); the window is the last `last` of them (0: all).  With smooth > 0 the history is
 * first averaged over a centred window of that width (s), against a high-frequency noise whose
 * peaks would count as the extremes and whose wiggles as crossings: say so when comparing. */
typedef struct {
  PetscReal mean, amplitude, frequency; /* frequency in 1/(the unit of t) */
  PetscReal t0, t1;                     /* the window: its first and last crossing */
  PetscInt  periods;                    /* whole periods in it (0: fewer than two crossings, nothing else set) */
} SeriesPeriodicStats;
PetscErrorCode SeriesPeriodic(const Series *s, PetscReal t_from, PetscInt last, PetscReal smooth, SeriesPeriodicStats *r);

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

/* One row of a keyed table in FILE of the reference data: the row whose column key[0] is val[0] and
 * column key[1] is val[1] (case-insensitive; key[1] NULL: one key), and its columns col[0..n) as
 * numbers (an empty cell or a missing column: 0).  Rank 0 reads; every rank of comm gets the row;
 * *found says whether it was there. */
PetscErrorCode RefDataRow(RefData *rd, MPI_Comm comm, const char *file, const char *const key[2], const char *const val[2], PetscInt n, const char *const col[], PetscReal out[], PetscBool *found);

/* Relative errors |sim - ref| / |ref| at the reference points with ref.t in [t0, t1], where the
 * simulated series is sampled at ref.t * tscale and its values divided by yscale. */
PetscErrorCode SeriesCompare(const Series *sim, const Series *ref, PetscReal tscale, PetscReal yscale, PetscReal t0, PetscReal t1, PetscBool relative, PetscReal *rms, PetscReal *max, PetscInt *npts);
SPHFSI_EXTERN_C_END
#endif
