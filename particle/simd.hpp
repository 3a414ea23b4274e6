#pragma once
// AVX-512 paths for the pair loops' compactions (the pairs kept, compressed into place). Used
// where the compiler targets AVX-512 (-march=native on a CPU that has it); each has a portable
// twin with bitwise the same results. nearbyint is roundscale in the current rounding mode without
// exceptions, in its maskz form with a full mask: the plain form trips GCC 12's
// maybe-uninitialized warning.
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#define TWINFLOW_AVX512 1
#endif
