#pragma once
// The calibration loop's per-sample kernels are chains of dependent multiply-adds. Built for the
// x86-64 baseline they get no FMA, which fuses each pair into one instruction of half the
// latency. ODOCAL_HOT_LOOP gives such a function a second, x86-64-v3 (AVX2 + FMA) clone; the
// dynamic loader picks one by CPUID at start-up (GCC function multiversioning), so the binary
// still runs on any x86-64. Results of the two clones agree to rounding (~1e-15 relative); the
// CMake option ODOCAL_FUNCTION_CLONES=OFF builds the baseline only. flatten inlines every
// helper into the kernel (a clone does not inline functions compiled for another target unless
// told to).

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(ODOCAL_NO_FUNCTION_CLONES)
#define ODOCAL_HOT_LOOP __attribute__((target_clones("arch=x86-64-v3", "default"), flatten))
#elif defined(__GNUC__)
#define ODOCAL_HOT_LOOP __attribute__((flatten))
#else
#define ODOCAL_HOT_LOOP
#endif
