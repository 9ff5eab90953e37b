/* Counts of every MPI call a process makes, by PETSc log stage: an LD_PRELOAD shim (PMPI), so that
 * the messages of hypre (BoomerAMG, which PETSc's -log_view cannot see: hypre is not compiled with
 * PETSc's counting macros) and the code's own MPI_Alltoallv count as well as PETSc's.  Nothing in the
 * program changes: each wrapper counts, then calls the PMPI_ routine.
 *   point to point: sends (MPI_Send/Isend/Issend/Ssend/Sendrecv, and each start of a persistent
 *     send, which PetscSF uses) to another rank, and their bytes; sends to the rank itself apart;
 *     exchange rounds (the sends posted between two completions: one latency each);
 *   collectives on communicators of more than one rank, by kind, and the bytes a rank contributes;
 *     MPI_Alltoallv also the destinations it has something for (the messages a sparse exchange
 *     would send), MPI_Alltoall(v) the P - 1 pairwise steps Open MPI runs.
 * The stage is the one the program last pushed (PetscLogStagePush, interposed too), so the counts
 * split into the code's phases (Halo+migrate, PPE solve, ...); "Main Stage" holds the set-up; inside
 * hypre's HYPRE_BoomerAMGSetup / HYPRE_BoomerAMGSolve (interposed) the stages "AMG setup" and
 * "AMG V-cycle" (stages of the PPE solve).
 * At MPI_Finalize each rank writes $COUNT_MPI_DIR/rank<r>.csv: one row per stage that saw traffic.
 * Build (tools/count_traffic.sh does): mpicc -shared -fPIC -O2 tools/count_mpi.c -o build/libcount_mpi.so -ldl
 * Use: COUNT_MPI_DIR=dir mpiexec -x LD_PRELOAD=build/libcount_mpi.so -x COUNT_MPI_DIR -n P bin/sphfsi ... */
#define _GNU_SOURCE
#include <mpi.h>
#include <dlfcn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { C_ALLREDUCE, C_BCAST, C_REDUCE, C_SCAN, C_ALLGATHER, C_GATHER, C_ALLTOALL, C_ALLTOALLV, C_BARRIER, C_IBARRIER, C_OTHER, NCOLL };
static const char *coll_name[NCOLL] = {"allreduce", "bcast", "reduce", "scan", "allgather", "gather", "alltoall", "alltoallv", "barrier", "ibarrier", "other_coll"};

#define MAX_STAGES 64
typedef struct {
  double sends, send_bytes, self_sends, rounds, coll[NCOLL], coll_bytes, a2av_dests, a2a_pairs;
} Counts;
static Counts cnt[MAX_STAGES];
static char   stage_name[MAX_STAGES][64] = {"Main Stage"};
static int    stack[256], depth, world_rank = -1;
/* An exchange round: the sends a rank posts before it next waits for a completion (MPI_Wait*,
 * MPI_Test*, a blocking receive); a blocking send is a round of its own.  A round costs one
 * latency however many neighbours it reaches (the model's alpha + o per further message). */
static int    in_round;

static int Stage(void) { return depth > 0 && stack[depth - 1] >= 0 && stack[depth - 1] < MAX_STAGES ? stack[depth - 1] : 0; }

/* Persistent sends: request -> (bytes, another rank?), counted at each start.  Open addressing;
 * a request freed is marked dead (key 1), never reused as a key by a live one. */
#define MAP_SIZE (1 << 17)
typedef struct {
  uintptr_t key;
  double    bytes;
  int       remote;
} Slot;
static Slot map[MAP_SIZE];
static double map_overflow;

static Slot *Find(uintptr_t k, int insert)
{
  size_t i = (k >> 4) & (MAP_SIZE - 1);
  for (size_t n = 0; n < MAP_SIZE; n++, i = (i + 1) & (MAP_SIZE - 1)) {
    if (map[i].key == k) return &map[i];
    if (map[i].key == 0 || (insert && map[i].key == 1)) return insert ? &map[i] : NULL;
  }
  return NULL;
}

static double Bytes(int count, MPI_Datatype t)
{
  int s = 0;
  PMPI_Type_size(t, &s);
  return (double)count * s;
}

static int Size(MPI_Comm c)
{
  int s = 1;
  PMPI_Comm_size(c, &s);
  return s;
}

