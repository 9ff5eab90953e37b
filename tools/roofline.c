/* The machine's limits for issue 57's analysis (docs/performance.md, "How far from the machine"):
 *   memory bandwidth: STREAM's triad a = b + s c over arrays far larger than the caches (24 bytes an
 *     element, STREAM's count: the write-allocate read of a is not counted), best of the repeats;
 *   attainable flop rate: independent fused multiply-adds on data in L1, as the compiler vectorises
 *     them with the code's own flags (-O3 -march=native), and the same loop kept scalar.
 * Every rank runs its own arrays at the same time (MPI_Barrier before each repeat), so the sums are
 * what 1, 2, ... cores reach together.  Built with the library's flags: make bin/roofline.
 *   mpiexec -n P bin/roofline [-n ELEMENTS_PER_RANK] [-repeat R] */
#include <sphfsi/base.h> /* PETSc, and PETSC_SUCCESS before PETSc 3.19 */

#define NACC 64 /* independent FMA chains: enough to cover the FMA latency at any vector width */

/* x = x a + b for every chain, k times: 2 NACC k flops, vectorised by the compiler */
static void FMAVector(double *x, double a, double b, PetscInt k)
{
  for (PetscInt r = 0; r < k; r++)
    for (int j = 0; j < NACC; j++) x[j] = x[j] * a + b;
}

/* the same, one element at a time */
__attribute__((optimize("no-tree-vectorize", "no-tree-slp-vectorize"))) static void FMAScalar(double *x, double a, double b, PetscInt k)
{
  for (PetscInt r = 0; r < k; r++)
    for (int j = 0; j < NACC; j++) x[j] = x[j] * a + b;
}

static void Triad(double *restrict a, const double *restrict b, const double *restrict c, double s, PetscInt n)
{
  for (PetscInt i = 0; i < n; i++) a[i] = b[i] + s * c[i];
}

/* the slowest rank's time of fn's repeats, best repeat */
static PetscErrorCode Best(MPI_Comm comm, PetscInt repeat, void (*body)(void *), void *ctx, PetscReal *best)
{
  PetscFunctionBeginUser;
  *best = PETSC_MAX_REAL;
  for (PetscInt r = 0; r < repeat; r++) {
    PetscLogDouble t0, t1;
    PetscReal      t;
    PetscCallMPI(MPI_Barrier(comm));
    PetscCall(PetscTime(&t0));
    body(ctx);
    PetscCall(PetscTime(&t1));
    t = t1 - t0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &t, 1, MPIU_REAL, MPIU_MAX, comm));
    *best = PetscMin(*best, t);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef struct {
  double  *a, *b, *c, x[NACC];
  PetscInt n, k;
} Work;

static void TriadBody(void *ctx)
{
  Work *w = (Work *)ctx;
  Triad(w->a, w->b, w->c, 3.0, w->n);
}
static void VectorBody(void *ctx)
{
  Work *w = (Work *)ctx;
  FMAVector(w->x, 0.999999, 1e-7, w->k);
}
static void ScalarBody(void *ctx)
{
  Work *w = (Work *)ctx;
  FMAScalar(w->x, 0.999999, 1e-7, w->k);
}

int main(int argc, char **argv)
{
  Work        w      = {.n = 1 << 26, .k = 4000000};
  PetscInt    repeat = 10;
  PetscMPIInt size;
  PetscReal   t, check = 0;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "roofline: memory bandwidth (STREAM triad) and flop rate of this machine"));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &w.n, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-fma_rounds", &w.k, NULL));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscMalloc3(w.n, &w.a, w.n, &w.b, w.n, &w.c));
  for (PetscInt i = 0; i < w.n; i++) { /* first touch */
    w.a[i] = 0;
    w.b[i] = 1;
    w.c[i] = 2;
  }
  for (int j = 0; j < NACC; j++) w.x[j] = j;
  PetscCall(Best(PETSC_COMM_WORLD, repeat, TriadBody, &w, &t));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "roofline: %d rank(s), STREAM triad over %.0f MB a rank: %.1f GB/s together, %.1f GB/s a rank\n", size, 24.0 * w.n / 1e6, 24.0 * w.n * size / t / 1e9, 24.0 * w.n / t / 1e9));
  PetscCall(Best(PETSC_COMM_WORLD, PetscMax(3, repeat / 3), VectorBody, &w, &t));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "roofline: %d rank(s), fused multiply-adds, vectorised as compiled: %.1f GFlop/s together, %.1f a rank\n", size, 2.0 * NACC * w.k * size / t / 1e9, 2.0 * NACC * w.k / t / 1e9));
  PetscCall(Best(PETSC_COMM_WORLD, PetscMax(3, repeat / 3), ScalarBody, &w, &t));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "roofline: %d rank(s), fused multiply-adds, scalar: %.1f GFlop/s together, %.1f a rank\n", size, 2.0 * NACC * w.k * size / t / 1e9, 2.0 * NACC * w.k / t / 1e9));
  for (int j = 0; j < NACC; j++) check += w.x[j];
  check += w.a[w.n / 2];
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "roofline: (checksum %g)\n", (double)check));
  PetscCall(PetscFree3(w.a, w.b, w.c));
  PetscCall(PetscFinalize());
  return 0;
}
