#pragma once
// point_light: a light of no size at `position`, emitting intensity I (power per unit solid
// angle) equally in every direction: a surface at distance d whose normal makes the angle theta
// with the direction to the light receives irradiance E = I cos(theta) / d^2. The course scenes'
// lights (whitted_scene.h); the path tracer samples them too (scene/light_set.h). No ray can hit
// one, so only light sampling finds it.

#include "color.h"
#include "vec3.h"

namespace rt {

struct point_light {
    point3 position;
    color intensity;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::point_light;
#endif
