// Run-time choice of AVX2 kernels: GCC and Clang on x86-64 compile them with a target attribute
// (the build itself stays generic) and GAUSSPHERE_X86_DISPATCH marks where they exist; each
// class that has some keeps its own switch, initialised from CpuHasAvx2(), so that tests can run
// its portable loops on an AVX2 machine too.
#ifndef VCG_EXT_GAUSSPHERE_CPU_DISPATCH_H
#define VCG_EXT_GAUSSPHERE_CPU_DISPATCH_H

// Not in builds that let the compiler fuse multiplies and adds (-mfma, -march=native): there it
// may round the portable loops differently from the kernels, whose results must be the same.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__FMA__)
#define GAUSSPHERE_X86_DISPATCH 1
#include <immintrin.h>
#endif

namespace vcg {
namespace gaussphere {

/// Whether this CPU runs AVX2 instructions (false where the kernels are not compiled).
inline bool CpuHasAvx2()
{
#ifdef GAUSSPHERE_X86_DISPATCH
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

} // namespace gaussphere
} // namespace vcg

#endif
