#pragma once
// SUITE_VECTOR_CLONES before a function definition compiles it twice on x86-64, for the baseline
// instruction set (SSE2) and for AVX2, and the program picks the one the CPU can run when it is
// loaded (GCC's target_clones): one binary runs on a cluster's oldest nodes and uses the 4-wide
// registers of the newer ones for the transfers' row kernels (transfer/stencil_rows.hpp). AVX2
// is asked for without FMA, so both clones perform the same operations with the same rounding and
// give bit-identical results: a job requeued onto another node type restarts bit for bit.
// `flatten` inlines the kernels the function calls into each clone. Elsewhere (other compilers
// or processors), or built with -DSUITE_NO_VECTOR_CLONES (to compare the two), the macro is empty.
//
// SUITE_INLINE_CALLS before a function definition inlines every call it makes (`flatten`), with
// no clones: for loops compiled for the baseline only. Eigen sums a small vector in another
// order with AVX2 than with SSE2, so code full of such sums (the return mapping) stays out of the
// clones, where the two would round differently.
#if defined(__GNUC__)
#define SUITE_INLINE_CALLS __attribute__((flatten))
#else
#define SUITE_INLINE_CALLS
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(SUITE_NO_VECTOR_CLONES)
#define SUITE_VECTOR_CLONES __attribute__((target_clones("avx2", "default"), flatten))
#else
#define SUITE_VECTOR_CLONES
#endif
