#pragma once
// Packets of doubles for the kernels that weigh every sample (Shepard's weights, the RBF sums)
// and the solver's far field (a block's points, an element's Gauss points): the widest vectors
// the build's -march offers, AVX-512 (8 lanes) or AVX2 with FMA (4 lanes), so
// that one kernel body serves both. RADRECON_SIMD is 0 when the build has neither (the kernels'
// scalar or Eigen forms run instead).
//
// Results depend on the width through the order of sums and on how a kernel pairs packets (one
// division for two, a masked tail): sum() adds the lanes in a fixed order and every operation is
// IEEE-rounded, so a given build gives the same bits on every CPU and with any number of threads.

#if (defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512DQ__) && defined(__AVX512VL__)) || \
    (defined(__AVX2__) && defined(__FMA__))
#define RADRECON_SIMD 1
#include <immintrin.h>

#include <cstdint>
#include <cstring>
#else
#define RADRECON_SIMD 0
#endif

namespace radrecon::simd {

#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512DQ__) && defined(__AVX512VL__)

/// 8 doubles (AVX-512 F, BW, DQ and VL: x86-64-v4).
struct PackD {
  static constexpr int kLanes = 8;
  /// Which lanes take part (a packet's first `count` at the end of an array, visible samples').
  struct Mask {
    __mmask8 bits;
    /// The first `count` lanes, 0 <= count <= kLanes.
    static Mask first(int count) { return {static_cast<__mmask8>((1u << count) - 1u)}; }
    /// The lanes whose byte of flags[0, kLanes) is 0 (all kLanes bytes readable).
    static Mask where_zero(const char* flags) {
      std::uint64_t b;
      std::memcpy(&b, flags, sizeof b);
      return {static_cast<__mmask8>(_mm_cmpeq_epi8_mask(_mm_cvtsi64_si128(static_cast<long long>(b)), _mm_setzero_si128()))};
    }
    friend Mask operator&(Mask a, Mask b) { return {static_cast<__mmask8>(a.bits & b.bits)}; }
  };
  __m512d v;

  static PackD set(double x) { return {_mm512_set1_pd(x)}; }
  static PackD zero() { return {_mm512_setzero_pd()}; }
  static PackD load(const double* p) { return {_mm512_loadu_pd(p)}; }
  void store(double* p) const { _mm512_storeu_pd(p, v); }
  /// The masked lanes from p, the others 0 (nothing read beyond them).
  static PackD load(const double* p, Mask m) { return {_mm512_maskz_loadu_pd(m.bits, p)}; }
  /// The masked lanes of a, the others b.
  static PackD select(Mask m, PackD a, PackD b) { return {_mm512_mask_blend_pd(m.bits, b.v, a.v)}; }

  friend PackD operator+(PackD a, PackD b) { return {_mm512_add_pd(a.v, b.v)}; }
  friend PackD operator-(PackD a, PackD b) { return {_mm512_sub_pd(a.v, b.v)}; }
  friend PackD operator*(PackD a, PackD b) { return {_mm512_mul_pd(a.v, b.v)}; }
  friend PackD operator/(PackD a, PackD b) { return {_mm512_div_pd(a.v, b.v)}; }
  /// a * b + c, one rounding.
  friend PackD fmadd(PackD a, PackD b, PackD c) { return {_mm512_fmadd_pd(a.v, b.v, c.v)}; }
  friend PackD sqrt(PackD a) { return {_mm512_sqrt_pd(a.v)}; }
  /// The lesser (greater) lane by lane; b where either is NaN, as the instructions have it.
  friend PackD min(PackD a, PackD b) { return {_mm512_min_pd(a.v, b.v)}; }
  friend PackD max(PackD a, PackD b) { return {_mm512_max_pd(a.v, b.v)}; }
  friend PackD abs(PackD a) { return {_mm512_abs_pd(a.v)}; }
  friend PackD operator-(PackD a) { return {_mm512_xor_pd(a.v, _mm512_set1_pd(-0.0))}; }
  friend Mask operator>(PackD a, PackD b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OQ)}; }
  friend Mask operator<=(PackD a, PackD b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LE_OQ)}; }
  /// Whether every lane is > 0 (false for a NaN lane).
  bool all_positive() const { return _mm512_cmp_pd_mask(v, _mm512_setzero_pd(), _CMP_GT_OQ) == 0xff; }

  /// The lanes' sum in a fixed order: halves added pairwise, ((0 + 4) + (2 + 6)) + ((1 + 5) + (3 + 7)).
  double sum() const {
    const __m256d h = _mm256_add_pd(_mm512_castpd512_pd256(v), _mm512_extractf64x4_pd(v, 1));
    const __m128d q = _mm_add_pd(_mm256_castpd256_pd128(h), _mm256_extractf128_pd(h, 1));
    return _mm_cvtsd_f64(_mm_add_sd(q, _mm_unpackhi_pd(q, q)));
  }
  /// The least and the largest lane, halves against halves as the AVX2 form does (a NaN lane:
  /// either may be returned; the callers' lanes are finite or infinite).
  double min_lane() const {
    const __m256d h = _mm256_min_pd(_mm512_castpd512_pd256(v), _mm512_extractf64x4_pd(v, 1));
    const __m128d q = _mm_min_pd(_mm256_castpd256_pd128(h), _mm256_extractf128_pd(h, 1));
    return _mm_cvtsd_f64(_mm_min_sd(q, _mm_unpackhi_pd(q, q)));
  }
  double max_lane() const {
    const __m256d h = _mm256_max_pd(_mm512_castpd512_pd256(v), _mm512_extractf64x4_pd(v, 1));
    const __m128d q = _mm_max_pd(_mm256_castpd256_pd128(h), _mm256_extractf128_pd(h, 1));
    return _mm_cvtsd_f64(_mm_max_sd(q, _mm_unpackhi_pd(q, q)));
  }
};

