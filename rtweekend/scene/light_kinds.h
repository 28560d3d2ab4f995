#pragma once
// The light kinds: what a light of the compiled scene is, and the record the light set keeps of
// each (scene/light_set.h samples them). Every kind is one header of scene/lights/ that answers:
//
//   is_delta                    whether no direction can find it (a point, a direction): light
//                               sampling alone does
//   area(), area_in_double()    its area (0 for a delta light), for its power and its light paths' density
//   power(mean), power_in_double(mean), arriving(p, s)
//                               a delta light only: its power for an emission of channel mean
//                               `mean`, and the factor of its emission that reaches p along the
//                               sampled direction s (1 / d^2 for a point)
//   sample(p, u1, u2, s)        a point y seen from p: direction, distance, normal, solid-angle pdf
//                               (1 for a delta light); false when nothing can be sampled from p
//   pdf(p, y, ny)               the density sample() gives the direction from p to its point y
//   meet(p, wi, y, ny)          where the half-line p + t wi first meets it (false for a point)
//   start_path(Le, two_sided, pmf, density, aim, u, r, throughput)
//                               a light path leaving it (render/caustic_paths.h); aim: the box of
//                               what light paths are worth sending to (a directional light aims
//                               at it, the others leave as they would)
//
// and one entry in light_kinds below. Emitting shapes become lights of the kind their shape kind
// names (scene/shape_kinds.h: light_of); point and directional lights come from the scene
// description, hidden squares from the course's scenes (add_hidden_square_light).

#include "../core/kind_list.h"
#include "leaf_query.h"
#include "lights/directional_emitter.h"
#include "lights/hidden_square_emitter.h"
#include "lights/point_emitter.h"
#include "lights/quad_emitter.h"
#include "lights/sphere_emitter.h"
#include "lights/triangle_emitter.h"

#include <cmath>
#include <cstdint>
#include <type_traits>

namespace rt {

using light_kinds =
    kind_list<sphere_emitter, quad_emitter, triangle_emitter, point_emitter, directional_emitter, hidden_square_emitter>;

// One light: where it is (its kind's own record) and what it emits. Positions are relative to the
// scene origin, in float, as the shapes'.
struct light {
    kind_variant<light_kinds> emitter;
    vec3f emission;          // area lights: the radiance Le they emit; point lights: the intensity I;
                             // directional lights: the irradiance E
    bool two_sided = false;  // an area light that emits from its back face too
    // A textured emitter: its index in the compiled scene's texture table (UINT32_MAX: none, the
    // constant `emission`), with `emission` then the texture's mean, which sets the light's power;
    // and the shape it is (its kind and place in its set), for the texture coordinates of a
    // sampled point.
    uint32_t texture = UINT32_MAX;
    shape_kind shape{};
    uint32_t shape_index = 0;

    // f(the emitter's record), for whichever kind it is.
    template <class F>
    RTWEEKEND_FORCE_INLINE decltype(auto) visit(F&& f) const { return visit_value<light_kinds>(emitter, f); }

    bool is_delta() const {
        return visit([](const auto& e) { return std::decay_t<decltype(e)>::is_delta; });
    }
    float area() const {
        return visit([](const auto& e) { return e.area(); });
    }
    // The power the light emits, averaged over channels (up to a common factor): Le A pi for a
    // one-sided area light (twice that two-sided), 4 pi I for a point light, E pi R^2 for a
    // directional light over a scene of bounding radius R. In double where float
    // overflows (a radiance of 1e37 over a few square units), so that every finite light has a
    // finite weight.
    double power() const;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline double light::power() const {
    const float mean = (emission.x + emission.y + emission.z) * (1.0f / 3.0f);
    const float p = visit([&](const auto& e) {
        if constexpr (std::decay_t<decltype(e)>::is_delta) return e.power(mean);
        else return mean * e.area() * pi_f * (two_sided ? 2.0f : 1.0f);
    });
    if (std::isfinite(p)) return p; // float, as always: the same weights, the same images
    // Beyond float's range: the same product in double (a NaN stays NaN, and is refused).
    const double pi_d = 3.14159265358979323846;
    const double mean_d = (double(emission.x) + double(emission.y) + double(emission.z)) / 3.0;
    return visit([&](const auto& e) {
        if constexpr (std::decay_t<decltype(e)>::is_delta) return e.power_in_double(mean_d);
        else return mean_d * e.area_in_double() * pi_d * (two_sided ? 2.0 : 1.0);
    });
}

} // namespace rt
