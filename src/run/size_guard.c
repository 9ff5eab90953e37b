#include "run/size_guard.h"
#include "base/options_used.h"
#include "solid/solid.h"
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/resource.h>

/* The estimate of a rank's peak resident memory: fixed + (its particles with their ghosts) x
 * BYTES_ARRAYS x the fields' bytes + its particles x (their neighbour list and, with ISPH, their
 * share of the pressure matrix and BoomerAMG) + its solid particles x the solid's own list and fits.
 * Pairs per particle: the lattice points in the kernel's ball (2 h, + the skin where the list keeps
 * candidates).  Calibrated on the peak resident memory of 5-step runs on 2 ranks, 5e4-1e6
 * particles (tools/size_guard_calibration.sh; docs/cluster.md, "Size guard"): 4 to 31 % above it
 * for the dam break (2D) and the 3D hydrostatic tank, WCSPH and ISPH (19 and 32 % on 1 rank), 11 to
 * 27 % for the solids and the WCSPH elastic gate, 3 % for the 3D Taylor-Green (ISPH, 2h = 4 dx), 41 %
 * for the ISPH gate, 53 and 82 % for SPHERIC Test 2, whose walls (40 % of its particles) have fewer
 * pairs and rows than every particle here.  A whole run peaks higher than its first steps (particles
 * and lists moved by rebalancing, walls the water reaches): the WCSPH dam break at 4.8e4 particles to
 * t = 0.3 s by 20 % (144 MB on 2 ranks, the estimate's 144 MB), 27 % with a checkpoint (152 MB). */
#define BYTES_ARRAYS     4.0   /* per byte of fields: capacity grown by half while the scene adds, the partition's and the migration's copies (2.5-3.3 measured) */
#define BYTES_LIST_PAIR  12.0  /* the main list per pair: b and F (W recomputed unless -neighbour_store_w: 8 B more) */
#define BYTES_CANDIDATE  4.0   /* with a skin, the candidates' copy; the list's arrays hold all candidates */
#define BYTES_ISPH_ROW   300.0 /* ISPH per particle: the PPE's vectors, row maps and coarse rows */
#define BYTES_ISPH_PAIR  30.0  /* ISPH per pair: PETSc's matrix and hypre's (12 B each), BoomerAMG's levels (21-30 B measured in all: 30 B with classical coarsening at 2h = 4 dx in 3D) */
#define BYTES_SOLID_PAIR 28.0  /* the solid's own list per pair (b, W, F: 20 B) and the reference kernel gradient (8 B) */
#define FIXED_MARGIN     (8.0 * 1048576)   /* resident per rank besides what it holds before the scene: hypre's and HDF5's first allocations */
#define VM_MARGIN        (128.0 * 1048576) /* address space mapped later per process besides the particles': MPI's buffers, threads' heaps */
#define VM_FACTOR        1.4   /* address space per byte of the estimate's particle part, for capacity malloc'd but never touched: 0.8-1.36 measured per rank (VmPeak less VmSize at start-up), ranks above the mean included */

typedef enum { FITS, OVER_NODE, OVER_VM, OVER_IDS } Verdict;

struct _n_SizeGuard {
  PetscBool   dry, stopped, armed;  /* the dry pass is on; it stopped at the limit; the real population is checked */
  PetscInt64  n, nsolid, n_safe;    /* points counted (every rank walks all: global), of them solid or clamp; below n_safe all fits */
  PetscInt    dim;
  PetscMPIInt size;
  PetscBool   ghosts;                        /* ranks or periodic images make ghosts */
  PetscReal   b_arrays, b_pair, b_solid, w;  /* bytes per particle with its ghosts, per particle, per solid particle; ghost layer (dx) */
  PetscReal   fixed;                         /* resident per rank before the first particle (the largest rank's) */
  PetscReal   share, node_limit;             /* memory per rank of the tightest node, and its limit */
  PetscMPIInt node_ranks;
  char        source[64];                    /* what sets that limit */
  PetscReal   vm_room, vm_limit;             /* address space a process has left and its limit (the tightest rank's); room PETSC_MAX_REAL: none */
  char        vm_name[16];
};

PetscBool SizeGuardCounting(Sim sim) { return (PetscBool)(sim->size_guard && sim->size_guard->dry); }

PetscErrorCode SizeGuardDestroy(SizeGuard *g)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*g));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Ball(PetscInt D, PetscReal r) { return D == 3 ? 4.0 / 3.0 * PETSC_PI * r * r * r : PETSC_PI * r * r; }

