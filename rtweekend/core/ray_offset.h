#pragma once
// Where a new ray starts after a hit.
//
// Instead of skipping intersections closer than a fixed epsilon (the book's 0.001), a spawned
// ray starts at the hit point pushed off the surface along the normal, by an amount that scales
// with the point's own magnitude: Wachter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems (2019), ch. 6. Far from the origin the push is a fixed
// number of float ulps; near the origin, where ulps vanish, it is a small absolute distance.

#include "force_inline.h"
#include "vec3f.h"

#include <cstdint>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rt {

namespace detail {
// f with its sign bit flipped where `mask` has it set (mask: 0 or 1u << 31): -f or f, no branch.
inline float flip_sign(float f, uint32_t mask) { return bits_float(float_bits(f) ^ mask); }

// Both pushes are computed and one is kept by a bit mask, not a branch (the compiler makes a
// branch of a ?: here): which one a component takes depends on where the path happens to be, and
// the branch was mispredicted often enough to matter.
RTWEEKEND_FORCE_INLINE float offset_component(float p, float n) {
    constexpr float origin = 1.0f / 32.0f;     // below this magnitude, offset by a distance
    constexpr float float_scale = 1.0f / 65536.0f;
    constexpr float int_scale = 256.0f;        // ulps per unit of normal
    const float by_distance = p + float_scale * n;
    // In unsigned arithmetic, which wraps: the sum is computed for every p, also where it is not
    // kept (-0, whose bits are INT_MIN, pushed by a negative of_i, would overflow an int).
    const uint32_t of_i = static_cast<uint32_t>(static_cast<int32_t>(int_scale * n));
    const uint32_t negative = 0u - static_cast<uint32_t>(p < 0); // all bits set when p < 0
    const uint32_t by_ulps = float_bits(p) + ((of_i ^ negative) - negative); // of_i, negated if p < 0
    const uint32_t near_origin = 0u - static_cast<uint32_t>(std::fabs(p) < origin);
    return bits_float((float_bits(by_distance) & near_origin) | (by_ulps & ~near_origin));
}
} // namespace detail

#if defined(__SSE2__)
namespace detail {
// offset_component's steps on the three axes at once, in SSE lanes (x, y, z, unused): a third of
// the instructions, and no wait for one axis's result before the next. The same bits.
RTWEEKEND_FORCE_INLINE __m128 offset_lanes(__m128 p, __m128 n) {
#if defined(__FMA__)
    const __m128 by_distance = _mm_fmadd_ps(_mm_set1_ps(1.0f / 65536.0f), n, p);
#else
    const __m128 by_distance = _mm_add_ps(p, _mm_mul_ps(_mm_set1_ps(1.0f / 65536.0f), n));
#endif
    const __m128i of_i = _mm_cvttps_epi32(_mm_mul_ps(_mm_set1_ps(256.0f), n));
    const __m128i negative = _mm_castps_si128(_mm_cmplt_ps(p, _mm_setzero_ps()));
    const __m128i by_ulps = _mm_add_epi32(_mm_castps_si128(p), _mm_sub_epi32(_mm_xor_si128(of_i, negative), negative));
    const __m128 near_origin = _mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), p), _mm_set1_ps(1.0f / 32.0f));
    return _mm_or_ps(_mm_and_ps(near_origin, by_distance), _mm_andnot_ps(near_origin, _mm_castsi128_ps(by_ulps)));
}
inline __m128 lanes_of(const vec3f& v) { return _mm_setr_ps(v.x, v.y, v.z, 0.0f); }
inline vec3f vec3f_of(__m128 v) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return {f[0], f[1], f[2]};
}
} // namespace detail
#endif

// The point p moved off the surface along the unit normal n (n points to the side the new ray
// leaves into).
RTWEEKEND_FORCE_INLINE vec3f offset_ray_origin(const vec3f& p, const vec3f& n) {
#if defined(__SSE2__)
    return detail::vec3f_of(detail::offset_lanes(detail::lanes_of(p), detail::lanes_of(n)));
#else
    return {detail::offset_component(p.x, n.x), detail::offset_component(p.y, n.y),
            detail::offset_component(p.z, n.z)};
#endif
}

} // namespace rt
