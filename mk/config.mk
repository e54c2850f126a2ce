# Toolchain and flags shared by every part. Override on the command line,
# e.g. `make CC=clang` or `make BUILD=/tmp/hylo-build`.
BUILD ?= build
CC := gcc
CXX := g++
AR := ar

# Onboard code is strict C99; -std=c99 also rules out FMA contraction, which
# keeps results bit-identical across x86-64 and aarch64 (deps.md).
C99_FLAGS := -std=c99 -Wall -Wextra -Werror -pedantic -O2 -g
CXX17_FLAGS := -std=c++17 -Wall -Wextra -Werror -O2 -g
DEP_FLAGS := -MMD -MP
SAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

# Third-party headers are included as system headers so that -Wextra stays
# about our code. Ipopt needs -DHAVE_CSTDDEF (deps.md).
IPOPT_CFLAGS := -isystem /usr/include/coin -DHAVE_CSTDDEF
# Labels must not depend on the CPU (trainer/numerics.hpp): every program
# that links Ipopt loads Debian's reference BLAS and LAPACK (libblas3,
# liblapack3), not the libblas.so.3/liblapack.so.3 alternatives (OpenBLAS).
# DT_RPATH, not RUNPATH: it also applies to libipopt's and MUMPS's own
# dependencies (they have no RUNPATH of their own).
MULTIARCH := $(shell $(CC) -print-multiarch)
NUMERICS_LDFLAGS := -Wl,--disable-new-dtags,-rpath,/usr/lib/$(MULTIARCH)/blas:/usr/lib/$(MULTIARCH)/lapack
IPOPT_LIBS := $(NUMERICS_LDFLAGS) -lipopt
SUNDIALS_LIBS := -lsundials_cvode
EIGEN_CFLAGS := -isystem /usr/include/eigen3
YAML_LIBS := -lyaml-cpp
SVM_LIBS := -lsvm
CMOCKA_LIBS := -lcmocka
LCM_LIBS := -llcm -pthread

ALL_TARGETS :=
BENCH_TARGETS :=
TESTS :=
TESTS_SAN :=
