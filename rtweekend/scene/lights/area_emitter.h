#pragma once
// What the emitters of area (sphere_emitter, quad_emitter, triangle_emitter) share: where a light
// path starts on them (caustic paths, render/caustic_paths.h), where a line meets a flat one, and
// their areas in double.

#include "../../core/constants.h"
#include "../../core/ray_offset.h"
#include "../../core/rng.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"

#include <cmath>

namespace rt::detail {

// A light path leaving the point y (outward unit normal n) of an area emitter of radiance
// `emission`, chosen with area density `density` (per path, the light's choice included): a
// two-sided light picks a side (u's next number), the direction is cosine-distributed about that
// side's normal (u's next pair), and the path carries Le cos / (density cos / pi).
template <class Uniform>
void start_area_path(const vec3f& y, vec3f n, const vec3f& emission, bool two_sided, float density, Uniform& u,
                     ray3f& r, vec3f& throughput) {
    if (two_sided && u.next_float() < 0.5f) n = -n;
    const auto [v1, v2] = draw_2d(u);
    r.dir = sample_cosine_direction(n, v1, v2);
    r.origin = offset_ray_origin(y, n);
    throughput = emission * (pi_f / density);
}

// |a x b| in double, of float vectors' coordinates.
inline double cross_length(double ax, double ay, double az, double bx, double by, double bz) {
    const double x = ay * bz - az * by, y = az * bx - ax * bz, z = ax * by - ay * bx;
    return std::sqrt(x * x + y * y + z * z);
}

// Where the half-line p + t wi (t > 0) meets the plane through q spanned by e1 and e2: the point
// y, the plane's unit normal ny (e1 x e2 normalised) and y's coordinates (a, b) in the frame
// q + a e1 + b e2. False when the line is parallel to the plane or meets it behind p.
inline bool meet_plane(const vec3f& p, const vec3f& wi, const vec3f& q, const vec3f& e1, const vec3f& e2, vec3f& y,
                       vec3f& ny, float& a, float& b) {
    const vec3f n = cross(e1, e2);
    const float denom = dot(n, wi);
    if (denom == 0) return false;
    const float t = dot(n, q - p) / denom;
    if (!(t > 0)) return false;
    const vec3f rel = p + t * wi - q;
    const vec3f w = n / dot(n, n);
    a = dot(w, cross(rel, e2));
    b = dot(w, cross(e1, rel));
    y = p + t * wi;
    ny = normalize(n);
    return true;
}

} // namespace rt::detail
