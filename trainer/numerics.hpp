// The numerics a label depends on, pinned so that every machine computes the
// same labels (docs/decisions.md, "Training labels do not depend on the CPU"):
//  - BLAS and LAPACK: Debian's reference libraries (libblas3, liblapack3),
//    linked by an rpath (NUMERICS_LDFLAGS, mk/config.mk). OpenBLAS picks its
//    kernels by CPU and its sums depend on buffer alignment; a program that
//    solves refuses to run with it or any other BLAS.
//  - libm: glibc picks FMA/AVX2 (and FMA4) variants of exp, sin, pow, ... by
//    CPU at run time, and their last bits differ from the SSE2 variants. On
//    x86-64 the program re-executes itself once with them masked
//    (GLIBC_TUNABLES glibc.cpu.hwcaps), so every CPU takes the SSE2 ones.
#ifndef HYLO_TRAINER_NUMERICS_HPP
#define HYLO_TRAINER_NUMERICS_HPP

#include <string>

namespace hylo::trainer {

// Call first in main() of every program that solves (Ipopt, CVODE). On
// x86-64, unless the libm variants are already masked (or the CPU lacks
// them), re-executes /proc/self/exe with argv and glibc.cpu.hwcaps=-AVX2,
// -FMA,-FMA4 added to GLIBC_TUNABLES (the user's tunables kept, a hwcaps
// mask of theirs extended); it does this once (HYLO_NUMERICS_REEXEC guards
// it). Then checks that no BLAS or LAPACK but the reference one is loaded.
// Returns true to go on; false after saying why on stderr (the exec failed,
// the mask did not take, another BLAS is loaded): main should exit 1.
bool pin_numerics(int argc, char **argv);

// What labels depend on, one "key: value" line each (newline-terminated):
// blas, lapack (real paths of the loaded libraries, marked "(reference)" or
// not), libm (glibc version and the pin), ipopt and mumps (version and the
// loaded library's real path). The dataset .meta records it.
std::string numerics_description();

}  // namespace hylo::trainer

#endif
