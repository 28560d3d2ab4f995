#pragma once
// Warps from uniform random numbers in [0,1) to the distributions the renderer samples. Each
// takes its uniforms explicitly, so the chi-square tests can drive it and the render loop can
// feed it from any generator.

#include "constants.h"
#include "force_inline.h"
#include "vec3f.h"

#include <cmath>
#include <cstdint>

namespace rt {

inline constexpr float pi_f = static_cast<float>(pi);

// (cos 2 pi u, sin 2 pi u) for u in [0, 1): a point of the unit circle at the fraction u of a
// turn. Renders draw one per bounce, and libm's sincosf is a function call of some 40 cycles;
// this reduces to an eighth of a turn and evaluates the Taylor polynomials there (degree 9 and
// 8: truncation error below 3e-8, under float's own rounding), then rotates by quarter turns.
RTWEEKEND_FORCE_INLINE vec3f unit_circle(float u) {
    float quarter = std::nearbyint(4.0f * u);   // nearest quarter turn: 0..4
    float x = (u - 0.25f * quarter) * (2.0f * pi_f); // |x| <= pi / 4
    float x2 = x * x;
    float s = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    float c = 1.0f + x2 * (-1.0f / 2 + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
    // Rotated by q quarter turns: (c, s), (-s, c), (-c, -s), (s, -c) for q = 0, 1, 2, 3. A switch
    // on q, which is random, was a mispredicted branch three times in four; bit masks instead
    // swap the two for odd q and flip the signs (x for q = 1, 2; y for q = 2, 3).
    const uint32_t q = static_cast<uint32_t>(quarter) & 3u;
    const uint32_t swap = 0u - (q & 1u); // all bits set for odd q
    const uint32_t cb = float_bits(c), sb = float_bits(s);
    const uint32_t xb = ((cb & ~swap) | (sb & swap)) ^ ((((q + 1u) >> 1) & 1u) << 31);
    const uint32_t yb = ((sb & ~swap) | (cb & swap)) ^ (((q >> 1) & 1u) << 31);
    return {bits_float(xb), bits_float(yb), 0};
}

// Uniform on the unit sphere: z uniform on [-1, 1] (Archimedes' hat-box theorem), phi uniform.
RTWEEKEND_FORCE_INLINE vec3f sample_unit_sphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float s = sqrt_f(fmax_inline(0.0f, 1.0f - z * z));
    vec3f circle = unit_circle(u2);
    return {s * circle.x, s * circle.y, z};
}

// Uniform inside the unit ball: a uniform direction scaled by cbrt(u3), since the volume within
// radius r grows as r^3.
inline vec3f sample_unit_ball(float u1, float u2, float u3) { return std::cbrt(u3) * sample_unit_sphere(u1, u2); }

// Uniform on the unit disk (z = 0): radius sqrt(u1) makes the area density constant.
inline vec3f sample_unit_disk(float u1, float u2) {
    float r = sqrt_f(u1);
    vec3f circle = unit_circle(u2);
    return {r * circle.x, r * circle.y, 0.0f};
}

// An orthonormal basis (e1, e2) across the unit vector w, without a branch on w's direction:
// Duff, Burgess, Christensen, Hery, Kensler, Liani and Villemin, "Building an Orthonormal Basis,
// Revisited", JCGT 6(1), 2017. (e1, e2, w) is right-handed.
RTWEEKEND_FORCE_INLINE void frame_across(const vec3f& w, vec3f& e1, vec3f& e2) {
    const float sign = std::copysign(1.0f, w.z);
    const float a = -1.0f / (sign + w.z);
    const float b = w.x * w.y * a;
    e1 = {1.0f + sign * w.x * w.x * a, sign * b, -sign * w.x};
    e2 = {b, sign + w.y * w.y * a, -w.y};
}

// Cosine-weighted direction about the unit normal n (density cos(theta)/pi): a uniform point of
// the unit disk across n lifted onto the hemisphere (Malley's method; pbrt, 4th ed., 13.6.3).
// The disk point's radius sqrt(u1) and the height sqrt(1 - u1) come from u1 directly and the
// frame from n alone, so the one square root on the path from the numbers to the direction does
// not wait on another. The book's construction (n plus a uniform point of the unit sphere,
// normalised) has the same density, with three long steps in a row: a root for the sphere point,
// then the root and the division of the normalisation; a path took one per diffuse bounce.
RTWEEKEND_FORCE_INLINE vec3f sample_cosine_direction(const vec3f& n, float u1, float u2) {
    const float r = sqrt_f(u1), height = sqrt_f(fmax_inline(0.0f, 1.0f - u1));
    const vec3f circle = unit_circle(u2);
    vec3f e1, e2;
    frame_across(n, e1, e2);
    return (r * circle.x) * e1 + (r * circle.y) * e2 + height * n;
}

// A direction uniform on the hemisphere about the unit normal n (density 1 / (2 pi)): cos theta
// = u1, the azimuth from u2.
RTWEEKEND_FORCE_INLINE vec3f sample_uniform_hemisphere(const vec3f& n, float u1, float u2) {
    const float radius = sqrt_f(fmax_inline(0.0f, 1.0f - u1 * u1));
    vec3f e1, e2;
    frame_across(n, e1, e2);
    const vec3f circle = unit_circle(u2);
    return normalize((radius * circle.x) * e1 + (radius * circle.y) * e2 + u1 * n);
}

// A direction about the unit axis a with the density of a Phong lobe, (p + 1) / (2 pi) cos^p of
// the angle to a over the sphere: cos = u1^(1 / (p + 1)), the azimuth from u2. Unit up to rounding
// (not renormalised). The Blinn-Phong half vector and the course's Phong lobe draw from it.
RTWEEKEND_FORCE_INLINE vec3f sample_cosine_power(const vec3f& a, float exponent, float u1, float u2) {
    const float c = std::pow(u1, 1.0f / (exponent + 1.0f));
    const float s = std::sqrt(fmax_inline(0.0f, 1.0f - c * c));
    vec3f e1, e2;
    frame_across(a, e1, e2);
    const vec3f circle = unit_circle(u2);
    return (s * circle.x) * e1 + (s * circle.y) * e2 + c * a;
}

} // namespace rt
