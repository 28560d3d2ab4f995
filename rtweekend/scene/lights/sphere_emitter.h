#pragma once
// sphere_emitter: a light kind (scene/light_kinds.h): an emitting sphere, sampled by the cone of
// directions it subtends (scene/light_sampling.h).

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"
#include "area_emitter.h"

#include <cmath>

namespace rt {

struct sphere_emitter {
    vec3f centre; // relative to the scene origin
    float radius = 0;

    static constexpr bool is_delta = false;
    float area() const { return 4.0f * pi_f * radius * radius; }
    // The same in double, for powers beyond float's range (light::power).
    double area_in_double() const { return 4.0 * 3.14159265358979323846 * double(radius) * double(radius); }

    bool sample(const vec3f& p, float u1, float u2, light_sample& s) const {
        return sample_sphere_light(p, centre, radius, u1, u2, s);
    }
    float pdf(const vec3f& p, const vec3f& y, const vec3f& ny) const { return sphere_light_pdf(p, centre, radius, y, ny); }

    // Where the half-line p + t wi (t > 0) first meets the sphere: the near root of
    // |p + t wi - c|^2 = r^2 that is positive (the far one from inside).
    bool meet(const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny) const {
        const vec3f oc = centre - p;
        const float h = dot(wi, oc);
        const vec3f perp = oc - h * wi;
        const float disc = radius * radius - length_squared(perp);
        if (!(disc >= 0)) return false;
        const float s = sqrt_f(disc);
        float t = h - s;
        if (!(t > 0)) t = h + s;
        if (!(t > 0)) return false;
        y = p + t * wi;
        ny = normalize(y - centre);
        return true;
    }

    // A light path from a uniform point of the sphere (u's first pair), leaving by its cosine.
    template <class Uniform>
    void start_path(const vec3f& emission, bool two_sided, float /*pmf*/, float density, const box3f& /*aim*/, Uniform& u,
                    ray3f& r, vec3f& throughput) const {
        const auto [u1, u2] = draw_2d(u);
        const vec3f n = sample_unit_sphere(u1, u2);
        detail::start_area_path(centre + radius * n, n, emission, two_sided, density, u, r, throughput);
    }
};

} // namespace rt
