/* A parallel HDF5 snapshot reads back: every id once, every field equal to what was written (with
 * -fluid isph or -wcsph_shift also the free-surface flag, `free_surface`). */
#include "run/sim.h"
#include <sphfsi.h>
#include "io/io.h"
#include <petscviewerhdf5.h>

static PetscErrorCode CompareField(Sim sim, PetscViewer v, const char *name, const PetscReal *a, PetscInt width, PetscReal *err)
{
  Vec                vec;
  const PetscScalar *r;
  PetscFunctionBeginUser;
  PetscCall(VecCreate(sim->comm, &vec));
  PetscCall(VecSetSizes(vec, width * sim->P->n, PETSC_DECIDE));
  PetscCall(VecSetBlockSize(vec, width));
  PetscCall(VecSetType(vec, VECSTANDARD));
  PetscCall(PetscObjectSetName((PetscObject)vec, name));
  PetscCall(VecLoad(vec, v));
  PetscCall(VecGetArrayRead(vec, &r));
  for (PetscInt k = 0; k < width * sim->P->n; k++) *err = PetscMax(*err, PetscAbsReal(r[k] - a[k]));
  PetscCall(VecRestoreArrayRead(vec, &r));
  PetscCall(VecDestroy(&vec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim         sim;
  PetscViewer v;
  IS          is;
  PetscReal   err = 0;
  PetscInt    N, *seen, nfields = 0;
  const char *path = "out/test_hdf5/snap.h5";
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(PetscOptionsSetValue(NULL, "-overwrite", NULL)); /* a test reruns into its own output directories */
  PetscCall(PetscOptionsSetValue(NULL, "-case", "dam_break"));
  PetscCall(PetscOptionsSetValue(NULL, "-dx", "0.004"));
  PetscCall(PetscOptionsSetValue(NULL, "-output_dir", "out/test_hdf5"));
  PetscCall(SimCreate(PETSC_COMM_WORLD, &sim));
  PetscCall(SimSetFromOptions(sim));
  PetscCall(SimSetUp(sim));
  PetscCall(IOWriteParticles(&sim->out, path));
  PetscCall(PetscViewerHDF5Open(sim->comm, path, FILE_MODE_READ, &v));
  { /* the snapshot's fields (the field table, particles.h) */
    FieldId out[FIELD_COUNT];
    nfields = ParticlesSnapshotFields(sim->P, out);
    for (PetscInt k = 0; k < nfields; k++) PetscCall(CompareField(sim, v, sim->P->f[out[k]].name, sim->P->f[out[k]].a, sim->P->f[out[k]].width, &err));
  }
  /* ids: the whole dataset on every rank; each id exactly once */
  PetscCall(ISCreate(sim->comm, &is));
  PetscCall(PetscObjectSetName((PetscObject)is, "id"));
  PetscCall(ISLoad(is, v));
  {
    const PetscInt *ids;
    PetscInt        n, nglob;
    PetscCall(ISGetLocalSize(is, &n));
    PetscCall(ISGetSize(is, &nglob));
    N = sim->nbhd.nparticles;
    PetscCheck(nglob == N, sim->comm, PETSC_ERR_PLIB, "Snapshot holds %" PetscInt_FMT " ids, expected %" PetscInt_FMT, nglob, N);
    PetscCall(PetscCalloc1(N, &seen));
    PetscCall(ISGetIndices(is, &ids));
    for (PetscInt k = 0; k < n; k++) { PetscCheck(ids[k] >= 0 && ids[k] < N, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Bad id"); seen[ids[k]]++; }
    PetscCall(ISRestoreIndices(is, &ids));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, seen, N, MPIU_INT, MPI_SUM, sim->comm));
    for (PetscInt k = 0; k < N; k++) PetscCheck(seen[k] == 1, sim->comm, PETSC_ERR_PLIB, "id %" PetscInt_FMT " appears %" PetscInt_FMT " times", k, seen[k]);
    PetscCall(PetscFree(seen));
  }
  PetscCall(ISDestroy(&is));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &err, 1, MPIU_REAL, MPIU_MAX, sim->comm));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "hdf5: %" PetscInt_FMT " particles, %" PetscInt_FMT " fields read back, max difference %g; every id once\n", N, nfields, (double)err));
  PetscCheck(err == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Fields read back differ by %g", (double)err);
  PetscCall(SimDestroy(&sim));
  PetscCall(PetscFinalize());
  return 0;
}
