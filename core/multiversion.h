// SPALLKIT_MULTIVERSION: function multi-versioning for a hot loop in a portable build. The
// function is compiled for x86-64-v4 (AVX-512), x86-64-v3 (AVX2, FMA) and the baseline, with
// everything it calls inlined into each version (flatten), and the loader picks the version for
// the running CPU once (GNU ifunc). Empty where that is not available (other compilers or
// platforms) or not needed (a baseline that already has AVX-512, e.g. -march=native there).
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(__AVX512F__)
#define SPALLKIT_MULTIVERSION \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"), flatten))
#else
#define SPALLKIT_MULTIVERSION
#endif
