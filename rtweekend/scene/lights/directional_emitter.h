#pragma once
// directional_emitter: a light kind (scene/light_kinds.h): light arriving from one direction at
// infinity (directional_light.h), irradiance E on a surface facing it. No ray can hit it; light
// sampling reaches it with a delta density, as a point light.
//
// Its power and its light paths need a size the light itself has not: the scene's. Seen from the
// light, the scene's bounding sphere (centre c, radius R) casts a disc of area pi R^2, and every
// ray of the light that can meet a shape crosses it: the power is E pi R^2 (pbrt-v4's
// DistantLight, Pharr, Jakob and Humphreys, 4th ed., 12.4), and a light path starts at a uniform
// point of that disc, moved out along the light's direction to the plane that touches the sphere.

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/sampling.h"
#include "../../core/vec3f.h"
#include "../light_sampling.h"

namespace rt {

struct directional_emitter {
    vec3f towards;       // unit: from the scene towards the light (the light travels along -towards)
    vec3f centre;        // of the scene's bounding sphere, relative to the scene origin
    float radius = 0;    // of that sphere (0: an empty scene, which it lights with no power)

    static constexpr bool is_delta = true;
    float area() const { return 0; }
    double area_in_double() const { return 0; }
    // The power of irradiance E (E averaged over channels; light::power): the disc the scene
    // casts, E pi R^2; in double where float overflows.
    float power(float mean) const { return pi_f * radius * radius * mean; }
    double power_in_double(double mean) const { return 3.14159265358979323846 * double(radius) * double(radius) * mean; }
    // What the emission is multiplied by at p for the sampled direction: 1, at infinity.
    float arriving(const vec3f& /*p*/, const light_sample& /*s*/) const { return 1; }

    // The direction to the light; y a point beyond the scene's bounding sphere along it, where the
    // shadow ray ends. pdf 1: the direction is certain (light_choice::delta).
    bool sample(const vec3f& p, float /*u1*/, float /*u2*/, light_sample& s) const {
        s.distance = length(p - centre) + 2.0f * radius + 1.0f;
        s.wi = towards;
        s.y = p + s.distance * towards;
        s.n = {0, 0, 0};
        s.pdf = 1;
        return true;
    }
    float pdf(const vec3f&, const vec3f&, const vec3f&) const { return 0; } // no direction finds it
    bool meet(const vec3f&, const vec3f&, vec3f&, vec3f&) const { return false; }

    // A light path along the light from a uniform point of the disc that `aim`'s bounding sphere
    // (centre a, radius r) casts, or the whole scene's when that is smaller or aim is empty, moved
    // out to the plane that touches the scene's sphere: E pi r^2 / pmf per path. Light tracing
    // aims at the shapes with delta lobes, since a path that meets none first adds nothing
    // (render/caustic_paths.h): under a sun, a glass ball on a ground 100 times its size gets all
    // the paths rather than one in 10^4.
    template <class Uniform>
    void start_path(const vec3f& emission, bool /*two_sided*/, float pmf, float /*density*/, const box3f& aim, Uniform& u,
                    ray3f& r, vec3f& throughput) const {
        vec3f a = centre;
        float ra = radius;
        if (!aim.empty()) {
            const float aim_radius = 0.5f * length(aim.hi - aim.lo);
            if (aim_radius < radius) {
                a = aim.centre();
                ra = aim_radius;
            }
        }
        const auto [u1, u2] = draw_2d(u);
        vec3f e1, e2;
        frame_across(towards, e1, e2);
        const vec3f d = sample_unit_disk(u1, u2);
        r.origin = a + ra * (d.x * e1 + d.y * e2) + (dot(centre - a, towards) + radius) * towards;
        r.dir = -towards;
        throughput = emission * (pi_f * ra * ra / pmf);
    }
};

} // namespace rt
