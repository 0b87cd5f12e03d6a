// COONS_VECTOR_CLONES: hot loops get an AVX2 clone next to the baseline one, chosen at load time
// (GCC function multi-versioning), without raising the architecture of the whole build.
#pragma once

// COONS_WIDE_CLONES adds an AVX-512 clone, for loops bound by their arithmetic (the products with
// the capacitance blocks' G); the sweeps' loops, bound by memory, were slower with it. The library
// is built with -ffp-contract=off, so that no clone fuses a multiply and an add the others do not
// (AVX-512F has FMA, the AVX2 target does not): every clone gives the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define COONS_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#define COONS_WIDE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define COONS_VECTOR_CLONES
#define COONS_WIDE_CLONES
#endif

// Four doubles as one value (GCC vector extension: two SSE2 registers in the baseline clone, one
// AVX2 register in the other), for kernels that lay out their lanes by hand; moved from and to
// memory with memcpy (any alignment, no aliasing question).
namespace coons::solvers::detail {
using Lanes = double __attribute__((vector_size(32)));
//! Eight doubles as one value (one AVX-512 register, two AVX2 ones, four SSE2 ones).
using Lanes8 = double __attribute__((vector_size(64)));
}  // namespace coons::solvers::detail
