#pragma once
// hidden_square_emitter: a light kind (scene/light_kinds.h): a parallelogram that emits radiance
// Le from both faces but is no surface: no ray hits it, so only light sampling finds it, as a
// point light (CENG795's <AreaLight>, course/course_lights.h: "two-sided, invisible"). A point y
// uniform over its area A reaches p with the irradiance Le A |n . wi| / |y - p|^2 (the course's
// E), so it is a delta light to the path tracer's multiple importance sampling (no material
// sample can find it) with an area to sample.
//
//   add_hidden_square_light(compiled, centre, edge_u, edge_v, radiance);   // scene_compiler.h

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"
#include "area_emitter.h"

#include <cmath>

namespace rt {

struct hidden_square_emitter {
    vec3f centre;         // relative to the scene origin
    vec3f edge_u, edge_v; // its sides
    vec3f normal;         // unit, edge_u x edge_v normalised
    float area_ = 0;

    static constexpr bool is_delta = true; // no direction finds it
    float area() const { return 0; }       // as a delta light: its light paths' density is not an area's
    double area_in_double() const { return 0; }
    // The power of radiance Le (Le averaged over channels; light::power): Le pi A from each face.
    float power(float mean) const { return 2.0f * pi_f * area_ * mean; }
    double power_in_double(double mean) const { return 2.0 * 3.14159265358979323846 * double(area_) * mean; }
    // What Le is multiplied by at p for the sampled point y: A |n . wi| / |y - p|^2.
    float arriving(const vec3f& p, const light_sample& s) const {
        return area_ * std::fabs(dot(normal, s.wi)) / length_squared(s.y - p);
    }

    // A uniform point of the parallelogram; pdf 1 (light_choice::delta).
    bool sample(const vec3f& p, float u1, float u2, light_sample& s) const {
        s.y = centre + (u1 - 0.5f) * edge_u + (u2 - 0.5f) * edge_v;
        const vec3f to = s.y - p;
        const float d2 = length_squared(to);
        if (!(d2 > 0)) return false;
        s.distance = sqrt_f(d2);
        s.wi = to / s.distance;
        s.n = {0, 0, 0}; // the shadow ray ends at y itself: there is no surface to step off
        s.pdf = 1;
        return true;
    }
    float pdf(const vec3f&, const vec3f&, const vec3f&) const { return 0; }
    bool meet(const vec3f&, const vec3f&, vec3f&, vec3f&) const { return false; }

    // A light path from a uniform point, leaving by its cosine from a face chosen at random:
    // Le 2 pi A / pmf.
    template <class Uniform>
    void start_path(const vec3f& emission, bool /*two_sided*/, float pmf, float /*density*/, const box3f& /*aim*/,
                    Uniform& u, ray3f& r, vec3f& throughput) const {
        const auto [u1, u2] = draw_2d(u);
        const vec3f y = centre + (u1 - 0.5f) * edge_u + (u2 - 0.5f) * edge_v;
        detail::start_area_path(y, normal, emission, true, pmf / (2.0f * area_), u, r, throughput);
    }
};

} // namespace rt
