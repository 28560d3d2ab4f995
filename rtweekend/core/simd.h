#pragma once
// floatv: a few floats processed by one instruction, for the renderer's inner loops. It maps to
// AVX-512 (16 lanes), AVX (8) or SSE2 (4) when the compiler targets them (-march=native picks the
// widest the machine has) and to plain scalar code elsewhere, with the same source.
//
//   floatv a = floatv::load(ptr), b(2.0f);    a + b, a * b, a / b, sqrt(a), min(a, b)
//   fmadd(a, b, c), fnmadd(a, b, c),          a * b + c, c - a * b and a * b - c, fused where the
//   fmsub(a, b, c)                            machine has FMA (written out, so the result does not
//                                             depend on what the compiler may contract)
//   -a, round_nearest(a)                      the sign flipped; the nearest integer (ties to even)
//   maskv m = a < b;                          select(m, a, b), any(m), m & n, m | n
//   bits(m)                                   one bit per lane, lane 0 in bit 0
//   first_lanes(n)                            the lanes below n (all of them for n >= width)
//   lanes_of(b)                               the lanes whose bits are set in b (bits(m)'s inverse)
//   reduce_min(a)                             the smallest lane
//
// Lane counts are a compile-time property: floatv::width.

#include <cmath>
#include <cstddef>

#if defined(__AVX512F__) || defined(__AVX__)
#include <immintrin.h>
#elif defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define RTWEEKEND_SSE2 1
#endif

namespace rt {

#if defined(__AVX512F__)

struct maskv {
    __mmask16 m;
};
struct floatv {
    static constexpr size_t width = 16;
    __m512 v;
    floatv() = default;
    floatv(__m512 x) : v(x) {}
    floatv(float x) : v(_mm512_set1_ps(x)) {}
    static floatv load(const float* p) { return _mm512_loadu_ps(p); }
    void store(float* p) const { _mm512_storeu_ps(p, v); }
};
inline floatv operator+(floatv a, floatv b) { return _mm512_add_ps(a.v, b.v); }
inline floatv operator-(floatv a, floatv b) { return _mm512_sub_ps(a.v, b.v); }
inline floatv operator*(floatv a, floatv b) { return _mm512_mul_ps(a.v, b.v); }
inline floatv operator/(floatv a, floatv b) { return _mm512_div_ps(a.v, b.v); }
// The maskz forms avoid GCC 12's false -Wmaybe-uninitialized on _mm512_undefined_ps.
inline floatv sqrt(floatv a) { return _mm512_maskz_sqrt_ps(0xFFFF, a.v); }
inline floatv min(floatv a, floatv b) { return _mm512_maskz_min_ps(0xFFFF, a.v, b.v); }
inline floatv max(floatv a, floatv b) { return _mm512_maskz_max_ps(0xFFFF, a.v, b.v); }
inline maskv operator<(floatv a, floatv b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)}; }
inline maskv operator>(floatv a, floatv b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)}; }
inline maskv operator>=(floatv a, floatv b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
inline maskv operator&(maskv a, maskv b) { return {static_cast<__mmask16>(a.m & b.m)}; }
inline maskv operator<=(floatv a, floatv b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
inline maskv operator==(floatv a, floatv b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)}; }
inline maskv operator|(maskv a, maskv b) { return {static_cast<__mmask16>(a.m | b.m)}; }
inline floatv select(maskv m, floatv a, floatv b) { return _mm512_mask_blend_ps(m.m, b.v, a.v); }
inline bool any(maskv m) { return m.m != 0; }
inline unsigned bits(maskv m) { return m.m; }
inline floatv operator-(floatv a) { return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.v), _mm512_set1_epi32(int(0x80000000u)))); }
inline floatv round_nearest(floatv a) { return _mm512_maskz_roundscale_ps(0xFFFF, a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC); }
inline floatv fmadd(floatv a, floatv b, floatv c) { return _mm512_fmadd_ps(a.v, b.v, c.v); }
inline floatv fnmadd(floatv a, floatv b, floatv c) { return _mm512_fnmadd_ps(a.v, b.v, c.v); }
inline floatv fmsub(floatv a, floatv b, floatv c) { return _mm512_fmsub_ps(a.v, b.v, c.v); }
inline maskv first_lanes(unsigned n) { return {static_cast<__mmask16>(n >= 16 ? 0xFFFFu : (1u << n) - 1u)}; }
inline maskv lanes_of(unsigned lane_bits) { return {static_cast<__mmask16>(lane_bits)}; }
inline float reduce_min(floatv a) {
    // Halves folded onto each other, then quarters, pairs and neighbours (the maskz forms, and not
    // _mm512_reduce_min_ps, for the warning above).
    __m512 m = _mm512_maskz_min_ps(0xFFFF, a.v, _mm512_maskz_shuffle_f32x4(0xFFFF, a.v, a.v, 0x4E));
    m = _mm512_maskz_min_ps(0xFFFF, m, _mm512_maskz_shuffle_f32x4(0xFFFF, m, m, 0xB1));
    m = _mm512_maskz_min_ps(0xFFFF, m, _mm512_maskz_permute_ps(0xFFFF, m, 0x4E));
    m = _mm512_maskz_min_ps(0xFFFF, m, _mm512_maskz_permute_ps(0xFFFF, m, 0xB1));
    return _mm512_cvtss_f32(m);
}

