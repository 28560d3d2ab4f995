#pragma once
// Where a new ray starts after a hit.
//
// Instead of skipping intersections closer than a fixed epsilon (the book's 0.001), a spawned
// ray starts at the hit point pushed off the surface along the normal, by an amount that scales
// with the point's own magnitude: Wachter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems (2019), ch. 6. Far from the origin the push is a fixed
// number of float ulps; near the origin, where ulps vanish, it is a small absolute distance.

#include "vec3f.h"

#include <cstdint>
#include <cstring>

namespace rt {

namespace detail {
inline int32_t float_as_int(float f) { int32_t i; std::memcpy(&i, &f, sizeof i); return i; }
inline float int_as_float(int32_t i) { float f; std::memcpy(&f, &i, sizeof f); return f; }

inline float offset_component(float p, float n) {
    constexpr float origin = 1.0f / 32.0f;     // below this magnitude, offset by a distance
    constexpr float float_scale = 1.0f / 65536.0f;
    constexpr float int_scale = 256.0f;        // ulps per unit of normal
    if (std::fabs(p) < origin) return p + float_scale * n;
    auto of_i = static_cast<int32_t>(int_scale * n);
    return int_as_float(float_as_int(p) + (p < 0 ? -of_i : of_i));
}
} // namespace detail

// The point p moved off the surface along the unit normal n (n points to the side the new ray
// leaves into).
inline vec3f offset_ray_origin(const vec3f& p, const vec3f& n) {
    return {detail::offset_component(p.x, n.x), detail::offset_component(p.y, n.y),
            detail::offset_component(p.z, n.z)};
}

} // namespace rt
