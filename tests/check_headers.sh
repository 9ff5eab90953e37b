#!/usr/bin/env bash
# The public interface (include/): every header compiles on its own, with -Wall -Wextra -pedantic
# -Werror, as C99 and as C++ (extern "C"), and says in its first comment what it is for.  PETSc's own
# headers are taken as system headers (their warnings are not ours).
cd "$(dirname "$0")/.." || exit 2
OUT=${1:-out/tests/headers}; mkdir -p "$OUT"
if [ -n "${PETSC_DIR:-}" ]; then
  PETSC_INC=$(make --no-print-directory -s -f - print <<'MK'
include $(PETSC_DIR)/lib/petsc/conf/variables
print: ; @echo $(PETSC_CC_INCLUDES)
MK
)
else
  PETSC_INC=$(pkg-config --cflags PETSc)
fi
SYS=$(echo " $PETSC_INC" | sed 's/ -I/ -isystem /g')
CC=${CC_MPI:-mpicc}; CXX=${CXX_MPI:-mpicxx}
n=0; bad=0
for h in include/sphfsi.h include/sphfsi/*.h; do
  name=${h#include/}
  head -c 300 "$h" | grep -q '^/\*' || { echo "headers: $h does not open with a comment saying what it is for"; bad=$((bad + 1)); }
  printf '#include <%s>\nint main(void) { return 0; }\n' "$name" > "$OUT/one.c"
  cp "$OUT/one.c" "$OUT/one.cc"
  $CC -std=c99 -pedantic -Wall -Wextra -Werror -Iinclude $SYS -fsyntax-only "$OUT/one.c" > "$OUT/c.log" 2>&1 || { echo "headers: $name as C99:"; head -5 "$OUT/c.log"; bad=$((bad + 1)); }
  $CXX -std=c++11 -pedantic -Wall -Wextra -Werror -Iinclude $SYS -fsyntax-only "$OUT/one.cc" > "$OUT/cxx.log" 2>&1 || { echo "headers: $name as C++:"; head -5 "$OUT/cxx.log"; bad=$((bad + 1)); }
  n=$((n + 1))
done
# only public headers in include/ (internals stay in src/)
extra=$(find include -type f ! -name '*.h' | head -3)
[ -z "$extra" ] || { echo "headers: include/ holds more than headers: $extra"; bad=$((bad + 1)); }
echo "headers: $n public headers, each alone as C99 and C++ with -Wall -Wextra -pedantic -Werror: $([ $bad = 0 ] && echo ok || echo "$bad problem(s)")"
[ $bad = 0 ]
