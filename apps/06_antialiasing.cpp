// 06_antialiasing: many samples per pixel (book section 8, "Antialiasing").
//
// The scene and shading of 05_hittable_list, but each pixel now averages 100 rays, each through
// a random point of the pixel's square instead of its centre. Along an edge some of those rays
// hit the sphere and some miss, so the pixel gets a blend of the two colours and the staircase
// becomes a smooth edge. (Colours are paler than in the book's figure: our writers apply gamma 2
// to every image.)
//
// Compare the edges with 05_hittable_list, or run with --spp 1 to get exactly that image back
// (a single sample goes through the pixel centre, unjittered).
//
//   06_antialiasing > smooth.ppm
//   06_antialiasing --spp 1 -o jagged.png

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
    const app::description d{"06_antialiasing", "Renders 05's spheres with 100 jittered samples per pixel.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        hittable_list world;
        world.add(make_shared<sphere>(point3(0, 0, -1), 0.5, nullptr));
        world.add(make_shared<sphere>(point3(0, -100.5, -1), 100, nullptr));

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 100; // random points in each pixel, averaged

        opt.apply(cam);
        // The image and its statistics: on Ctrl-C, write_output says how many samples it holds.
        app::write_output(opt, rt::render(cam, world, ray_color));
    });
}