#elif defined(__AVX__)

struct maskv {
    __m256 m;
};
struct floatv {
    static constexpr size_t width = 8;
    __m256 v;
    floatv() = default;
    floatv(__m256 x) : v(x) {}
    floatv(float x) : v(_mm256_set1_ps(x)) {}
    static floatv load(const float* p) { return _mm256_loadu_ps(p); }
    void store(float* p) const { _mm256_storeu_ps(p, v); }
};
inline floatv operator+(floatv a, floatv b) { return _mm256_add_ps(a.v, b.v); }
inline floatv operator-(floatv a, floatv b) { return _mm256_sub_ps(a.v, b.v); }
inline floatv operator*(floatv a, floatv b) { return _mm256_mul_ps(a.v, b.v); }
inline floatv operator/(floatv a, floatv b) { return _mm256_div_ps(a.v, b.v); }
inline floatv sqrt(floatv a) { return _mm256_sqrt_ps(a.v); }
inline floatv min(floatv a, floatv b) { return _mm256_min_ps(a.v, b.v); }
inline floatv max(floatv a, floatv b) { return _mm256_max_ps(a.v, b.v); }
inline maskv operator<(floatv a, floatv b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
inline maskv operator>(floatv a, floatv b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
inline maskv operator>=(floatv a, floatv b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
inline maskv operator&(maskv a, maskv b) { return {_mm256_and_ps(a.m, b.m)}; }
inline maskv operator<=(floatv a, floatv b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
inline maskv operator==(floatv a, floatv b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
inline maskv operator|(maskv a, maskv b) { return {_mm256_or_ps(a.m, b.m)}; }
inline floatv select(maskv m, floatv a, floatv b) { return _mm256_blendv_ps(b.v, a.v, m.m); }
inline bool any(maskv m) { return _mm256_movemask_ps(m.m) != 0; }
inline unsigned bits(maskv m) { return static_cast<unsigned>(_mm256_movemask_ps(m.m)); }
inline floatv operator-(floatv a) { return _mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f)); }
inline floatv round_nearest(floatv a) { return _mm256_round_ps(a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC); }
#if defined(__FMA__)
inline floatv fmadd(floatv a, floatv b, floatv c) { return _mm256_fmadd_ps(a.v, b.v, c.v); }
inline floatv fnmadd(floatv a, floatv b, floatv c) { return _mm256_fnmadd_ps(a.v, b.v, c.v); }
inline floatv fmsub(floatv a, floatv b, floatv c) { return _mm256_fmsub_ps(a.v, b.v, c.v); }
#else
inline floatv fmadd(floatv a, floatv b, floatv c) { return _mm256_add_ps(_mm256_mul_ps(a.v, b.v), c.v); }
inline floatv fnmadd(floatv a, floatv b, floatv c) { return _mm256_sub_ps(c.v, _mm256_mul_ps(a.v, b.v)); }
inline floatv fmsub(floatv a, floatv b, floatv c) { return _mm256_sub_ps(_mm256_mul_ps(a.v, b.v), c.v); }
#endif
inline maskv lanes_of(unsigned lane_bits) {
    const __m256i lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return {_mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(lane_bits)), lane), lane))};
}
inline maskv first_lanes(unsigned n) {
    return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(int(n < 8 ? n : 8)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)))};
}
inline float reduce_min(floatv a) {
    __m128 m = _mm_min_ps(_mm256_castps256_ps128(a.v), _mm256_extractf128_ps(a.v, 1));
    m = _mm_min_ps(m, _mm_movehl_ps(m, m));
    m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
    return _mm_cvtss_f32(m);
}