static void Send(int count, MPI_Datatype t, int dest, MPI_Comm c)
{
  int r;
  if (dest == MPI_PROC_NULL) return;
  PMPI_Comm_rank(c, &r);
  if (dest == r) { cnt[Stage()].self_sends++; return; }
  cnt[Stage()].sends++;
  cnt[Stage()].send_bytes += Bytes(count, t);
  if (!in_round) cnt[Stage()].rounds++;
  in_round = 1;
}

static void Blocking(void) { in_round = 0; } /* a blocking send ends its round */

static void Coll(int kind, double bytes, MPI_Comm c)
{
  if (Size(c) < 2) return;
  cnt[Stage()].coll[kind]++;
  cnt[Stage()].coll_bytes += bytes;
}

/* ---- PETSc log stages ---- */
typedef int (*PushFn)(int);
typedef int (*PopFn)(void);
typedef int (*RegFn)(const char *, int *);

int PetscLogStageRegister(const char *name, int *stage)
{
  static RegFn real;
  int          e;
  if (!real) real = (RegFn)dlsym(RTLD_NEXT, "PetscLogStageRegister");
  e = real(name, stage);
  if (!e && *stage >= 0 && *stage < MAX_STAGES) snprintf(stage_name[*stage], sizeof(stage_name[0]), "%s", name);
  return e;
}

int PetscLogStagePush(int stage)
{
  static PushFn real;
  if (!real) real = (PushFn)dlsym(RTLD_NEXT, "PetscLogStagePush");
  if (depth < 256) stack[depth] = stage;
  depth++;
  return real(stage);
}

int PetscLogStagePop(void)
{
  static PopFn real;
  if (!real) real = (PopFn)dlsym(RTLD_NEXT, "PetscLogStagePop");
  if (depth > 0) depth--;
  return real();
}

/* ---- hypre's BoomerAMG (through PETSc's PCHYPRE): its set-up and its V-cycles as stages of their
 * own, so that the PPE's traffic splits into what the set-up costs at every step and the rest ---- */
#define STAGE_AMG_SETUP (MAX_STAGES - 2)
#define STAGE_AMG_SOLVE (MAX_STAGES - 1)
typedef int (*AmgFn)(void *, void *, void *, void *);

static int Amg(const char *fn, int stage, const char *name, void *s, void *A, void *b, void *x)
{
  AmgFn real = (AmgFn)dlsym(RTLD_NEXT, fn);
  int   e;
  snprintf(stage_name[stage], sizeof(stage_name[0]), "%s", name);
  if (depth < 256) stack[depth] = stage;
  depth++;
  e = real(s, A, b, x);
  depth--;
  return e;
}
int HYPRE_BoomerAMGSetup(void *s, void *A, void *b, void *x) { return Amg("HYPRE_BoomerAMGSetup", STAGE_AMG_SETUP, "AMG setup", s, A, b, x); }
int HYPRE_BoomerAMGSolve(void *s, void *A, void *b, void *x) { return Amg("HYPRE_BoomerAMGSolve", STAGE_AMG_SOLVE, "AMG V-cycle", s, A, b, x); }

/* ---- point to point ---- */
int MPI_Send(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c) { Send(n, t, d, c); Blocking(); return PMPI_Send(b, n, t, d, tag, c); }
int MPI_Ssend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c) { Send(n, t, d, c); Blocking(); return PMPI_Ssend(b, n, t, d, tag, c); }
int MPI_Isend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request *r) { Send(n, t, d, c); return PMPI_Isend(b, n, t, d, tag, c, r); }
int MPI_Issend(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request *r) { Send(n, t, d, c); return PMPI_Issend(b, n, t, d, tag, c, r); }
int MPI_Sendrecv(const void *sb, int sn, MPI_Datatype st, int d, int stag, void *rb, int rn, MPI_Datatype rt, int s, int rtag, MPI_Comm c, MPI_Status *status)
{
  Send(sn, st, d, c);
  Blocking();
  return PMPI_Sendrecv(sb, sn, st, d, stag, rb, rn, rt, s, rtag, c, status);
}

int MPI_Send_init(const void *b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request *r)
{
  int e = PMPI_Send_init(b, n, t, d, tag, c, r), me;
  Slot *s;
  PMPI_Comm_rank(c, &me);
  if (e == MPI_SUCCESS && d != MPI_PROC_NULL && (s = Find((uintptr_t)*r, 1))) {
    s->key = (uintptr_t)*r; s->bytes = Bytes(n, t); s->remote = d != me;
  } else if (e == MPI_SUCCESS) map_overflow++;
  return e;
}

