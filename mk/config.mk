# Toolchain and flags shared by every part, the GNU way: CC, CXX, AR and
# PKG_CONFIG, and the user's CPPFLAGS, CFLAGS, CXXFLAGS and LDFLAGS, come from
# the environment or the command line, e.g. `make CC=clang CFLAGS='-O3 -g'`
# or `make BUILD=/tmp/hylo-build`. The user's flags go after hylo's own on
# every command line (so they can change the optimization or add warnings);
# the flags hylo needs (-std, -ffp-contract=off, the warnings) are always there.
BUILD ?= build
ifeq ($(origin CC),default)
CC := gcc
endif
ifeq ($(origin CXX),default)
CXX := g++
endif
AR ?= ar
PKG_CONFIG ?= pkg-config
CFLAGS ?= -O2 -g
CXXFLAGS ?= -O2 -g
CPPFLAGS ?=
LDFLAGS ?=

# Onboard code is strict C99. -ffp-contract=off: no fused multiply-adds, one
# rounding per operation, which keeps plans bit-identical across x86-64 and
# aarch64 (make cross-test). gcc's ISO modes (-std=c99, -std=c++17) already
# default to it; clang contracts by default, so it is explicit, for C++ too.
C99_REQUIRED := -std=c99 -ffp-contract=off -Wall -Wextra -Werror -pedantic
CXX17_REQUIRED := -std=c++17 -ffp-contract=off -Wall -Wextra -Werror
C99_FLAGS := $(C99_REQUIRED) $(CPPFLAGS) $(CFLAGS)
CXX17_FLAGS := $(CXX17_REQUIRED) $(CPPFLAGS) $(CXXFLAGS)
DEP_FLAGS := -MMD -MP
SAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

# Third-party flags from pkg-config where Debian ships a working .pc file,
# else Debian 12's own. $(call pkg,NAME,--cflags|--libs,FALLBACK)
pkg = $(shell $(PKG_CONFIG) --exists $(1) 2>/dev/null && $(PKG_CONFIG) $(2) $(1) 2>/dev/null || echo '$(3)')
# Third-party headers are included as system headers (-I becomes -isystem)
# so that -Wextra stays about our code.
isystem = $(patsubst -I%,-isystem %,$(filter-out -I/usr/include,$(1)))

# Ipopt's headers need -DHAVE_CSTDDEF (ipopt.pc has it).
IPOPT_CFLAGS := $(call isystem,$(call pkg,ipopt,--cflags,-I/usr/include/coin -DHAVE_CSTDDEF))
# Labels must not depend on the CPU (trainer/numerics.hpp): every program
# that links Ipopt loads Debian's reference BLAS and LAPACK (libblas3,
# liblapack3), not the libblas.so.3/liblapack.so.3 alternatives (OpenBLAS).
# DT_RPATH, not RUNPATH: it also applies to libipopt's and MUMPS's own
# dependencies (they have no RUNPATH of their own).
MULTIARCH := $(or $(shell $(CC) -print-multiarch 2>/dev/null),$(shell gcc -print-multiarch 2>/dev/null))
NUMERICS_LDFLAGS := -Wl,--disable-new-dtags,-rpath,/usr/lib/$(MULTIARCH)/blas:/usr/lib/$(MULTIARCH)/lapack
IPOPT_LIBS := $(NUMERICS_LDFLAGS) $(call pkg,ipopt,--libs,-lipopt)
EIGEN_CFLAGS := $(call isystem,$(call pkg,eigen3,--cflags,-I/usr/include/eigen3))
YAML_CFLAGS := $(call isystem,$(call pkg,yaml-cpp,--cflags,))
YAML_LIBS := $(call pkg,yaml-cpp,--libs,-lyaml-cpp)
CMOCKA_CFLAGS := $(call isystem,$(call pkg,cmocka,--cflags,))
CMOCKA_LIBS := $(call pkg,cmocka,--libs,-lcmocka)
# lcm.pc requires glib-2.0's .pc (libglib2.0-dev), which LCM itself does not
# need: without it, plain -llcm.
LCM_CFLAGS := $(call isystem,$(call pkg,lcm,--cflags,))
LCM_LIBS := $(call pkg,lcm,--libs,-llcm) -pthread
PNG_CFLAGS := $(call isystem,$(call pkg,libpng,--cflags,))
PNG_LIBS := $(call pkg,libpng,--libs,-lpng)
FREETYPE_CFLAGS := $(call isystem,$(call pkg,freetype2,--cflags,-I/usr/include/freetype2))
FREETYPE_LIBS := $(call pkg,freetype2,--libs,-lfreetype)
# Link -lOSMesa and never -lGL (with -lGL every GL call is a no-op).
OSMESA_CFLAGS := $(call isystem,$(call pkg,osmesa,--cflags,))
OSMESA_LIBS := $(call pkg,osmesa,--libs,-lOSMesa)
# No .pc files in Debian 12: SUNDIALS 6.4 and libsvm 3.24.
SUNDIALS_LIBS := -lsundials_cvode
SVM_LIBS := -lsvm

ALL_TARGETS :=
BENCH_TARGETS :=
TESTS :=
TESTS_SAN :=
