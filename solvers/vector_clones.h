// COONS_VECTOR_CLONES: hot loops get an AVX2 clone next to the baseline one, chosen at load time
// (GCC function multi-versioning), without raising the architecture of the whole build.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define COONS_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define COONS_VECTOR_CLONES
#endif