#elif defined(RTWEEKEND_SSE2)

struct maskv {
    __m128 m;
};
struct floatv {
    static constexpr size_t width = 4;
    __m128 v;
    floatv() = default;
    floatv(__m128 x) : v(x) {}
    floatv(float x) : v(_mm_set1_ps(x)) {}
    static floatv load(const float* p) { return _mm_loadu_ps(p); }
    void store(float* p) const { _mm_storeu_ps(p, v); }
};
inline floatv operator+(floatv a, floatv b) { return _mm_add_ps(a.v, b.v); }
inline floatv operator-(floatv a, floatv b) { return _mm_sub_ps(a.v, b.v); }
inline floatv operator*(floatv a, floatv b) { return _mm_mul_ps(a.v, b.v); }
inline floatv operator/(floatv a, floatv b) { return _mm_div_ps(a.v, b.v); }
inline floatv sqrt(floatv a) { return _mm_sqrt_ps(a.v); }
inline floatv min(floatv a, floatv b) { return _mm_min_ps(a.v, b.v); }
inline floatv max(floatv a, floatv b) { return _mm_max_ps(a.v, b.v); }
inline maskv operator<(floatv a, floatv b) { return {_mm_cmplt_ps(a.v, b.v)}; }
inline maskv operator>(floatv a, floatv b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline maskv operator>=(floatv a, floatv b) { return {_mm_cmpge_ps(a.v, b.v)}; }
inline maskv operator&(maskv a, maskv b) { return {_mm_and_ps(a.m, b.m)}; }
inline maskv operator<=(floatv a, floatv b) { return {_mm_cmple_ps(a.v, b.v)}; }
inline maskv operator==(floatv a, floatv b) { return {_mm_cmpeq_ps(a.v, b.v)}; }
inline maskv operator|(maskv a, maskv b) { return {_mm_or_ps(a.m, b.m)}; }
inline floatv select(maskv m, floatv a, floatv b) { return _mm_or_ps(_mm_and_ps(m.m, a.v), _mm_andnot_ps(m.m, b.v)); }
inline bool any(maskv m) { return _mm_movemask_ps(m.m) != 0; }
inline unsigned bits(maskv m) { return static_cast<unsigned>(_mm_movemask_ps(m.m)); }
inline floatv operator-(floatv a) { return _mm_xor_ps(a.v, _mm_set1_ps(-0.0f)); }
inline floatv round_nearest(floatv a) { // SSE2 has no rounding instruction: lane by lane
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, a.v);
    for (float& x : lanes) x = std::nearbyint(x);
    return _mm_load_ps(lanes);
}
inline floatv fmadd(floatv a, floatv b, floatv c) { return _mm_add_ps(_mm_mul_ps(a.v, b.v), c.v); }
inline floatv fnmadd(floatv a, floatv b, floatv c) { return _mm_sub_ps(c.v, _mm_mul_ps(a.v, b.v)); }
inline floatv fmsub(floatv a, floatv b, floatv c) { return _mm_sub_ps(_mm_mul_ps(a.v, b.v), c.v); }
inline maskv first_lanes(unsigned n) {
    return {_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_set1_epi32(int(n < 4 ? n : 4)), _mm_setr_epi32(0, 1, 2, 3)))};
}
inline maskv lanes_of(unsigned lane_bits) {
    const __m128i lane = _mm_setr_epi32(1, 2, 4, 8);
    return {_mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(int(lane_bits)), lane), lane))};
}
inline float reduce_min(floatv a) {
    __m128 m = _mm_min_ps(a.v, _mm_movehl_ps(a.v, a.v));
    m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
    return _mm_cvtss_f32(m);
}

