// A book-1 style main that includes camera.h and the scene's own headers, and neither rtweekend.h
// nor any engine header: camera.h alone must bring in everything cam.render(world) needs. Built
// with only rtweekend/ on the include path.

#include "camera.h"
#include "hittable_list.h"
#include "material.h"
#include "sphere.h"

#include <memory>

int main() {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, -100.5, -1), 100, std::make_shared<lambertian>(color(0.8, 0.8, 0))));
    world.add(std::make_shared<sphere>(point3(0, 0, -1.2), 0.5, std::make_shared<metal>(color(0.8, 0.6, 0.2), 0.3)));

    camera cam;
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 32;
    cam.samples_per_pixel = 4;
    cam.max_depth = 8;
    cam.render(world);
}
