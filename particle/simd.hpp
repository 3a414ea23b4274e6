#pragma once
// AVX-512 paths for the pair loops' compactions (the pairs kept, compressed into place). Used
// where the compiler targets AVX-512 (-march=native on a CPU that has it); each has a portable
// twin with bitwise the same results.
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#define TWINFLOW_AVX512 1

namespace twinflow::particle {
// Minimum image of eight separations, r - box nearbyint(r / box) with the multiply by inv_box, as
// the portable loops compute it (bitwise). nearbyint is roundscale in the current rounding mode
// without exceptions, in its maskz form with a full mask: the plain form trips GCC 12's
// maybe-uninitialized warning.
inline __m512d minimum_image(__m512d r, double box, double inv_box) {
  const __m512d image = _mm512_maskz_roundscale_pd(0xFF, _mm512_mul_pd(r, _mm512_set1_pd(inv_box)),
                                                   _MM_FROUND_CUR_DIRECTION | _MM_FROUND_NO_EXC);
  return _mm512_sub_pd(r, _mm512_mul_pd(_mm512_set1_pd(box), image));
}
} // namespace twinflow::particle
#endif
