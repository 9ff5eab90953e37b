/* Size guard: a run that cannot fit in memory stops before its scene allocates the particles, with
 * one line (bad input, exit status 2) that names the particle count, the estimate per rank and the
 * limit, instead of allocating until the kernel kills it or a malloc fails deep inside.
 *
 * The limit: -max_memory (per node), else the smaller of the node's physical memory and its cgroup's
 * limit, shared by the node's ranks; and each process's address space (ulimit -v, -d) when limited.
 * The count: when the domain's lattice at -dx could exceed the limit (or -size_guard_count), the
 * scene is populated once dry (its builders count and add nothing; the ids and the extrusion are
 * restored after), stopping as soon as the estimate passes the limit.  The real population checks
 * the same estimate as it goes, for scenes whose particles are spaced finer than -dx.  The estimate
 * per particle and its calibration: size_guard.c and docs/cluster.md. */
#pragma once
#include "run/sim.h"

PetscErrorCode SizeGuardCheck(Sim sim);
/* Called by the scene's builders (scene.c) for n points of one kind: during the dry pass they are
 * counted; during the real population the run stops once the count passes the limit (collective:
 * every rank walks every point, so every rank stops at the same one). */
PetscErrorCode SizeGuardAdd(Sim sim, ParticleKind kind, PetscInt64 n);
/* During the dry pass: the builders count (SizeGuardAdd) and add no particle. */
PetscBool      SizeGuardCounting(Sim sim);
PetscErrorCode SizeGuardDestroy(SizeGuard *g);
