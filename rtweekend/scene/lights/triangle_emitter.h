#pragma once
// triangle_emitter: a light kind (scene/light_kinds.h): an emitting triangle (of a mesh, or a
// single one), sampled uniformly by area (scene/light_sampling.h).

#include "../../core/box3f.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"
#include "area_emitter.h"

#include <cmath>

namespace rt {

struct triangle_emitter {
    vec3f a, b, c; // relative to the scene origin; the front face is the side (b - a) x (c - a) points to

    static constexpr bool is_delta = false;
    float area() const { return 0.5f * length(cross(b - a, c - a)); }
    double area_in_double() const {
        return 0.5 * detail::cross_length(double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z, double(c.x) - a.x,
                                          double(c.y) - a.y, double(c.z) - a.z);
    }

    bool sample(const vec3f& p, float u1, float u2, light_sample& s) const {
        return sample_triangle_light(p, a, b, c, u1, u2, s);
    }
    float pdf(const vec3f& p, const vec3f& y, const vec3f& ny) const { return triangle_light_pdf(p, a, b, c, y, ny); }

    // Where the half-line p + t wi (t > 0) meets the triangle.
    bool meet(const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny) const {
        float s, t;
        if (!detail::meet_plane(p, wi, a, b - a, c - a, y, ny, s, t)) return false;
        return s >= 0 && t >= 0 && s + t <= 1;
    }

    // A light path from a uniform point of the triangle (u's first pair), leaving by its cosine.
    template <class Uniform>
    void start_path(const vec3f& emission, bool two_sided, float /*pmf*/, float density, const box3f& /*aim*/, Uniform& u,
                    ray3f& r, vec3f& throughput) const {
        const auto [u1, u2] = draw_2d(u);
        const barycentric w = uniform_triangle_point(u1, u2);
        detail::start_area_path(w.b0 * a + w.b1 * b + w.b2 * c, normalize(cross(b - a, c - a)), emission, two_sided,
                                density, u, r, throughput);
    }
};

} // namespace rt
