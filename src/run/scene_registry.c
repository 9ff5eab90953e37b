#include "run/scene_registry.h"
#include <sphfsi.h>

#define SCENES_MAX 64
static const SceneOps *Scenes[SCENES_MAX];
static PetscInt        nscenes = 0;

PetscErrorCode SPHFSIRegisterScene(const SceneOps *ops)
{
  const SceneOps *old;
  PetscFunctionBeginUser;
  PetscCheck(ops && ops->name && ops->create && ops->populate, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "A scene needs a name, a create and a populate operation");
  PetscCheck(ops->nprobes >= 0 && ops->nprobes <= SCENE_MAX_PROBES, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Scene %s has %" PetscInt_FMT " probes; at most %d (SCENE_MAX_PROBES)", ops->name, ops->nprobes, SCENE_MAX_PROBES);
  PetscCheck(!ops->nprobes || ops->probe, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "Scene %s names probes but has no probe operation", ops->name);
  PetscCall(SceneFind(ops->name, &old));
  if (old == ops) PetscFunctionReturn(PETSC_SUCCESS); /* registered twice: once is enough */
  PetscCheck(!old, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "A scene named %s is registered already: choose another name", ops->name);
  PetscCheck(nscenes < SCENES_MAX, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "More than %d scenes registered", SCENES_MAX);
  Scenes[nscenes++] = ops;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneFind(const char *name, const SceneOps **ops)
{
  PetscFunctionBeginUser;
  *ops = NULL;
  for (PetscInt k = 0; k < nscenes && !*ops; k++) {
    PetscBool eq;
    PetscCall(PetscStrcmp(name, Scenes[k]->name, &eq));
    if (eq) *ops = Scenes[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SceneListNames(char *buf, size_t len)
{
  PetscFunctionBeginUser;
  buf[0] = 0;
  for (PetscInt k = 0; k < nscenes; k++) {
    PetscCall(PetscStrlcat(buf, Scenes[k]->name, len));
    if (k < nscenes - 1) PetscCall(PetscStrlcat(buf, ", ", len));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