/* Resident bytes of one rank's share of n particles, ns of them solid, besides the fixed part; its
 * ghosts as a layer all round a cube of its particles. */
static PetscReal Variable(SizeGuard g, PetscReal n, PetscReal ns)
{
  const PetscReal own = n / g->size, all = g->ghosts ? PetscPowReal(PetscPowReal(own, 1.0 / g->dim) + 2 * g->w, g->dim) : own;
  return all * g->b_arrays + own * g->b_pair + ns / g->size * g->b_solid;
}

static Verdict Judge(SizeGuard g, PetscInt64 n, PetscInt64 ns)
{
  const PetscReal var = Variable(g, (PetscReal)n, (PetscReal)ns);
  const PetscReal node = (g->fixed + var) / g->share, vm = g->vm_room == PETSC_MAX_REAL ? 0 : g->vm_room > 0 ? VM_FACTOR * var / g->vm_room : PETSC_MAX_REAL;
  if (node > 1 || vm > 1) return vm > node ? OVER_VM : OVER_NODE;
  return n > PETSC_MAX_INT ? OVER_IDS : FITS; /* ids are PetscInt */
}

static void Bytes(PetscReal b, char *buf, size_t len)
{
  const char *unit[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int         k      = 0;
  for (; b >= 1024 && k < 6; k++) b /= 1024;
  snprintf(buf, len, b < 100 && k ? "%.1f %s" : "%.0f %s", (double)b, unit[k]);
}

/* The one line that stops the run (collective: every rank has the same counts and limits). */
static PetscErrorCode Refuse(Sim sim, PetscBool at_least)
{
  SizeGuard       g   = sim->size_guard;
  const Verdict   v   = Judge(g, g->n, g->nsolid);
  const PetscReal var = Variable(g, (PetscReal)g->n, (PetscReal)g->nsolid), own = (PetscReal)g->n / g->size;
  char            count[96], need[32], each[32], fixed[32], lim[32], total[32];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(count, sizeof(count), "the scene has %s%" PetscInt64_FMT " particles at -dx %g", at_least ? "at least " : "", g->n, (double)sim->phys.dx));
  PetscCheck(v != OVER_IDS, sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s, more than this build can number (PETSc's 32-bit PetscInt: %d): choose a larger -dx, or PETSc configured --with-64-bit-indices", count, (int)PETSC_MAX_INT);
  Bytes(own > 0 ? var / own : 0, each, sizeof(each));
  Bytes(g->fixed, fixed, sizeof(fixed));
  if (v == OVER_VM) {
    Bytes(VM_FACTOR * var, need, sizeof(need));
    Bytes(g->vm_room, lim, sizeof(lim));
    Bytes(g->vm_limit, total, sizeof(total));
    SETERRQ(sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: about %s of address space per rank on %d rank(s) (%s per particle; docs/cluster.md), more than the %s a process has left under its limit of %s (%s): choose a larger -dx, run on more ranks, or raise the limit", count, need, (int)g->size, each, lim, total, g->vm_name);
  }
  Bytes(g->fixed + var, need, sizeof(need));
  Bytes(g->share, lim, sizeof(lim));
  Bytes(g->node_limit, total, sizeof(total));
  SETERRQ(sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: about %s per rank on %d rank(s) (%s + %s per particle; docs/cluster.md), more than the %s per rank a node allows (%s: %s, shared by its %d rank(s)): choose a larger -dx, run on more nodes, or give -max_memory with the memory of a node (e.g. 64G) if it has more", count, need, (int)g->size, fixed, each, lim, total, g->source, (int)g->node_ranks);
}

PetscErrorCode SizeGuardAdd(Sim sim, ParticleKind kind, PetscInt64 n)
{
  SizeGuard g = sim->size_guard;
  PetscFunctionBeginUser;
  if (!g || !(g->dry || g->armed)) PetscFunctionReturn(PETSC_SUCCESS);
  g->n += n;
  if (KindIsSolid(kind)) g->nsolid += n;
  if (g->n <= g->n_safe || Judge(g, g->n, g->nsolid) == FITS) PetscFunctionReturn(PETSC_SUCCESS);
  if (g->dry) { /* back through the scene to SizeGuardCheck, silently (its error handler) */
    g->stopped = PETSC_TRUE;
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "The count passed the limit");
  }
  PetscCall(Refuse(sim, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* "8G", "500M", "1.5T", "2e9": bytes, or K, M, G, T, P (powers of 1024), optionally followed by B or iB. */
static PetscBool ParseBytes(const char *s, PetscReal *v)
{
  const char *units = "KMGTP", *u;
  char       *end;
  double      x = strtod(s, &end);
  if (end == s || !(x > 0) || x > 1e30) return PETSC_FALSE;
  if (*end && (u = strchr(units, toupper((unsigned char)*end)))) {
    for (const char *k = units; k <= u; k++) x *= 1024;
    if (*++end == 'i') end++;
    if (*end == 'B') end++;
  } else if (*end == 'B') end++;
  *v = x;
  return (PetscBool)(*end == 0);
}

/* A limit in bytes from a file of the cgroup tree; none (PETSC_MAX_REAL) for "max", v1's "unlimited" (~2^63) or no file. */
static PetscReal ReadLimit(const char *path)
{
  FILE  *f = fopen(path, "r");
  double v = 0;
  int    ok;
  if (!f) return PETSC_MAX_REAL;
  ok = fscanf(f, "%lf", &v) == 1;
  fclose(f);
  return ok && v > 0 && v < 1e18 ? (PetscReal)v : PETSC_MAX_REAL;
}

/* The memory limit of this process's cgroup and its ancestors (v2 memory.max, v1 memory.limit_in_bytes). */
static PetscReal CgroupLimit(void)
{
  FILE     *f = fopen("/proc/self/cgroup", "r");
  char      line[1024], path[PETSC_MAX_PATH_LEN + 64];
  PetscReal lim = PETSC_MAX_REAL;
  if (!f) return lim;
  while (fgets(line, sizeof(line), f)) {
    char *ctl = strchr(line, ':'), *rel = ctl ? strchr(ctl + 1, ':') : NULL, *nl, *cut;
    const char *base, *file;
    size_t      nbase;
    if (!rel) continue;
    if ((nl = strchr(rel, '\n'))) *nl = 0;
    if (!strncmp(line, "0::", 3)) { base = "/sys/fs/cgroup"; file = "memory.max"; }
    else if (strstr(ctl, "memory") && strstr(ctl, "memory") < rel) { base = "/sys/fs/cgroup/memory"; file = "memory.limit_in_bytes"; }
    else continue;
    snprintf(path, sizeof(path), "%s%s", base, rel + 1);
    nbase = strlen(base);
    for (;;) { /* the cgroup, then each parent up to the root of the mount */
      size_t len = strlen(path);
      snprintf(path + len, sizeof(path) - len, "%s%s", path[len - 1] == '/' ? "" : "/", file);
      lim       = PetscMin(lim, ReadLimit(path));
      path[len] = 0;
      if (len <= nbase || !(cut = strrchr(path, '/')) || (size_t)(cut - path) < nbase) break;
      *cut = 0;
    }
  }
  fclose(f);
  return lim;
}

/* Resident and virtual bytes of this process now (/proc/self/statm); a typical start-up's without it. */
static void ProcessBytes(PetscReal *rss, PetscReal *vm)
{
  FILE         *f    = fopen("/proc/self/statm", "r");
  unsigned long size = 0, res = 0;
  const long    page = sysconf(_SC_PAGESIZE);
  *rss = 40.0 * 1048576;
  *vm  = 300.0 * 1048576;
  if (!f) return;
  if (fscanf(f, "%lu %lu", &size, &res) == 2 && page > 0) {
    *rss = (PetscReal)res * page;
    *vm  = (PetscReal)size * page;
  }
  fclose(f);
}

/* The limits, the same on every rank: the tightest node's memory per rank and the tightest
 * process's address space. */
static PetscErrorCode Limits(Sim sim, SizeGuard g, PetscBool given, PetscReal max_memory)
{
  struct { double v; int rank; } mine, tight;
  struct { double limit; int ranks; char source[64]; } node;
  struct { double room, limit; char name[16]; } vm = {PETSC_MAX_REAL, 0, ""};
  MPI_Comm  shm;
  PetscReal rss, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_split_type(sim->comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &shm));
  PetscCallMPI(MPI_Comm_size(shm, &node.ranks));
  PetscCallMPI(MPI_Comm_free(&shm));
  if (given) {
    node.limit = max_memory;
    PetscCall(PetscStrncpy(node.source, "-max_memory", sizeof(node.source)));
  } else {
    const long      pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const PetscReal phys = pages > 0 && page > 0 ? (PetscReal)pages * page : PETSC_MAX_REAL, cg = CgroupLimit();
    node.limit = PetscMin(phys, cg);
    PetscCall(PetscStrncpy(node.source, cg < phys ? "its cgroup's memory limit" : "physical memory", sizeof(node.source)));
  }
  mine.v    = node.limit / node.ranks;
  mine.rank = sim->rank;
  PetscCallMPI(MPI_Allreduce(&mine, &tight, 1, MPI_DOUBLE_INT, MPI_MINLOC, sim->comm));
  PetscCallMPI(MPI_Bcast(&node, sizeof(node), MPI_BYTE, tight.rank, sim->comm));
  g->share      = tight.v;
  g->node_limit = node.limit;
  g->node_ranks = node.ranks;
  PetscCall(PetscStrncpy(g->source, node.source, sizeof(g->source)));

  ProcessBytes(&rss, &size);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &rss, 1, MPIU_REAL, MPIU_MAX, sim->comm));
  g->fixed = rss + FIXED_MARGIN;
  { /* a process's address space: ulimit -v (RLIMIT_AS) and -d (RLIMIT_DATA, private mappings since Linux 4.7) */
    const int   res[2]  = {RLIMIT_AS, RLIMIT_DATA};
    const char *name[2] = {"ulimit -v", "ulimit -d"};
    for (int k = 0; k < 2; k++) {
      struct rlimit rl;
      if (getrlimit(res[k], &rl) || rl.rlim_cur == RLIM_INFINITY || (double)rl.rlim_cur - size - VM_MARGIN >= vm.room) continue;
      vm.room  = (double)rl.rlim_cur - size - VM_MARGIN;
      vm.limit = (double)rl.rlim_cur;
      PetscCall(PetscStrncpy(vm.name, name[k], sizeof(vm.name)));
    }
  }
  mine.v = vm.room;
  PetscCallMPI(MPI_Allreduce(&mine, &tight, 1, MPI_DOUBLE_INT, MPI_MINLOC, sim->comm));
  PetscCallMPI(MPI_Bcast(&vm, sizeof(vm), MPI_BYTE, tight.rank, sim->comm));
  g->vm_room  = vm.room;
  g->vm_limit = vm.limit;
  PetscCall(PetscStrncpy(g->vm_name, vm.name, sizeof(g->vm_name)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Bytes per particle of this run's fields, lists and schemes (after ParticlesSetUp). */
static PetscErrorCode Model(Sim sim, SizeGuard g)
{
  const PetscInt  D = sim->phys.dim;
  const PetscReal hf = sim->phys.kernel.h_factor, skin = sim->nbhd.skin / sim->phys.dx;
  PetscBool       store_w = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-neighbour_store_w", &store_w, NULL)); /* SimSetUp reads it after the scene */
  g->dim        = D;
  g->size       = sim->size;
  g->b_arrays   = BYTES_ARRAYS * ParticlesBytesPerParticle(sim->P);
  g->b_pair     = skin > 0 ? Ball(D, 2 * hf + skin) * (BYTES_LIST_PAIR + (store_w ? 8 : 0) + BYTES_CANDIDATE) : Ball(D, 2 * hf) * (BYTES_LIST_PAIR + (store_w ? 8 : 0));
  g->w          = 2 * hf + skin;
  if (sim->phys.isph) g->b_pair += BYTES_ISPH_ROW + BYTES_ISPH_PAIR * Ball(D, 2 * hf);
  if (sim->phys.solid) { /* the total-Lagrangian fits (order 2 at most) in capacity grown by half */
    const PetscInt nb = D + D * (D + 1) / 2;
    g->b_solid = BYTES_SOLID_PAIR * Ball(D, 2 * hf + sim->phys.solid->skin) + 1.5 * sizeof(PetscReal) * (nb * nb + D * D + D * nb);
    g->w += sim->phys.solid->skin;
  }
  g->ghosts = (PetscBool)(sim->size > 1);
  for (PetscInt d = 0; d < D; d++) g->ghosts = (PetscBool)(g->ghosts || sim->periodic[d]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SizeGuardCheck(Sim sim)
{
  SizeGuard g;
  char      text[64] = "node"; /* -help shows it as the default: the node's memory */
  PetscBool given, force = PETSC_FALSE;
  PetscReal max_memory = 0, lattice = 1;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&g));
  sim->size_guard = g;
  PetscOptionsBegin(sim->comm, NULL, "Size guard", "Sim");
  /* not recorded in options_used unless given: a default would pin this node's memory on a rerun elsewhere */
  PetscCall(PetscOptionsString("-max_memory", "Memory a node may give this run, all its ranks together: bytes, or with K, M, G, T (powers of 1024: 8G, 500M); the run stops at set-up when its estimate exceeds it; default: the node's physical memory or its cgroup's limit, whichever is smaller", "", text, text, sizeof(text), &given));
  PetscCall(OptBool("-size_guard_count", "Count the scene's particles before allocating them even when the domain's lattice fits the memory (a check of the size guard: the run is the same bit for bit)", "", force, &force, NULL));
  PetscOptionsEnd();
  PetscCheck(!given || ParseBytes(text, &max_memory), sim->comm, PETSC_ERR_ARG_OUTOFRANGE, "-max_memory %s is not a size: give bytes (8000000000) or a number with K, M, G or T (powers of 1024: 8G, 500M)", text);
  PetscCall(Model(sim, g));
  PetscCall(Limits(sim, g, given, max_memory));
  { /* below n_safe every count fits, solids or not: SizeGuardAdd's test in the real population is then a comparison */
    PetscInt64 lo = 0, hi = (PetscInt64)1 << 62;
    while (hi - lo > 1) {
      const PetscInt64 mid = lo + (hi - lo) / 2;
      if (Judge(g, mid, sim->phys.solid ? mid : 0) == FITS) lo = mid;
      else hi = mid;
    }
    g->n_safe = lo;
  }
  PetscCall(PetscInfo(NULL, "Size guard: %g B per rank + %g B per particle with its ghosts + %g B per particle (+ %g B per solid one); limit %g B per rank (%s over %d ranks), address space left %g B; all fits below %" PetscInt64_FMT " particles\n", (double)g->fixed, (double)g->b_arrays, (double)g->b_pair, (double)g->b_solid, (double)g->share, g->source, (int)g->node_ranks, (double)g->vm_room, g->n_safe));
  /* the domain's lattice at -dx bounds the scene's count (-case boxes may space a box finer: the real population checks) */
  for (PetscInt d = 0; d < sim->phys.dim; d++) lattice *= (sim->dom_hi[d] - sim->dom_lo[d]) / sim->phys.dx + 1;
  /* The dry pass: the scene's populate with the builders counting.  What it leaves is undone or
   * redone: the ids and the extrusion here; in the scenes' contexts (src/scenes) hydrostatic and
   * water_on_plate round their extents to whole particles (the same values again), taylor_green's
   * E0 and water_on_plate's weights are sums over the particles (an allreduce every rank reaches,
   * the stop being at the same point on all) set again by the real pass, the level gauges' column
   * tables are recomputed the same; no scene checks a count.  tools/bitcheck.sh with
   * -size_guard_count 1 compares every case file bit for bit. */
  if (force || lattice > (PetscReal)g->n_safe) {
    const PetscInt              next_id = sim->next_id;
    const __typeof__(sim->extrude) extrude = sim->extrude; /* a scene stopped between SceneExtrudeBegin and End */
    PetscErrorCode              ierr;
    g->dry = PETSC_TRUE;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = sim->scene->populate(sim); /* not PetscCall: the stop at the limit returns through the scene */
    PetscCall(PetscPopErrorHandler());
    g->dry       = PETSC_FALSE;
    sim->next_id = next_id;
    sim->extrude = extrude;
    PetscCheck(sim->P->n == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The dry count added %" PetscInt_FMT " particles", sim->P->n);
    PetscCall(PetscInfo(NULL, "Size guard: the dry count %s %" PetscInt64_FMT " particles (%" PetscInt64_FMT " solid): estimate %g B resident per rank\n", g->stopped ? "stopped at" : ierr ? "failed after" : "found", g->n, g->nsolid, (double)(g->fixed + Variable(g, (PetscReal)g->n, (PetscReal)g->nsolid))));
    if (g->stopped || (!ierr && Judge(g, g->n, g->nsolid) != FITS)) PetscCall(Refuse(sim, g->stopped));
    /* another error of the scene's: its real population raises it again, with its message */
  }
  g->n = g->nsolid = 0;
  g->armed = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
