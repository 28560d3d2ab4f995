// 08_metal: materials, and metal in particular (book section 10, "Metal").
//
// Each sphere now carries its own material, which decides how a ray scatters off it:
//   ground  lambertian, yellow-green (0.8, 0.8, 0.0)
//   centre  lambertian, blue (0.1, 0.2, 0.5), a little further back at z = -1.2
//   left    metal, silver (0.8, 0.8, 0.8), fuzz 0.3
//   right   metal, gold (0.8, 0.6, 0.2), fuzz 1.0
// A metal reflects a ray like a mirror, then moves the reflected direction by a random offset
// of length up to `fuzz`: fuzz 0 is a perfect mirror, 0.3 a slightly blurred one and 1.0 a
// brushed, almost matte reflection. Directions pushed below the surface are absorbed.
// This is the fuzzed scene of section 10.6; set both fuzz values to 0 for section 10.5's mirrors.
//
//   08_metal > metal.ppm
//   08_metal -o metal.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"08_metal", "Path traces two diffuse spheres and two fuzzy metal ones.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        auto material_ground = make_shared<lambertian>(color(0.8, 0.8, 0.0));
        auto material_center = make_shared<lambertian>(color(0.1, 0.2, 0.5));
        auto material_left = make_shared<metal>(color(0.8, 0.8, 0.8), 0.3);
        auto material_right = make_shared<metal>(color(0.8, 0.6, 0.2), 1.0);

        hittable_list world;
        world.add(make_shared<sphere>(point3(0.0, -100.5, -1.0), 100.0, material_ground));
        world.add(make_shared<sphere>(point3(0.0, 0.0, -1.2), 0.5, material_center));
        world.add(make_shared<sphere>(point3(-1.0, 0.0, -1.0), 0.5, material_left));
        world.add(make_shared<sphere>(point3(1.0, 0.0, -1.0), 0.5, material_right));

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 100;
        cam.max_depth = 50;

        opt.apply(cam);
        rt::render_result result = rt::render(cam, world); // the path tracer
        app::write_output(opt, result);
    });
}
