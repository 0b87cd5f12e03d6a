// COONS_VECTOR_CLONES: hot loops get an AVX2 clone next to the baseline one, chosen at load time
// (GCC function multi-versioning), without raising the architecture of the whole build.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define COONS_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define COONS_VECTOR_CLONES
#endif

// Four doubles as one value (GCC vector extension: two SSE2 registers in the baseline clone, one
// AVX2 register in the other), for kernels that lay out their lanes by hand; moved from and to
// memory with memcpy (any alignment, no aliasing question).
namespace coons::solvers::detail {
using Lanes = double __attribute__((vector_size(32)));
}  // namespace coons::solvers::detail
