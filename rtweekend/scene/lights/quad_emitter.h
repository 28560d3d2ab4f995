#pragma once
// quad_emitter: a light kind (scene/light_kinds.h): an emitting parallelogram (book 2's quad,
// corner Q and edges u, v), sampled by solid angle where it looks large and by area elsewhere
// (scene/light_sampling.h).

#include "../../core/box3f.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"
#include "area_emitter.h"

#include <cmath>

namespace rt {

struct quad_emitter {
    vec3f corner; // relative to the scene origin
    vec3f u, v;   // the edges; the front face is the side u x v points to

    static constexpr bool is_delta = false;
    float area() const { return length(cross(u, v)); }
    double area_in_double() const {
        return detail::cross_length(u.x, u.y, u.z, v.x, v.y, v.z);
    }

    bool sample(const vec3f& p, float u1, float u2, light_sample& s) const {
        return sample_quad_light(p, corner, u, v, u1, u2, s);
    }
    float pdf(const vec3f& p, const vec3f& y, const vec3f& ny) const { return quad_light_pdf(p, corner, u, v, y, ny); }

    // Where the half-line p + t wi (t > 0) meets the quad.
    bool meet(const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny) const {
        float a, b;
        if (!detail::meet_plane(p, wi, corner, u, v, y, ny, a, b)) return false;
        return a >= 0 && a <= 1 && b >= 0 && b <= 1;
    }

    // A light path from a uniform point of the quad (u's first pair), leaving by its cosine.
    template <class Uniform>
    void start_path(const vec3f& emission, bool two_sided, float /*pmf*/, float density, const box3f& /*aim*/, Uniform& rng,
                    ray3f& r, vec3f& throughput) const {
        const auto [u1, u2] = draw_2d(rng);
        detail::start_area_path(corner + u1 * u + u2 * v, normalize(cross(u, v)), emission, two_sided, density, rng, r,
                                throughput);
    }
};

} // namespace rt
