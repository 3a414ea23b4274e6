#pragma once
// Vector paths for the pair loops' compactions (the pairs kept, compressed into place): eight
// wide where the compiler targets AVX-512, four wide where it targets AVX2 (the x86-64-v4 and -v3
// levels of the build's dispatch, or -march=native). Each has a portable twin with bitwise the
// same results.
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

#elif defined(__AVX2__)
#include <immintrin.h>

#include <cstdint>
#define TWINFLOW_AVX2 1

namespace twinflow::particle {
// Four separations' minimum image, as above (round in the current mode without exceptions is
// nearbyint).
inline __m256d minimum_image(__m256d r, double box, double inv_box) {
  const __m256d image = _mm256_round_pd(_mm256_mul_pd(r, _mm256_set1_pd(inv_box)),
                                        _MM_FROUND_CUR_DIRECTION | _MM_FROUND_NO_EXC);
  return _mm256_sub_pd(r, _mm256_mul_pd(_mm256_set1_pd(box), image));
}

// AVX2 has no compress: a permutation per 4-bit keep mask moves the kept lanes to the front in
// order (the lanes after them are don't-care; the callers store all four and advance by the
// count). Entry k of kCompress4 lists, for each output 32-bit lane, its input lane; a double is
// two 32-bit lanes.
struct Compress4 {
  std::int32_t lanes[16][4];   // one 32-bit lane per element
  std::int32_t doubles[16][8]; // two 32-bit lanes per element
  constexpr Compress4() : lanes(), doubles() {
    for (int mask = 0; mask < 16; ++mask) {
      int out = 0;
      for (int k = 0; k < 4; ++k)
        if (mask >> k & 1) {
          lanes[mask][out] = k;
          doubles[mask][2 * out] = 2 * k;
          doubles[mask][2 * out + 1] = 2 * k + 1;
          ++out;
        }
      for (; out < 4; ++out)
        lanes[mask][out] = 0, doubles[mask][2 * out] = 0, doubles[mask][2 * out + 1] = 1;
    }
  }
};
inline constexpr Compress4 kCompress4{};

// x[index[0..3]]: four scalar loads, not the hardware gather (on Zen 3 the whole cutoff pass
// took 8.0 ns per pair with vgatherdpd, 4.6 with loads, 11 portable: docs/performance.md).
inline __m256d gather(const double* x, const std::uint32_t* index) {
  const __m128d low = _mm_loadh_pd(_mm_load_sd(x + index[0]), x + index[1]);
  const __m128d high = _mm_loadh_pd(_mm_load_sd(x + index[2]), x + index[3]);
  return _mm256_set_m128d(high, low);
}

inline __m256d compress(__m256d v, int keep) {
  const __m256i order =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kCompress4.doubles[keep]));
  return _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(v), order));
}
inline __m128i compress(__m128i v, int keep) {
  const __m128i order = _mm_loadu_si128(reinterpret_cast<const __m128i*>(kCompress4.lanes[keep]));
  return _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(v), order));
}

} // namespace twinflow::particle
#endif