#elif RADRECON_SIMD

/// 4 doubles (AVX2 and FMA).
struct PackD {
  static constexpr int kLanes = 4;
  struct Mask {
    __m256i bits;  // all ones in a lane that takes part
    /// The first `count` lanes, 0 <= count <= kLanes.
    static Mask first(int count) {
      return {_mm256_cmpgt_epi64(_mm256_set1_epi64x(count), _mm256_setr_epi64x(0, 1, 2, 3))};
    }
    /// The lanes whose byte of flags[0, kLanes) is 0 (all kLanes bytes readable).
    static Mask where_zero(const char* flags) {
      std::int32_t b;
      std::memcpy(&b, flags, sizeof b);
      return {_mm256_cmpeq_epi64(_mm256_cvtepi8_epi64(_mm_cvtsi32_si128(b)), _mm256_setzero_si256())};
    }
    friend Mask operator&(Mask a, Mask b) { return {_mm256_and_si256(a.bits, b.bits)}; }
  };
  __m256d v;

  static PackD set(double x) { return {_mm256_set1_pd(x)}; }
  static PackD zero() { return {_mm256_setzero_pd()}; }
  static PackD load(const double* p) { return {_mm256_loadu_pd(p)}; }
  void store(double* p) const { _mm256_storeu_pd(p, v); }
  static PackD load(const double* p, Mask m) { return {_mm256_maskload_pd(p, m.bits)}; }
  static PackD select(Mask m, PackD a, PackD b) { return {_mm256_blendv_pd(b.v, a.v, _mm256_castsi256_pd(m.bits))}; }

  friend PackD operator+(PackD a, PackD b) { return {_mm256_add_pd(a.v, b.v)}; }
  friend PackD operator-(PackD a, PackD b) { return {_mm256_sub_pd(a.v, b.v)}; }
  friend PackD operator*(PackD a, PackD b) { return {_mm256_mul_pd(a.v, b.v)}; }
  friend PackD operator/(PackD a, PackD b) { return {_mm256_div_pd(a.v, b.v)}; }
  friend PackD fmadd(PackD a, PackD b, PackD c) { return {_mm256_fmadd_pd(a.v, b.v, c.v)}; }
  friend PackD sqrt(PackD a) { return {_mm256_sqrt_pd(a.v)}; }
  friend PackD min(PackD a, PackD b) { return {_mm256_min_pd(a.v, b.v)}; }
  friend PackD max(PackD a, PackD b) { return {_mm256_max_pd(a.v, b.v)}; }
  friend PackD abs(PackD a) { return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)}; }
  friend PackD operator-(PackD a) { return {_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0))}; }
  friend Mask operator>(PackD a, PackD b) { return {_mm256_castpd_si256(_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ))}; }
  friend Mask operator<=(PackD a, PackD b) { return {_mm256_castpd_si256(_mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ))}; }
  bool all_positive() const { return _mm256_movemask_pd(_mm256_cmp_pd(v, _mm256_setzero_pd(), _CMP_GT_OQ)) == 0xf; }

  /// The lanes' sum in a fixed order: (0 + 2) + (1 + 3).
  double sum() const {
    const __m128d q = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_add_sd(q, _mm_unpackhi_pd(q, q)));
  }
  double min_lane() const {
    const __m128d q = _mm_min_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_min_sd(q, _mm_unpackhi_pd(q, q)));
  }
  double max_lane() const {
    const __m128d q = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_max_sd(q, _mm_unpackhi_pd(q, q)));
  }
};

#endif

}  // namespace radrecon::simd
