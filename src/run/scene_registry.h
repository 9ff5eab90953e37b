/* The scenes a run can be given (-case NAME): those registered (SPHFSIRegisterScene, <sphfsi.h>). */
#pragma once
#include <sphfsi/scene.h>

/* The scene of that name (NULL: none). */
PetscErrorCode SceneFind(const char *name, const SceneOps **ops);
/* Their names, "a, b, c", in the order registered. */
PetscErrorCode SceneListNames(char *buf, size_t len);
