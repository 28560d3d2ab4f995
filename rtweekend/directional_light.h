#pragma once
// directional_light: light from one direction at infinity (the sun, glTF's KHR_lights_punctual
// "directional", CENG795's <DirectionalLight>). A surface whose normal makes the angle theta with
// the direction towards the light receives irradiance E cos(theta) at any distance, wherever it
// is not in shadow; `irradiance` is E, the irradiance on a surface facing the light (lux, for
// glTF; the course's <Radiance> element). No ray can hit one, so only light sampling finds it.
//
//   std::vector<directional_light> sun{{vec3(-1, -2, -1), color(3, 3, 3)}};
//   rt::render(cam, world, {}, sun);
//
// The path tracer (scene/lights/directional_emitter.h) takes them beside point lights; the
// course's Whitted scenes shade them (course/whitted.h).

#include "color.h"
#include "vec3.h"

namespace rt {

struct directional_light {
    vec3 direction; // the way the light travels (any length but zero)
    color irradiance;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::directional_light;
#endif