#else

struct maskv {
    bool m;
};
struct floatv {
    static constexpr size_t width = 1;
    float v;
    floatv() = default;
    floatv(float x) : v(x) {}
    static floatv load(const float* p) { return *p; }
    void store(float* p) const { *p = v; }
};
inline floatv operator+(floatv a, floatv b) { return a.v + b.v; }
inline floatv operator-(floatv a, floatv b) { return a.v - b.v; }
inline floatv operator*(floatv a, floatv b) { return a.v * b.v; }
inline floatv operator/(floatv a, floatv b) { return a.v / b.v; }
inline floatv sqrt(floatv a) { return std::sqrt(a.v); }
inline floatv min(floatv a, floatv b) { return a.v < b.v ? a.v : b.v; }
inline floatv max(floatv a, floatv b) { return a.v > b.v ? a.v : b.v; }
inline maskv operator<(floatv a, floatv b) { return {a.v < b.v}; }
inline maskv operator>(floatv a, floatv b) { return {a.v > b.v}; }
inline maskv operator>=(floatv a, floatv b) { return {a.v >= b.v}; }
inline maskv operator&(maskv a, maskv b) { return {a.m && b.m}; }
inline maskv operator<=(floatv a, floatv b) { return {a.v <= b.v}; }
inline maskv operator==(floatv a, floatv b) { return {a.v == b.v}; }
inline maskv operator|(maskv a, maskv b) { return {a.m || b.m}; }
inline floatv select(maskv m, floatv a, floatv b) { return m.m ? a : b; }
inline bool any(maskv m) { return m.m; }
inline unsigned bits(maskv m) { return m.m ? 1u : 0u; }
inline floatv operator-(floatv a) { return -a.v; }
inline floatv round_nearest(floatv a) { return std::nearbyint(a.v); }
inline floatv fmadd(floatv a, floatv b, floatv c) { return std::fma(a.v, b.v, c.v); }
inline floatv fnmadd(floatv a, floatv b, floatv c) { return std::fma(-a.v, b.v, c.v); }
inline floatv fmsub(floatv a, floatv b, floatv c) { return std::fma(a.v, b.v, -c.v); }
inline maskv first_lanes(unsigned n) { return {n > 0}; }
inline maskv lanes_of(unsigned lane_bits) { return {(lane_bits & 1u) != 0}; }
inline float reduce_min(floatv a) { return a.v; }

#endif

// x, with the compiler forbidden to fuse the operation that produced it into a later one. GCC
// and Clang contract a * b - c * d into fma(a, b, -(c * d)) when they may (GNU mode does by
// default); that rounds the two products differently, so the same difference computed with
// its terms swapped is no longer exactly the negation. The watertight triangle test depends on
// exactly that symmetry (triangle.h).
template <class T>
inline T rounded(T x) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    __asm__("" : "+v"(x));
#elif defined(__GNUC__)
    __asm__("" : "+w"(x));
#endif
    return x;
}
inline floatv rounded(floatv x) { return floatv(rounded(x.v)); }

} // namespace rt
