#pragma once
// The calibration loop's per-sample kernels are chains of dependent multiply-adds. Built for the
// x86-64 baseline they get no FMA, which fuses each pair into one instruction of half the
// latency. ODOCAL_HOT_LOOP gives such a function a second, x86-64-v3 (AVX2 + FMA) clone; the
// dynamic loader picks one by CPUID at start-up (GCC function multiversioning), so the binary
// still runs on any x86-64. Results of the two clones agree to rounding.

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define ODOCAL_HOT_LOOP __attribute__((target_clones("arch=x86-64-v3", "default"), flatten))
#else
#define ODOCAL_HOT_LOOP
#endif
