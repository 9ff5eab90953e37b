/* bin/sphfsi: the library's program with the built-in scenes (a program of one's own looks the same,
 * with its scenes registered: cases/user_scene/). */
#include <sphfsi.h>

int main(int argc, char **argv)
{
  int status;
  if (SPHFSIInitialize(&argc, &argv, NULL, &status)) return status;
  PetscCall(SPHFSIRegisterBuiltinScenes());
  PetscCall(SPHFSIRun(&status));
  PetscCall(SPHFSIFinalize());
  return status;
}
