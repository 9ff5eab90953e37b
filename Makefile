# sphfsi — build, test, run.  `make run` and `make check` install missing dependencies first.
#
# PETSc is taken from PETSC_DIR/PETSC_ARCH when PETSC_DIR is set (PETSc's own conf/variables),
# else from pkg-config (PETSc).  METIS: METIS_DIR (include/, lib/) or the system paths.

.DEFAULT_GOAL := all
SHELL := /bin/bash

ifeq ($(shell id -u),0)
export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
endif

ifdef PETSC_DIR
  include $(PETSC_DIR)/lib/petsc/conf/variables
  PETSC_CFLAGS := $(PETSC_CC_INCLUDES)
  PETSC_LIBS   := $(PETSC_WITH_EXTERNAL_LIB)
  CC           := $(PCC)
else
  PETSC_CFLAGS := $(shell pkg-config --cflags PETSc 2>/dev/null) $(shell pkg-config --cflags hdf5-mpi 2>/dev/null || pkg-config --cflags hdf5 2>/dev/null)
  PETSC_LIBS   := $(shell pkg-config --libs PETSc 2>/dev/null) $(shell pkg-config --libs hdf5-mpi 2>/dev/null || pkg-config --libs hdf5 2>/dev/null)
  # hypre, when PETSc has it: src/base/csr_hypre.c builds hypre matrices itself
  PETSC_VARS   := $(shell pkg-config --variable=prefix PETSc 2>/dev/null)/lib/petsc/conf/petscvariables
  PETSC_CFLAGS += $(shell sed -n 's/^HYPRE_INCLUDE = //p' $(PETSC_VARS) 2>/dev/null)
  PETSC_LIBS   += $(shell sed -n 's/^HYPRE_LIB = //p' $(PETSC_VARS) 2>/dev/null)
  CC           := mpicc
endif
ifdef METIS_DIR
  METIS_CFLAGS := -I$(METIS_DIR)/include
  METIS_LIBS   := -L$(METIS_DIR)/lib -Wl,-rpath,$(METIS_DIR)/lib -lmetis
else
  METIS_LIBS   := -lmetis
endif

# MARCH: the instruction set.  -march=native builds for the CPU of the machine that compiles; for
# compute nodes that differ from it, build on one of them or give a portable target, e.g.
# `make clean; make MARCH=-march=x86-64-v3` (AVX2 and FMA, 2013 on) or `MARCH=` (any x86-64).
MARCH   ?= -march=native
# -march=native also tunes for the CPU, unless the compiler cannot name it (a virtual machine that
# hides the model): it then tunes for a generic x86, which, among others, never uses vector gathers,
# and the pair loops that SPHPairsSum vectorises run no faster than scalar ones (docs/performance.md).
# Tune for the CPU that -march=native found instead (GCC; nothing changes where it names the model).
ifeq ($(MARCH),-march=native)
  NATIVE_ARCH := $(shell $(CC) -march=native -Q --help=target 2>/dev/null | awk '$$1 == "-march=" {print $$2; exit}')
  NATIVE_TUNE := $(shell $(CC) -march=native -mtune=native -v -E -x c /dev/null 2>&1 | grep -o 'mtune=[a-z0-9-]*' | grep -v '=native' | head -1)
  ifeq ($(NATIVE_TUNE),mtune=generic)
    ifneq ($(NATIVE_ARCH),)
      MARCH := $(MARCH) $(shell $(CC) -mtune=$(NATIVE_ARCH) -E -x c /dev/null >/dev/null 2>&1 && echo -mtune=$(NATIVE_ARCH))
    endif
  endif
endif
OPT     ?= -O3 $(MARCH) -fno-math-errno
SAN     ?=
ifeq ($(SAN),1)
  SANFLAGS := -fsanitize=address,undefined
  OPT      := -O1 -g -fno-omit-frame-pointer $(SANFLAGS)
  BUILD    := build-san
  BINDIR   := bin/san
  # Open MPI and HDF5 keep allocations until exit: leak reports there are not ours
  export ASAN_OPTIONS ?= detect_leaks=0
  export UBSAN_OPTIONS ?= print_stacktrace=1:halt_on_error=1
else
  SANFLAGS :=
  BUILD    := build
  BINDIR   := bin
