/* The scenes that come with sphfsi, in the order -help lists them. */
#include <sphfsi.h>

extern const SceneOps SceneHydrostatic, SceneDamBreak, SceneDamBreakLobovsky, SceneDamBreakBuchner, SceneSluiceGate, SceneTaylorGreen, ScenePoiseuille, SceneOscillatingPlate, SceneSolidBlock, SceneElasticGate, SceneWaterOnPlate, SceneSphericTest2, SceneTurekHron;
extern const SceneOps SceneParticlesFile, SceneOpenChannel;
extern SceneOps       SceneBoxes; /* its probes come from the options */

PetscErrorCode SPHFSIRegisterBuiltinScenes(void)
{
  const SceneOps *const all[] = {&SceneHydrostatic, &SceneDamBreak, &SceneDamBreakLobovsky, &SceneDamBreakBuchner, &SceneSluiceGate, &SceneTaylorGreen, &ScenePoiseuille, &SceneOscillatingPlate, &SceneSolidBlock, &SceneElasticGate, &SceneWaterOnPlate, &SceneSphericTest2, &SceneTurekHron, &SceneBoxes, &SceneParticlesFile, &SceneOpenChannel};
  PetscFunctionBeginUser;
  for (size_t k = 0; k < sizeof(all) / sizeof(all[0]); k++) PetscCall(SPHFSIRegisterScene(all[k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}