static void Started(MPI_Request r)
{
  Slot *s = Find((uintptr_t)r, 0);
  if (!s) return; /* a persistent receive */
  if (!s->remote) { cnt[Stage()].self_sends++; return; }
  cnt[Stage()].sends++;
  cnt[Stage()].send_bytes += s->bytes;
  if (!in_round) cnt[Stage()].rounds++;
  in_round = 1;
}

int MPI_Start(MPI_Request *r) { Started(*r); return PMPI_Start(r); }
int MPI_Startall(int n, MPI_Request r[])
{
  for (int k = 0; k < n; k++) Started(r[k]);
  return PMPI_Startall(n, r);
}
int MPI_Request_free(MPI_Request *r)
{
  Slot *s = Find((uintptr_t)*r, 0);
  if (s) s->key = 1;
  return PMPI_Request_free(r);
}

/* completions end a round */
int MPI_Wait(MPI_Request *r, MPI_Status *st) { in_round = 0; return PMPI_Wait(r, st); }
int MPI_Waitall(int n, MPI_Request r[], MPI_Status st[]) { in_round = 0; return PMPI_Waitall(n, r, st); }
int MPI_Waitany(int n, MPI_Request r[], int *i, MPI_Status *st) { in_round = 0; return PMPI_Waitany(n, r, i, st); }
int MPI_Waitsome(int n, MPI_Request r[], int *no, int i[], MPI_Status st[]) { in_round = 0; return PMPI_Waitsome(n, r, no, i, st); }
int MPI_Test(MPI_Request *r, int *f, MPI_Status *st) { in_round = 0; return PMPI_Test(r, f, st); }
int MPI_Testall(int n, MPI_Request r[], int *f, MPI_Status st[]) { in_round = 0; return PMPI_Testall(n, r, f, st); }
int MPI_Testany(int n, MPI_Request r[], int *i, int *f, MPI_Status *st) { in_round = 0; return PMPI_Testany(n, r, i, f, st); }
int MPI_Testsome(int n, MPI_Request r[], int *no, int i[], MPI_Status st[]) { in_round = 0; return PMPI_Testsome(n, r, no, i, st); }
int MPI_Recv(void *b, int n, MPI_Datatype t, int s, int tag, MPI_Comm c, MPI_Status *st) { in_round = 0; return PMPI_Recv(b, n, t, s, tag, c, st); }

