#pragma once
// Settings that keep one fuzzer execution's render to a few milliseconds, applied after a scene is
// loaded and checked: at most 8x8 pixels, 2 samples per pixel and 4 rays per path on one thread,
// quiet; an XML scene's cameras at most 4x4 pixels and 3 bounces. Only values that are valid
// and larger are lowered, so invalid ones still reach the checks that refuse them.

#include <rtweekend/camera.h>
#include <rtweekend/course/whitted_scene.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace fuzz {

inline void shrink(rt::camera& cam) {
    cam.image_width = std::min(cam.image_width, 8);
    if (cam.image_height > 8) cam.image_height = 8;
    else if (cam.image_height == 0 && cam.image_width >= 1 && std::isfinite(cam.aspect_ratio) && cam.aspect_ratio > 0 &&
             cam.image_width / cam.aspect_ratio > 8)
        cam.image_height = 8;
    cam.samples_per_pixel = std::min(cam.samples_per_pixel, 2);
    cam.settings.adaptive_min_samples = std::min(cam.settings.adaptive_min_samples, 2);
    cam.max_depth = std::min(cam.max_depth, 4);
    cam.settings.threads = 1;
    cam.settings.quiet = true;
    cam.settings.stop = nullptr;
}

// A model's world rendered tiny (shrink), seen from (0, 0, 4) towards the origin under a white sky,
// with its point lights: what the model harnesses (mtl, gltf) do with an accepted input.
inline void render_model(rt::hittable_list&& objects, const std::vector<rt::point_light>& lights = {}) {
    rt::camera cam;
    cam.lookfrom = rt::point3(0, 0, 4);
    cam.lookat = rt::point3(0, 0, 0);
    cam.background = rt::color(1, 1, 1);
    shrink(cam);
    rt::hittable_list world;
    world.add(std::make_shared<rt::hittable_list>(std::move(objects)));
    rt::render(cam, world, lights);
}

inline void shrink(rt::whitted_scene& scene) {
    for (rt::view_camera& c : scene.cameras) {
        c.width = std::min(c.width, 4);
        c.height = std::min(c.height, 4);
        c.samples = std::min(c.samples, 4); // NumSamples may ask for 2^24
    }
    scene.max_recursion_depth = std::min(scene.max_recursion_depth, 3);
}

} // namespace fuzz
