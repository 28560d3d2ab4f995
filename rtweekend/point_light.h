#pragma once
// point_light: a light of no size at `position`, emitting intensity I (power per unit solid
// angle) equally in every direction: a surface at distance d whose normal makes the angle theta
// with the direction to the light receives irradiance E = I cos(theta) / d^2. The course scenes'
// lights (whitted_scene.h); the path tracer samples them too (scene/light_set.h). No ray can hit
// one, so only light sampling finds it.
//
// A spot light (glTF's KHR_lights_punctual spot) is one with a cone: given a `spot_direction`
// (any length; zero: none, the light shines every way), intensity falls off from the inner cone
// to the outer (half-angles in radians) as glTF's lights do, I a^2 with
//   a = clamp((cos theta - cos outer) / (cos inner - cos outer), 0, 1)
// and theta the angle from the direction; nothing past the outer cone. `cone_exponent` is that
// power, 2 as glTF's; CENG795's spot lights fall off as a^4 (course/course_lights.h), which
// `render --integrator path` gives them. The path tracer takes spot lights; the course's Whitted
// scenes have their own (course/course_lights.h).

#include "color.h"
#include "vec3.h"

namespace rt {

struct point_light {
    point3 position;
    color intensity;
    vec3 spot_direction{0, 0, 0};
    double inner_cone = 0, outer_cone = 0; // radians, 0 <= inner <= outer <= pi
    double cone_exponent = 2;              // the fall-off a^cone_exponent between the cones, at least 1
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::point_light;
#endif
