#pragma once
// Which Highway targets the batch kernels are compiled for. Included before hwy/foreach_target.h
// by every kernel translation unit. SSSE3 / SSE4 are left out: they would double the compile
// time for CPUs that bezinv does not target (every x86-64 machine since 2013 has AVX2). The
// portable baseline (HWY_BASELINE_SCALAR: HWY_SCALAR, one lane of plain C++, with GCC 12 where
// Highway 1.0.3 marks EMU128 broken; EMU128 elsewhere) is the "scalar" reference implementation.
// HWY_COMPILE_ALL_ATTAINABLE: Highway's default policy drops the portable target when the
// baseline already has SIMD, but "scalar" must exist for BEZINV_KERNEL=scalar.
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
// BEZINV_KERNEL_ONLY_TARGET (CMake: BEZINV_KERNEL_TARGETS=native, the trees of scripts/test.sh):
// the portable baseline and these Highway target bits alone (those this machine runs; 0: the
// baseline alone), so a tree that is only tested on the machine that builds it compiles no kernel
// it cannot run (on an AVX2 machine, twice instead of four times).
#ifndef HWY_DISABLED_TARGETS
#ifdef BEZINV_KERNEL_ONLY_TARGET
#define HWY_DISABLED_TARGETS \
  (HWY_SSSE3 | HWY_SSE4 | ((HWY_AVX2 | HWY_AVX3 | HWY_AVX3_DL) & ~(BEZINV_KERNEL_ONLY_TARGET)))
#else
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4)
#endif
#endif
