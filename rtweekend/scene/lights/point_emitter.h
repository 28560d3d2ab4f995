#pragma once
// point_emitter: a light kind (scene/light_kinds.h): a light of no size (point_light.h), intensity
// I in every direction. No ray can hit it; light sampling reaches it with a delta density.

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"

#include <cmath>

namespace rt {

struct point_emitter {
    vec3f position; // relative to the scene origin
    // A spot light's cone (point_light.h): the unit axis (zero: no cone), the cosines of the outer
    // half-angle and 1 / (cos inner - cos outer).
    vec3f axis{0, 0, 0};
    float cos_outer = -1, inv_cone_width = 0;
    float exponent = 2; // of the fall-off between the cones

    // The share of the intensity sent along the unit direction d (from the light): 1 without a
    // cone; a^exponent with a = clamp((d . axis - cos outer) / (cos inner - cos outer), 0, 1)
    // with one.
    float falloff(const vec3f& d) const {
        if (axis.x == 0 && axis.y == 0 && axis.z == 0) return 1;
        const float a = fmin_inline(fmax_inline((dot(d, axis) - cos_outer) * inv_cone_width, 0.0f), 1.0f);
        if (exponent == 2) return a * a;
        if (exponent == 4) return (a * a) * (a * a);
        return std::pow(a, exponent);
    }
    // The fraction of the sphere the light shines into (for its power): the outer cone's.
    float solid_angle_share() const {
        if (axis.x == 0 && axis.y == 0 && axis.z == 0) return 1;
        return 0.5f * (1.0f - cos_outer);
    }

    static constexpr bool is_delta = true;
    float area() const { return 0; }
    double area_in_double() const { return 0; }
    // The power of intensity I (I averaged over channels; light::power): 4 pi I over the sphere,
    // the cone's share of it for a spot; in double where float overflows.
    float power(float mean) const { return 4.0f * pi_f * mean * solid_angle_share(); }
    double power_in_double(double mean) const { return 4.0 * 3.14159265358979323846 * mean * double(solid_angle_share()); }
    // What the intensity is multiplied by at p for the sampled point (s.y, the light): the cone's
    // fall-off over the squared distance, I a^2 / d^2.
    float arriving(const vec3f& p, const light_sample& s) const { return falloff(-s.wi) / length_squared(s.y - p); }

    // The direction to the point; the light set weighs its intensity by 1 / d^2. pdf 1: the
    // direction is certain (light_choice::delta).
    bool sample(const vec3f& p, float /*u1*/, float /*u2*/, light_sample& s) const {
        const vec3f to = position - p;
        const float d2 = length_squared(to);
        if (!(d2 > 0)) return false;
        s.distance = sqrt_f(d2);
        s.wi = to / s.distance;
        s.y = position;
        s.n = {0, 0, 0};
        s.pdf = 1;
        return true;
    }
    float pdf(const vec3f&, const vec3f&, const vec3f&) const { return 0; } // no direction finds it
    bool meet(const vec3f&, const vec3f&, vec3f&, vec3f&) const { return false; }

    // A light path from the point, in a uniform direction (u's first pair): intensity I over the
    // whole sphere, I 4 pi / pmf per path.
    template <class Uniform>
    void start_path(const vec3f& emission, bool /*two_sided*/, float pmf, float /*density*/, const box3f& /*aim*/, Uniform& u,
                    ray3f& r, vec3f& throughput) const {
        const auto [u1, u2] = draw_2d(u);
        r.origin = position;
        r.dir = sample_unit_sphere(u1, u2);
        throughput = emission * (4.0f * pi_f * falloff(r.dir) / pmf);
    }
};

} // namespace rt
