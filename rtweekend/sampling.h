#pragma once
// Warps from uniform random numbers in [0,1) to the distributions the renderer samples. Each
// takes its uniforms explicitly, so the chi-square tests can drive it and the render loop can
// feed it from any generator.

#include "constants.h"
#include "vec3f.h"

#include <cmath>

namespace rt {

inline constexpr float pi_f = static_cast<float>(pi);

// Uniform on the unit sphere: z uniform on [-1, 1] (Archimedes' hat-box theorem), phi uniform.
inline vec3f sample_unit_sphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float s = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
    float phi = 2.0f * pi_f * u2;
    return {s * std::cos(phi), s * std::sin(phi), z};
}

// Uniform inside the unit ball: a uniform direction scaled by cbrt(u3), since the volume within
// radius r grows as r^3.
inline vec3f sample_unit_ball(float u1, float u2, float u3) { return std::cbrt(u3) * sample_unit_sphere(u1, u2); }

// Uniform on the unit disk (z = 0): radius sqrt(u1) makes the area density constant.
inline vec3f sample_unit_disk(float u1, float u2) {
    float r = std::sqrt(u1);
    float phi = 2.0f * pi_f * u2;
    return {r * std::cos(phi), r * std::sin(phi), 0.0f};
}

// Cosine-weighted direction about the unit normal n: n plus a uniform unit vector, normalised,
// has density cos(theta)/pi (the book's Lambertian construction). The degenerate case where the
// two cancel falls back to n.
inline vec3f sample_cosine_direction(const vec3f& n, float u1, float u2) {
    vec3f d = n + sample_unit_sphere(u1, u2);
    float len2 = length_squared(d);
    if (!(len2 > 1e-12f)) return n;
    return d * (1.0f / std::sqrt(len2));
}

} // namespace rt
