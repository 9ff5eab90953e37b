/* Statistics of probe histories (<sphfsi/refdata.h>): a steady state's mean, a periodic one's mean,
 * amplitude and frequency as the benchmarks define them. */
#include "base/refdata.h"

void SeriesMean(const Series *s, PetscReal t0, PetscReal t1, PetscReal *mean, PetscReal *std)
{
  PetscReal n = 0, sum = 0, sum2 = 0;
  for (PetscInt k = 0; k < s->n; k++)
    if (s->t[k] >= t0 && s->t[k] <= t1) { n += 1; sum += s->y[k]; sum2 += s->y[k] * s->y[k]; }
  *mean = n > 0 ? sum / n : 0;
  *std  = n > 1 ? PetscSqrtReal(PetscMax(0, sum2 / n - *mean * *mean)) : 0;
}

/* The centred moving average of y over [t - w/2, t + w/2] at each sample (two running indices). */
static void Smooth(const Series *s, PetscReal w, PetscReal *ys)
{
  PetscInt  lo = 0, hi = 0;
  PetscReal sum = 0;
  for (PetscInt k = 0; k < s->n; k++) {
    while (hi < s->n && s->t[hi] <= s->t[k] + 0.5 * w) sum += s->y[hi++];
    while (s->t[lo] < s->t[k] - 0.5 * w) sum -= s->y[lo++];
    ys[k] = sum / (hi - lo);
  }
}

PetscErrorCode SeriesPeriodic(const Series *s, PetscReal t_from, PetscInt last, PetscReal smooth, SeriesPeriodicStats *r)
{
  PetscReal *y, lo = PETSC_MAX_REAL, hi = -PETSC_MAX_REAL, level, tc[2] = {0, 0};
  PetscInt   nc = 0, k = 0, i0 = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(r, sizeof(*r)));
  if (s->n < 3) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMalloc1(s->n, &y));
  if (smooth > 0) Smooth(s, smooth, y);
  else PetscCall(PetscArraycpy(y, s->y, s->n));
  while (i0 < s->n && s->t[i0] < t_from) i0++;
  for (PetscInt i = i0; i < s->n; i++) { lo = PetscMin(lo, y[i]); hi = PetscMax(hi, y[i]); }
  level = 0.5 * (lo + hi);
  for (PetscInt i = i0 + 1; i < s->n; i++) nc += y[i - 1] < level && y[i] >= level;
  if (nc >= 2) {
    r->periods = last > 0 ? PetscMin(last, nc - 1) : nc - 1;
    for (PetscInt i = i0 + 1; i < s->n; i++) /* the window's first and last crossings */
      if (y[i - 1] < level && y[i] >= level) {
        PetscReal t = s->t[i - 1] + (s->t[i] - s->t[i - 1]) * (level - y[i - 1]) / (y[i] - y[i - 1]);
        if (k == nc - 1 - r->periods) tc[0] = t;
        if (k == nc - 1) tc[1] = t;
        k++;
      }
    lo = PETSC_MAX_REAL; hi = -PETSC_MAX_REAL;
    for (PetscInt i = i0; i < s->n; i++)
      if (s->t[i] >= tc[0] && s->t[i] <= tc[1]) { lo = PetscMin(lo, y[i]); hi = PetscMax(hi, y[i]); }
    r->mean      = 0.5 * (hi + lo);
    r->amplitude = 0.5 * (hi - lo);
    r->frequency = r->periods / (tc[1] - tc[0]);
    r->t0        = tc[0];
    r->t1        = tc[1];
  }
  PetscCall(PetscFree(y));
  PetscFunctionReturn(PETSC_SUCCESS);
}
