// 05_hittable_list: more than one object (book section 6, "A List of Hittable Objects").
//
// The world is now a hittable_list holding two spheres: the small one from 04_normals and a huge
// one of radius 100 just below it, whose top acts as the ground. The list reports the closest
// hit along each ray, so the small sphere correctly hides the ground behind it. Both are shaded
// by their normals: the ground, whose normal points almost straight up, comes out green.
// (Colours are paler than in the book's figure: our writers apply gamma 2 to every image.)
//
// Edges are jagged (one ray per pixel); 06_antialiasing fixes that.
//
//   05_hittable_list > world.ppm
//   05_hittable_list -o world.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

color ray_color(const ray& r, const hittable& world) {
    hit_record rec;
    if (world.hit(r, interval(0, infinity), rec)) return 0.5 * (rec.normal + color(1, 1, 1));

    vec3 unit_direction = unit_vector(r.direction());
    auto a = 0.5 * (unit_direction.y() + 1.0);
    return (1.0 - a) * color(1.0, 1.0, 1.0) + a * color(0.5, 0.7, 1.0);
}

int main(int argc, char** argv) {
    const app::description d{"05_hittable_list", "Renders two spheres (one is the ground) from a hittable_list.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        hittable_list world;
        world.add(make_shared<sphere>(point3(0, 0, -1), 0.5, nullptr));
        world.add(make_shared<sphere>(point3(0, -100.5, -1), 100, nullptr)); // the ground

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 1;

        opt.apply(cam);
        // The image and its statistics: on Ctrl-C, write_output says how many samples it holds.
        app::write_output(opt, rt::render(cam, world, ray_color));
    });
}
