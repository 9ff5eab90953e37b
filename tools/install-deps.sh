#!/usr/bin/env bash
# Install what sphfsi needs when it is missing: PETSc (with hypre + HDF5), METIS, Open MPI,
# pkg-config (Debian packages), and numpy/h5py/matplotlib for the tools.
set -u
PKGS="petsc-dev libmetis-dev openmpi-bin libopenmpi-dev libhdf5-openmpi-dev pkg-config"

have_petsc() {
  if [ -n "${PETSC_DIR:-}" ]; then [ -f "$PETSC_DIR/lib/petsc/conf/variables" ]; return; fi
  pkg-config --exists PETSc 2>/dev/null
}
have_metis() { [ -n "${METIS_DIR:-}" ] && [ -f "$METIS_DIR/include/metis.h" ] || [ -f /usr/include/metis.h ]; }
have_mpi()   { command -v mpiexec >/dev/null 2>&1 && command -v mpicc >/dev/null 2>&1; }

if have_petsc && have_metis && have_mpi; then
  :
else
  echo "sphfsi: PETSc, METIS or MPI not found; installing Debian packages: $PKGS"
  if [ "$(id -u)" = 0 ]; then SUDO=""
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then SUDO="sudo"
  else
    cat >&2 <<MSG
sphfsi: cannot install packages (not root, no password-less sudo). Ask an administrator for:
    apt-get install $PKGS
or point PETSC_DIR/PETSC_ARCH at your own PETSc (built with --download-hypre --download-hdf5
--download-metis) and METIS_DIR at a METIS installation, then run make again.
MSG
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q || exit 1
  $SUDO apt-get install -y -q $PKGS || exit 1
  have_petsc || { echo "sphfsi: PETSc still not found after installing $PKGS" >&2; exit 1; }
fi

# Python tools (plots, studies); the test suite itself needs only python3's standard library.
PY=${PYTHON:-python3}
if command -v "$PY" >/dev/null 2>&1 && ! "$PY" -c "import numpy, h5py, matplotlib" 2>/dev/null; then
  echo "sphfsi: installing numpy, h5py, matplotlib for the tools (pip)"
  "$PY" -m pip install -q numpy h5py matplotlib 2>/dev/null \
    || "$PY" -m pip install -q --user numpy h5py matplotlib 2>/dev/null \
    || echo "sphfsi: note: could not install numpy/h5py/matplotlib; tools/ plots will not run" >&2
fi
exit 0