/* ---- collectives ---- */
int MPI_Allreduce(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) { Coll(C_ALLREDUCE, Bytes(n, t), c); return PMPI_Allreduce(sb, rb, n, t, op, c); }
int MPI_Iallreduce(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c, MPI_Request *r) { Coll(C_ALLREDUCE, Bytes(n, t), c); return PMPI_Iallreduce(sb, rb, n, t, op, c, r); }
int MPI_Reduce(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, int root, MPI_Comm c) { Coll(C_REDUCE, Bytes(n, t), c); return PMPI_Reduce(sb, rb, n, t, op, root, c); }
int MPI_Reduce_scatter_block(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) { Coll(C_REDUCE, Bytes(n, t) * Size(c), c); return PMPI_Reduce_scatter_block(sb, rb, n, t, op, c); }
int MPI_Bcast(void *b, int n, MPI_Datatype t, int root, MPI_Comm c) { Coll(C_BCAST, Bytes(n, t), c); return PMPI_Bcast(b, n, t, root, c); }
int MPI_Scan(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) { Coll(C_SCAN, Bytes(n, t), c); return PMPI_Scan(sb, rb, n, t, op, c); }
int MPI_Exscan(const void *sb, void *rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) { Coll(C_SCAN, Bytes(n, t), c); return PMPI_Exscan(sb, rb, n, t, op, c); }
int MPI_Barrier(MPI_Comm c) { Coll(C_BARRIER, 0, c); return PMPI_Barrier(c); }
int MPI_Ibarrier(MPI_Comm c, MPI_Request *r) { Coll(C_IBARRIER, 0, c); return PMPI_Ibarrier(c, r); }
int MPI_Allgather(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt, MPI_Comm c) { Coll(C_ALLGATHER, Bytes(sn, st), c); return PMPI_Allgather(sb, sn, st, rb, rn, rt, c); }
int MPI_Allgatherv(const void *sb, int sn, MPI_Datatype st, void *rb, const int rn[], const int dis[], MPI_Datatype rt, MPI_Comm c) { Coll(C_ALLGATHER, Bytes(sn, st), c); return PMPI_Allgatherv(sb, sn, st, rb, rn, dis, rt, c); }
int MPI_Gather(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt, int root, MPI_Comm c) { Coll(C_GATHER, Bytes(sn, st), c); return PMPI_Gather(sb, sn, st, rb, rn, rt, root, c); }
int MPI_Gatherv(const void *sb, int sn, MPI_Datatype st, void *rb, const int rn[], const int dis[], MPI_Datatype rt, int root, MPI_Comm c) { Coll(C_GATHER, Bytes(sn, st), c); return PMPI_Gatherv(sb, sn, st, rb, rn, dis, rt, root, c); }
int MPI_Scatter(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt, int root, MPI_Comm c) { Coll(C_OTHER, Bytes(rn, rt), c); return PMPI_Scatter(sb, sn, st, rb, rn, rt, root, c); }
int MPI_Scatterv(const void *sb, const int sn[], const int dis[], MPI_Datatype st, void *rb, int rn, MPI_Datatype rt, int root, MPI_Comm c) { Coll(C_OTHER, Bytes(rn, rt), c); return PMPI_Scatterv(sb, sn, dis, st, rb, rn, rt, root, c); }
int MPI_Alltoall(const void *sb, int sn, MPI_Datatype st, void *rb, int rn, MPI_Datatype rt, MPI_Comm c)
{
  int P = Size(c);
  Coll(C_ALLTOALL, Bytes(sn, st) * (P - 1), c);
  if (P > 1) cnt[Stage()].a2a_pairs += P - 1;
  return PMPI_Alltoall(sb, sn, st, rb, rn, rt, c);
}
int MPI_Alltoallv(const void *sb, const int sn[], const int sd[], MPI_Datatype st, void *rb, const int rn[], const int rd[], MPI_Datatype rt, MPI_Comm c)
{
  int P = Size(c), me;
  PMPI_Comm_rank(c, &me);
  if (P > 1) {
    double b = 0;
    for (int q = 0; q < P; q++)
      if (q != me && sn[q] > 0) { b += Bytes(sn[q], st); cnt[Stage()].a2av_dests++; }
    Coll(C_ALLTOALLV, b, c);
    cnt[Stage()].a2a_pairs += P - 1;
  }
  return PMPI_Alltoallv(sb, sn, sd, st, rb, rn, rd, rt, c);
}

/* ---- set-up and the report ---- */
int MPI_Init(int *argc, char ***argv)
{
  int e = PMPI_Init(argc, argv);
  PMPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  return e;
}

int MPI_Init_thread(int *argc, char ***argv, int req, int *prov)
{
  int e = PMPI_Init_thread(argc, argv, req, prov);
  PMPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  return e;
}

int MPI_Finalize(void)
{
  const char *dir = getenv("COUNT_MPI_DIR");
  char        path[4096];
  FILE       *f;
  if (dir && world_rank >= 0) {
    snprintf(path, sizeof(path), "%s/rank%05d.csv", dir, world_rank);
    if ((f = fopen(path, "w"))) {
      fprintf(f, "stage,sends,send_bytes,self_sends,rounds,coll_bytes,a2av_dests,a2a_pairs");
      for (int k = 0; k < NCOLL; k++) fprintf(f, ",%s", coll_name[k]);
      fprintf(f, "\n");
      for (int s = 0; s < MAX_STAGES; s++) {
        Counts *c = &cnt[s];
        double  any = c->sends + c->self_sends;
        for (int k = 0; k < NCOLL; k++) any += c->coll[k];
        if (!any) continue;
        fprintf(f, "%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f", stage_name[s][0] ? stage_name[s] : "?", c->sends, c->send_bytes, c->self_sends, c->rounds, c->coll_bytes, c->a2av_dests, c->a2a_pairs);
        for (int k = 0; k < NCOLL; k++) fprintf(f, ",%.0f", c->coll[k]);
        fprintf(f, "\n");
      }
      if (map_overflow) fprintf(f, "# persistent sends not tracked: %.0f\n", map_overflow);
      fclose(f);
    }
  }
  return PMPI_Finalize();
}