endif
CFLAGS  := $(OPT) -std=gnu11 -Wall -Wextra -Wno-unused-parameter -Iinclude -Isrc $(PETSC_CFLAGS) $(METIS_CFLAGS)
LDLIBS  := $(PETSC_LIBS) $(METIS_LIBS) -lm
LDFLAGS := $(SANFLAGS)

# src/<layer>/: base, particles, physics (fluid, solid), io, run, build, scenes, app (docs/architecture.md);
# internal headers beside their sources, the public interface in include/ (<sphfsi.h>, <sphfsi/*.h>)
LIB_SRC  := $(wildcard src/*/*.c)
LIB_SRC  := $(filter-out src/app/main.c,$(LIB_SRC))
LIB_OBJ  := $(LIB_SRC:%.c=$(BUILD)/%.o)
TEST_SRC := $(wildcard tests/test_*.c)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BINDIR)/%)
BIN      := $(BINDIR)/sphfsi
# The library: lib/libsphfsi.a (bin/sphfsi and the tests link it) and lib/libsphfsi.so (objects built
# again as position-independent code; a program of one's own links it through pkg-config sphfsi)
LIBDIR   := $(if $(filter 1,$(SAN)),lib/san,lib)
LIB_A    := $(LIBDIR)/libsphfsi.a
LIB_SO   := $(LIBDIR)/libsphfsi.so
SO_MAJOR := $(firstword $(subst ., ,$(shell cat VERSION 2>/dev/null || echo 0)))
PIC_OBJ  := $(LIB_SRC:%.c=$(BUILD)/pic/%.o)

NP      ?= $(shell nproc 2>/dev/null || echo 2)
MPIEXEC ?= mpiexec
# Open MPI refuses more ranks than cores without --oversubscribe (and then yields when idle by itself).
# Open MPI 4 prints "mpiexec (OpenRTE) 4.1.4", 5 "(Open MPI)".  At 2 ranks on 2 cores the flag changes
# nothing: the ranks are still bound to a core each and mpi_yield_when_idle stays 0 (read through MPI_T).
MPIEXEC_FLAGS ?= $(shell $(MPIEXEC) --version 2>/dev/null | grep -Eqi "open ?-?mpi|openrte" && echo --oversubscribe)
export MPIEXEC MPIEXEC_FLAGS

.PHONY: all deps run check check-unit bench hard ranks study slurm clean tests install layers FORCE
all: $(BIN) $(TEST_BIN) $(if $(filter 1,$(SAN)),,$(LIB_SO))

HEADERS := $(wildcard src/*/*.h include/*.h include/sphfsi/*.h)
$(BUILD)/%.o: %.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@
$(BUILD)/pic/%.o: %.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fPIC -fno-semantic-interposition -c $< -o $@

# The version (file VERSION) and the commit, for -version and summary.json, and the absolute path of
# the reference data of this source tree (REFDATA), so that the program finds them from any current
# directory (the lookup order: src/base/refdata.c): rewritten only when they change.
REFDATA ?= ../shared/refdata
SPHFSI_VERSION := $(shell cat VERSION 2>/dev/null || echo unknown)
SPHFSI_COMMIT  := $(shell git rev-parse --short HEAD 2>/dev/null || echo unknown)$(shell git rev-parse HEAD >/dev/null 2>&1 && ! git diff --quiet HEAD -- src 2>/dev/null && echo +modified)
$(BUILD)/sphfsi_build.h: FORCE
	@mkdir -p $(BUILD)
	@printf '#define SPHFSI_VERSION "%s"\n#define SPHFSI_COMMIT "%s"\n#define SPHFSI_SOURCE_REFDATA "%s"\n' '$(SPHFSI_VERSION)' '$(SPHFSI_COMMIT)' '$(abspath $(REFDATA))' > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi
$(BUILD)/src/base/version.o $(BUILD)/pic/src/base/version.o: $(BUILD)/sphfsi_build.h
$(BUILD)/src/base/version.o $(BUILD)/pic/src/base/version.o: CFLAGS += -I$(BUILD)
FORCE:
# The files whose pair loops SPHPairsSum vectorises (src/particles/pair_loop.h): a term's branches
# become selects only where the compiler may evaluate both sides, that is where no floating-point
# exception traps (a division in a lane that is not selected).  The code traps none, so no result
# changes.
VECTOR_PAIR_SRC := src/fluid/wcsph.c
$(VECTOR_PAIR_SRC:%.c=$(BUILD)/%.o) $(VECTOR_PAIR_SRC:%.c=$(BUILD)/pic/%.o): CFLAGS += -fno-trapping-math

$(LIB_A): $(LIB_OBJ)
	@mkdir -p $(LIBDIR)
	@rm -f $@; ar rcs $@ $^

$(LIB_SO): $(PIC_OBJ)
	@mkdir -p $(LIBDIR)
	$(CC) $(LDFLAGS) -shared -Wl,-soname,libsphfsi.so.$(SO_MAJOR) -o $@ $^ $(LDLIBS)

$(BIN): $(BUILD)/src/app/main.o $(LIB_A)
	@mkdir -p $(BINDIR)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BINDIR)/test_%: $(BUILD)/tests/test_%.o $(LIB_A)
	@mkdir -p $(BINDIR)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

tests: $(BIN) $(TEST_BIN)

# Parallel compilation for `make check` (a clean checkout compiles in half the time on 2 cores)
BUILD_JOBS ?= $(shell nproc 2>/dev/null || echo 2)

# Installs the Debian packages when PETSc (or METIS) cannot be found; does nothing otherwise.
deps:
	@bash tools/install-deps.sh

CASE ?= elastic_gate
run: deps
	@$(MAKE) --no-print-directory all
	$(MPIEXEC) $(MPIEXEC_FLAGS) -n $(NP) $(BIN) -options_file cases/$(CASE).opts -overwrite $(ARGS)

# The test suite on 2 MPI ranks; ends with 'N passed, N failed'.  SAN=1: the unit tests built with
# AddressSanitizer + UndefinedBehaviorSanitizer (bin/san/).
check: deps
	@$(MAKE) --no-print-directory -j$(BUILD_JOBS) all
	@BINDIR=$(BINDIR) bash tests/run_tests.sh $(if $(filter 1,$(SAN)),--unit-only,)

# Throughput, scaling, memory and the partition model (tools/bench.sh; out/bench/bench.md, ~20 min on 2 cores).
bench: deps
	@$(MAKE) --no-print-directory all $(BINDIR)/partition_model $(BINDIR)/roofline
	@BINDIR=$(BINDIR) bash tools/bench.sh

# Hard cases of issue 6 (tools/hard.sh; each case PASS/FAIL with why, out/hard/hard.md, ~25 min on 2
# cores).  2 ranks unless NP is given on the command line or in the environment.
hard: deps
	@$(MAKE) --no-print-directory all
	@BINDIR=$(BINDIR) NP=$(if $(filter command line environment,$(origin NP)),$(NP),2) bash tools/hard.sh

# The batch recipe of docs/cluster.md under a real SLURM on this machine (issue 46): as root, installs
# Debian's slurm-wlm and munge if missing, starts a one-node cluster (tools/slurm_local.sh), runs
# tools/slurm_check.sh (sbatch, scancel, a 1 min time limit, --signal, resubmission)
# into out/slurm and stops the cluster it started.  Skipped with one line when not root or SLURM
# cannot be installed.  Not part of `make check`, not in CI.
slurm: deps
	@$(MAKE) --no-print-directory all
	@bash tools/slurm_check.sh --setup $(CURDIR)/out/slurm

# Past two ranks (issue 46): small cases on 3, 8 and 16 ranks against 1 rank (2D and 3D, WCSPH, ISPH, the
# gate), restarts 8 -> 3 and 3 -> 8, ranks without particles, too many ranks, rebalancing at every step
# (tools/ranks.sh; each check PASS/FAIL with the measured value and bound, out/ranks/ranks.md; 21 min here
# at a load of 20-36 from other jobs, 10 min of CPU).  The ranks are oversubscribed on a small machine
# (the script adds --oversubscribe when MPIEXEC_FLAGS lacks it; Open MPI then yields when idle).
ranks: deps
	@$(MAKE) --no-print-directory all
	@BINDIR=$(BINDIR) bash tools/ranks.sh

# Speed against error: every validated scene, each scheme at 3 resolutions on NP ranks (tools/study.sh;
# out/study/study.md + one PNG per scene, ~30 min on 2 cores).  STUDY_SCENES (subset), STUDY_REUSE=1
# (keep earlier results), STUDY_SIZE=cluster (5 resolutions, for a cluster), NP (ranks; 2 unless given).
study: deps
	@$(MAKE) --no-print-directory all
	@BINDIR=$(BINDIR) $(if $(filter command line environment,$(origin NP)),NP=$(NP)) bash tools/study.sh

# The layers of the code and the calls that cross them upward (tools/layers.py; --list for each one)
layers:
	@python3 tools/layers.py --list

# The machine's memory bandwidth and flop rate (tools/roofline.c; docs/performance.md)
$(BINDIR)/roofline: $(BUILD)/tools/roofline.o $(LIB_A)
	@mkdir -p $(BINDIR)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# Partition statistics of a scene's cell graph for many ranks (tools/partition_model.c)
$(BINDIR)/partition_model: $(BUILD)/tools/partition_model.o $(LIB_A)
	@mkdir -p $(BINDIR)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# Install for users who do not run from the source tree: PREFIX/bin/sphfsi, the case files and tools
# in PREFIX/share/sphfsi (cases/, tools/) and the reference data (REFDATA, ../shared/refdata) in
# PREFIX/share/sphfsi/refdata, where the installed program finds it; the library for programs of
# one's own: PREFIX/include (sphfsi.h, sphfsi/), PREFIX/lib (libsphfsi.a, libsphfsi.so) and
# PREFIX/lib/pkgconfig/sphfsi.pc (pkg-config --cflags --libs sphfsi; it Requires PETSc's own .pc).
PREFIX  ?= /usr/local
SHARE   := $(DESTDIR)$(PREFIX)/share/sphfsi
PC_REQUIRES := $(if $(PETSC_DIR),,PETSc)
install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(SHARE)/cases/boxes $(SHARE)/tools $(SHARE)/refdata $(DESTDIR)$(PREFIX)/include/sphfsi $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/sphfsi
	install -m 644 include/sphfsi.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 include/sphfsi/*.h $(DESTDIR)$(PREFIX)/include/sphfsi/
	install -m 644 $(LIB_A) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(LIB_SO) $(DESTDIR)$(PREFIX)/lib/libsphfsi.so.$(SPHFSI_VERSION)
	ln -sf libsphfsi.so.$(SPHFSI_VERSION) $(DESTDIR)$(PREFIX)/lib/libsphfsi.so.$(SO_MAJOR)
	ln -sf libsphfsi.so.$(SO_MAJOR) $(DESTDIR)$(PREFIX)/lib/libsphfsi.so
	@printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$${prefix}/lib' 'includedir=$${prefix}/include' '' \
	  'Name: sphfsi' 'Description: Smoothed Particle Hydrodynamics for fluid-structure interaction (MPI, PETSc)' \
	  'Version: $(SPHFSI_VERSION)' 'Requires: $(PC_REQUIRES)' \
	  'Cflags: -I$${includedir} $(if $(PETSC_DIR),$(PETSC_CFLAGS))' \
	  'Libs: -L$${libdir} -Wl,-rpath,$${libdir} -lsphfsi $(if $(PETSC_DIR),$(PETSC_LIBS)) -lm' \
	  'Libs.private: $(METIS_LIBS)' > $(DESTDIR)$(PREFIX)/lib/pkgconfig/sphfsi.pc
	install -m 644 cases/*.opts $(SHARE)/cases/
	install -m 644 cases/boxes/*.opts cases/boxes/*.txt cases/boxes/*.stl $(SHARE)/cases/boxes/
	install -m 755 tools/*.py tools/*.sh $(SHARE)/tools/
	@if [ -d "$(REFDATA)" ]; then install -m 644 $(REFDATA)/*.csv $(SHARE)/refdata/; else echo "sphfsi: no reference data at $(REFDATA) (REFDATA=...): summary.json will have no errors against experiments"; fi
	@echo "installed: $(DESTDIR)$(PREFIX)/bin/sphfsi; cases in $(SHARE)/cases"

clean:
	rm -rf build build-san bin lib out
